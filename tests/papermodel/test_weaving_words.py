"""What the weaving page says about the pattern's directions matches the pattern."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from weavecut import inputs
from weavecut.papermodel import assembly
from weavecut.papermodel.modules import plan_modules
from weavecut.subdivision import subdivide
from weavecut.weave.snub_weave import snub_weaves


@pytest.mark.parametrize("spec", ["ngon:5", "ngon:6", "ngon:8", "ngon:12"])
def test_right_angles_are_denied_only_where_no_two_directions_meet_at_one(spec):
    """A k-fold pattern's strand directions are turned by multiples of 360/k degrees; the text
    says "no right angles" exactly when no such turn is 90 degrees (modulo a half turn)."""
    weave = snub_weaves(subdivide(inputs.get(spec), 2))[-1]
    plan = plan_modules(weave)
    book = SimpleNamespace(plan=plan, pieces=(), extra_pages=(1, 2), callout_pages=())
    steps, _ = assembly.weaving_steps(weave, book, 0.0)
    text = " ".join(steps)
    turns = [(i * 360 / plan.k) % 180 for i in range(plan.k)]
    right = any(abs(t - 90) < 1e-9 for t in turns)
    assert f"{plan.k} directions" in text
    assert ("no right angles" in text) is not right, (plan.k, text[:300])
