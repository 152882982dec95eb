"""Draw the web app's pictures into ``src/weavecut/web/static/``: a picture per product of the
start page (``products/NAME.webp``, 480 x 360, from weave-cut's own previews, a laser card
sheet drawn by librsvg's ``rsvg-convert``, and the README's images) and the logo (``logo.svg``: the pentagon after one snub step, in the paper model's
colours). Run after a change that redraws them: ``python tools/web_pictures.py [NAME ...]``
(the names of the pictures to draw again; none: all and the logo).
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

from PIL import Image

ROOT = Path(__file__).resolve().parents[1]
STATIC = ROOT / "src" / "weavecut" / "web" / "static"
SIZE = (480, 360)
BACKGROUND = (255, 255, 255)

# picture -> weave-cut arguments making a PNG ({out}) or a file of the repository
PRODUCTS = {
    "paper-model": ("strands", "square-grid", "--preview", "-o", "{out}"),
    "pentagon-flower": ("strands", "pentagon-flower", "--preview", "-o", "{out}"),
    "woven-ball": ("strands", "dodecahedron", "--levels", "1", "--project", "sphere", "--size",
                   "12cm", "--preview", "-o", "{out}"),  # the kit's own view: the front
    "cut-by-machine": ("strands", "square-grid", "--size", "27cm", "--laser-card", "--palette",
                       "maritime-4", "-o", "{out}.card"),
    "jigsaw-puzzle": "docs/puzzle-front.png",
    "your-drawing": "examples/previews/heart-puzzle-front.png",
    "weave": ("weave", "pentagon", "--levels", "3", "--outline-level", "2", "-o", "{out}"),
    "subdivide": "docs/pentagon-level4.png",
    "figures": "docs/level-image.png",
}
CROPS = {"woven-ball": (0.0, 0.0, 0.5, 0.9), "cut-by-machine": (0.0, 0.0, 1.0, 0.56)}


def picture(name: str, source, tmp: Path) -> Image.Image:
    if isinstance(source, str):
        image = Image.open(ROOT / source)
    else:
        out = tmp / f"{name}.png"
        subprocess.run([sys.executable, "-m", "weavecut", *(a.replace("{out}", str(out))
                                                            for a in source)],
                       check=True, cwd=ROOT, capture_output=True)
        if source[-1].endswith(".card"):  # the first laser-cut card sheet, drawn by librsvg
            sheet = sorted(Path(f"{out}.card").glob("*.svg"))[0]
            subprocess.run(["rsvg-convert", "-w", "900", "-b", "white", str(sheet), "-o",
                            str(out)], check=True)
        image = Image.open(out)
    image = image.convert("RGBA")
    if name in CROPS:
        x0, y0, x1, y1 = CROPS[name]
        w, h = image.size
        image = image.crop((int(x0 * w), int(y0 * h), int(x1 * w), int(y1 * h)))
    image.thumbnail((SIZE[0] - 24, SIZE[1] - 24), Image.LANCZOS)
    card = Image.new("RGB", SIZE, BACKGROUND)
    card.paste(image, ((SIZE[0] - image.width) // 2, (SIZE[1] - image.height) // 2), image)
    return card


def logo() -> str:
    """The pentagon's first snub level, each pentagon in a maritime-12 colour."""
    from weavecut import inputs
    from weavecut.subdivision import subdivide

    mesh = subdivide(inputs.get("pentagon"), 1)[-1].mesh
    colours = ["#0b3c5d", "#0f7173", "#c9a227", "#c05640", "#5b8db8"]
    v = mesh.vertices * 15 + 16
    polys = "".join(
        f'<polygon points="{" ".join(f"{x:.2f},{32 - y:.2f}" for x, y in v[face])}" '
        f'fill="{colours[k % 5]}"/>' for k, face in enumerate(mesh.faces()))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 32 32" '
            f'stroke="#fff" stroke-width="0.8" stroke-linejoin="round">{polys}</svg>\n')


def save(image: Image.Image, path) -> None:
    image.save(path, "WEBP", quality=82, method=6)


def main(names: list[str]) -> None:
    """Draw the pictures ``names`` (all, and the logo, for none)."""
    (STATIC / "products").mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        for name in names or PRODUCTS:
            save(picture(name, PRODUCTS[name], Path(tmp)), STATIC / "products" / f"{name}.webp")
    if not names:
        (STATIC / "logo.svg").write_text(logo())


if __name__ == "__main__":
    main(sys.argv[1:])
