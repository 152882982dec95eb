"""Which packages the distribution holds (everything else is in pyproject.toml).

The code is in ``src/``; the presets stay in ``templates/`` at the top of the checkout, where
users look for them, and install as the package ``weavecut.templates`` (its TOML files are
package data, read with ``importlib.resources``); the example recipes and their drawings in
``examples/`` install as ``weavecut.examples``, so ``build star-paper-model`` works anywhere;
the web app's style sheet, script and pictures (``weavecut/web/static/``) and the kit page's
3-D viewer (``weavecut/kitpage/static/``: three.js and its licence) are package data too. Folders are found, not listed (data folders such as ``static/`` as namespace packages,
which setuptools asks for), so a new subpackage or preset kind ships without touching this file.
"""

from setuptools import find_namespace_packages, setup

TEMPLATES = ["weavecut.templates",
             *(f"weavecut.templates.{kind}" for kind in find_namespace_packages("templates"))]

setup(packages=find_namespace_packages("src", exclude=["*.__pycache__"]) + TEMPLATES + ["weavecut.examples"],
      package_dir={"": "src", "weavecut.templates": "templates", "weavecut.examples": "examples"},
      package_data={"weavecut.templates": ["*/*.toml", "recipes/*.svg"],
                    "weavecut.examples": ["*.toml", "*.svg", "*.dxf", "*.obj", "*.json"],
                    "weavecut.web": ["static/*.*", "static/products/*.webp"],
                    "weavecut.kitpage": ["static/*.js", "static/*.LICENSE"]})
