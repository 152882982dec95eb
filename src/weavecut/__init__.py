"""weave-cut: the pentagon snub subdivision scheme, its weaves, paper models and jigsaw puzzles."""

from __future__ import annotations

__version__ = "0.1.0"
