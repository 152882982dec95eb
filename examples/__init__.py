"""weave-cut's example recipes and the drawings and meshes they read. This folder installs as
the package ``weavecut.examples`` (see setup.py); ``weavecut.presets`` finds its recipes by
name beside those of ``templates/recipes``."""
