"""The boundary curve of the snub scheme as a Lindenmayer system (paper section 4).

Every edge of level t is replaced by a Z-triplet in each later step, so it becomes a curve of
3^(t'-t) edges at level t'. On the boundary nothing is smoothed and the curve is exactly the
Lindenmayer system ``F -> vF-F+F^`` (v: turn by +alpha, ^: by -alpha, +/-: by +-60 degrees),
with edges 1/sqrt(7) as long each step, so the limit has dimension log 3 / log sqrt 7. Here:
alpha, the rule, its words and its curve.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

ALPHA = math.atan(math.sqrt(3.0) / 5.0)
"""Angle between an edge and the first edge of its Z-triplet: atan(sqrt 3 / 5), 19.1066 deg."""
SCALE = 1.0 / math.sqrt(7.0)
"""Length of a Z edge relative to the edge it replaces."""
DIMENSION = math.log(3.0) / math.log(math.sqrt(7.0))
"""Similarity dimension of the boundary curve, log 3 / log sqrt 7 = 1.12915..."""

AXIOM, RULE = "F", "vF-F+F^"
TURNS = {"v": ALPHA, "^": -ALPHA, "+": math.pi / 3, "-": -math.pi / 3}


def alpha_from_z_triplet() -> float:
    """Alpha derived from the Z-triplet: three equal edges, 120 degrees between consecutive ones.

    The Z u-x-y-w with |ux| = |xy| = |yw| = s and point symmetry about the midpoint has
    x = (a, b), y = (1 - a, -b) for the unit edge, with |x| = s and the angle u-x-y 120
    degrees: solving gives x = (5 + i sqrt 3) / 14, so alpha = atan2(sqrt 3, 5).

    Examples
    --------
    >>> round(math.degrees(alpha_from_z_triplet()), 4)
    19.1066
    """
    x = complex(5.0, math.sqrt(3.0)) / 14.0
    y = 1.0 - x
    s = abs(x)
    inner = (x - 0) / (x - y)  # direction x->u against x->y
    angle = abs(math.atan2(inner.imag, inner.real))
    assert abs(abs(y - x) - s) < 1e-15 and abs(angle - 2 * math.pi / 3) < 1e-12
    return math.atan2(x.imag, x.real)


def lsystem_string(levels: int) -> str:
    """The L-system word after ``levels`` rewritings of the axiom F.

    Examples
    --------
    >>> lsystem_string(1)
    'vF-F+F^'
    """
    word = AXIOM
    for _ in range(levels):
        word = word.replace("F", RULE)
    return word


def lsystem_curve(levels: int, start=(0.0, 0.0), end=(1.0, 0.0),
                  chirality: str = "left") -> NDArray[np.float64]:
    """(3**levels + 1, 2) points of the L-system curve from ``start`` to ``end``.

    The turtle is vectorised: turns become a cumulative heading, F steps a cumulative sum.
    ``chirality="right"`` mirrors every turn (the snub step's other chirality).
    """
    word = np.frombuffer(lsystem_string(levels).encode("ascii"), dtype=np.uint8)
    sign = -1.0 if chirality == "right" else 1.0
    turn = np.zeros(len(word))
    for symbol, angle in TURNS.items():
        turn[word == ord(symbol)] = sign * angle
    heading = np.cumsum(turn)[word == ord("F")]
    start = complex(*start)
    chord = complex(*end) - start
    steps = np.exp(1j * heading) * (chord * SCALE**levels)
    points = np.concatenate([[start], start + np.cumsum(steps)])
    return np.column_stack([points.real, points.imag])
