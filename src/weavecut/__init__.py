"""weave-cut: the pentagon snub subdivision scheme, its weaves, paper models and jigsaw puzzles."""

__version__ = "0.1.0"
