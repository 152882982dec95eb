"""Layouts: everything that turns meshes and weaves into Drawings (figures, paper strands, puzzle)."""
