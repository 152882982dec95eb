"""weave-cut's presets. This folder installs as the package ``weavecut.templates`` (see
setup.py); ``weavecut.presets`` reads its TOML files with ``importlib.resources``."""
