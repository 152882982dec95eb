"""One error tree for everything weave-cut refuses to do."""

from __future__ import annotations


class WeaveCutError(Exception):
    """Base of every error weave-cut raises on purpose; the CLI prints it as one line."""


class MeshError(WeaveCutError, ValueError):
    """The mesh data is invalid (indices, degenerate or clockwise faces, overlaps, ...)."""


class NonManifoldError(MeshError):
    """An edge has more than two faces, or two faces on the same side."""


class MeshFileError(MeshError):
    """A mesh file cannot be parsed."""


class TooLargeError(WeaveCutError):
    """The requested work would not fit in memory."""


class ExportError(WeaveCutError, OSError):
    """An output cannot be written."""


class TurnedOverError(WeaveCutError):
    """Faces of a subdivided level cross themselves (sharp corners, slim faces)."""
