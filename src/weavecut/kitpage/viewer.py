"""The kit page's 3-D viewer: a ``.glb`` a command wrote shown as a model a person can turn.

The model is embedded in the page (base64), and the viewer's scripts are inlined once per page:
three.js (vendored from the npm registry, ``static/three.min.js``, see ``tools/three/``) and
``static/viewer.js``. So the page needs no file beside it and no other host, and works from
``file://`` (where a browser refuses to fetch files and ES module imports) as from a server.
"""

from __future__ import annotations

import base64
from html import escape
from importlib import resources
from pathlib import Path

MARK = '<figure class="model3d"'
MAX_EMBEDDED = 16 * 2**20  # bytes of a .glb shown in the page; a larger one is only linked
STATIC = Path(__file__).resolve().parent / "static"  # three.min.js, viewer.js (the app serves them)
HINT = "Drag to turn, scroll or pinch to zoom, right-drag to move."


def static(name: str) -> str:
    """The text of a file of the package's ``kitpage/static/``."""
    return resources.files(__package__).joinpath("static", name).read_text(encoding="utf-8")


def figure(path: Path, href: str) -> str:
    """The viewer of the glTF binary at ``path`` (linked as ``href``), "" when it is missing,
    not glTF binary, or too large to embed."""
    try:
        size = path.stat().st_size
        if size > MAX_EMBEDDED:
            return ""
        data = path.read_bytes()
    except OSError:
        return ""
    if data[:4] != b"glTF":
        return ""
    label = escape(f"{path.name}: the finished model in 3-D")
    return (f'{MARK} data-state="loading"><canvas role="img" aria-label="{label}"></canvas>'
            f'<figcaption>{escape(HINT)} <button type="button">Reset view</button> '
            f'<a href="{href}">GLB</a></figcaption><script type="model/gltf-binary">'
            f"{base64.b64encode(data).decode('ascii')}</script></figure>")


def scripts(body: str) -> str:
    """The viewer's scripts when ``body`` has a viewer, else ""."""
    if MARK not in body:
        return ""
    # "</script" cannot occur in the minified code, but make sure: it would end the element
    code = [static(n).replace("</script", "<\\/script") for n in ("three.min.js", "viewer.js")]
    return "".join(f"<script>{c}</script>" for c in code)
