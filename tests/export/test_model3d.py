"""3-D model writers read back by programs other than weave-cut: OBJ and glTF by trimesh (and
the OBJ's text by the format's own rules), PNG views by Pillow, probed where geometry worked
out by hand puts each triangle: the view from above shows the upper of two stacked squares,
from below the lower one, each at its place, size and shade."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from weavecut.errors import ExportError
from weavecut.export import model3d

from tests.export.test_png_details import lanczos_halved

trimesh = pytest.importorskip("trimesh")

TEAL, SAND = (0x12, 0x7A, 0x7A), (0xE0, 0xC0, 0x80)


def square(z: float, half: float = 1.0, x: float = 0.0):
    """A square in the plane at height z, centred at (x, 0), facing up (counter-clockwise
    seen from above)."""
    v = np.array([[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]])
    return v + [x, 0, 0], np.array([[0, 1, 2], [0, 2, 3]])


def model(*parts):
    """(vertices, triangles, colours) of (square, colour) parts."""
    vertices, triangles, colours, n = [], [], [], 0
    for (v, t), colour in parts:
        vertices.append(v)
        triangles.append(t + n)
        colours.append(np.tile(np.array(colour, dtype=np.uint8), (len(v), 1)))
        n += len(v)
    return np.concatenate(vertices), np.concatenate(triangles), np.concatenate(colours)


def test_two_sided_adds_every_triangle_turned_on_its_own_vertices():
    v, t, c = model((square(0.0), TEAL))
    v2, t2, c2 = model3d.two_sided(v, t, c)
    np.testing.assert_array_equal(v2, np.concatenate([v, v]))
    np.testing.assert_array_equal(c2, np.concatenate([c, c]))
    np.testing.assert_array_equal(t2[:2], t)
    # the copies use the second set of vertices and face down (their normals point to -z)
    assert (t2[2:] >= len(v)).all()
    corners = v2[t2]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert (normals[:2, 2] > 0).all() and (normals[2:, 2] < 0).all()
    assert {frozenset(tri) for tri in (t2[2:] - len(v)).tolist()} == \
        {frozenset(tri) for tri in t.tolist()}


def test_obj_reads_back_with_its_colours_and_both_sides():
    v, t, c = model((square(0.25, 0.5), TEAL), (square(-1.5, 2.0, x=3.0), SAND))
    data = model3d.obj_bytes(v, t, c, comments=["a ball", "two\nlines"])
    lines = data.decode().splitlines()
    assert lines[:2] == ["# a ball", "# two lines"]  # a newline cannot open a data line
    vs = [line.split()[1:] for line in lines if line.startswith("v ")]
    fs = [line.split()[1:] for line in lines if line.startswith("f ")]
    assert len(vs) == 2 * len(v) and len(fs) == 2 * len(t)
    xyz = np.array([[float(x) for x in row[:3]] for row in vs])
    rgb = np.array([[float(x) for x in row[3:]] for row in vs])
    np.testing.assert_array_equal(xyz, np.concatenate([v, v]))  # exact (repr), not rounded
    np.testing.assert_allclose(rgb * 255, np.concatenate([c, c]), atol=0.02)
    faces = np.array(fs, dtype=int)
    assert faces.min() == 1 and faces.max() == 2 * len(v)  # OBJ counts vertices from 1

    mesh = trimesh.load(io.BytesIO(data), file_type="obj", force="mesh", process=False)
    assert len(mesh.faces) == 2 * len(t)
    np.testing.assert_allclose(mesh.vertices, np.concatenate([v, v]))
    got = {tuple(x) for x in np.asarray(mesh.visual.vertex_colors)[:, :3].tolist()}
    assert got == {TEAL, SAND}
    # half the faces look up, half down: two-sided, and the second copy is the first turned
    assert np.isclose(mesh.face_normals[:, 2], 1).sum() == len(t)
    assert np.isclose(mesh.face_normals[:, 2], -1).sum() == len(t)


def rotation_oracle(azimuth, elevation):
    """World to view from first principles: the camera turns about z by ``azimuth`` and
    rises by ``elevation``; view x right, y up, z towards the viewer."""
    a, e = np.radians(azimuth), np.radians(elevation)
    # direction from the model to the camera, and the camera's right-hand and up axes
    towards = np.array([np.sin(a) * np.cos(e), -np.cos(a) * np.cos(e), np.sin(e)])
    right = np.array([np.cos(a), np.sin(a), 0.0])
    up = np.cross(towards, right)
    return np.array([right, up, towards])


@pytest.mark.parametrize("view", [(0, 0), (20, 25), (110, 25), (200, 25), (290, -60),
                                  (0, 90), (45, -90)])
def test_view_rotation_is_the_camera_turned_and_raised(view):
    r = model3d._rotation(*view)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(r) == pytest.approx(1.0)
    np.testing.assert_allclose(r, rotation_oracle(*view), atol=1e-12)


SIZE = 64


def views(data, n, size=SIZE):
    """The PNG's n views as (size, size, 3) arrays, left to right, top to bottom."""
    with Image.open(io.BytesIO(data)) as im:
        img = np.asarray(im.convert("RGB"))
    assert img.shape == (-(-n // 2) * size, 2 * size, 3)
    return [img[(k // 2) * size:(k // 2 + 1) * size, (k % 2) * size:(k % 2 + 1) * size]
            for k in range(n)]


def drawn(img) -> np.ndarray:
    """Where a view is drawn: well off white (the resampling filter rings faintly)."""
    return (255 - img.astype(int)).max(axis=2) > 40


def lit(colour, normal_towards_viewer):
    """Flat shading as the writer's docstring says: 35 % ambient and 65 % from a light at
    LIGHT, either side lit."""
    light = model3d.LIGHT / np.linalg.norm(model3d.LIGHT)
    return np.array(colour) * (0.35 + 0.65 * abs(np.dot(normal_towards_viewer, light)))


def test_png_views_show_the_nearest_square_in_place_and_shade():
    # teal above sand; seen from above (elevation 90) teal covers sand, from below sand
    # covers teal, each seen face-on; a view from the side (elevation 0) sees both edge-on
    parts = model((square(0.5), TEAL), (square(-0.5), SAND))
    top, bottom, side = views(model3d.png_bytes(*parts, size=SIZE,
                                                views=((0, 90), (0, -90), (0, 0))), 3)
    for img, colour in [(top, TEAL), (bottom, SAND)]:
        centre = img[SIZE // 2 - 4:SIZE // 2 + 4, SIZE // 2 - 4:SIZE // 2 + 4].reshape(-1, 3)
        np.testing.assert_allclose(centre, np.tile(lit(colour, [0, 0, 1]), (64, 1)), atol=1.5)
        # centred, the radius (corner of a square) at 0.47 of the view: the square spans
        # 0.47 SIZE / sqrt(3) either side (radius sqrt(1 + 1 + 0.5^2) = 1.5)
        covered = np.argwhere(drawn(img))
        half = 0.47 * SIZE / 1.5
        for lo, hi in zip(covered.min(axis=0), covered.max(axis=0)):
            assert lo == pytest.approx(SIZE / 2 - half, abs=1.5)
            assert hi + 1 == pytest.approx(SIZE / 2 + half, abs=1.5)
    # edge-on, the two squares are two thin lines, 1 unit apart: most of the view is white
    assert drawn(side).mean() < 0.1


def test_png_view_up_is_up_and_right_is_right():
    # seen from above with azimuth 0 the camera's up is world +y and its right world +x;
    # a teal square at +x, a sand one at -x
    parts = model((square(0.0, 0.5, x=1.0), TEAL), (square(0.0, 0.5, x=-1.0), SAND))
    (img,) = views(model3d.png_bytes(*parts, size=SIZE, views=((0, 90),)), 1)[:1]
    right, left = img[SIZE // 2, 3 * SIZE // 4], img[SIZE // 2, SIZE // 4]
    assert np.abs(right - lit(TEAL, [0, 0, 1])).max() < 2
    assert np.abs(left - lit(SAND, [0, 0, 1])).max() < 2
    # a triangle pointing to +y (world) points up in the picture
    tri = (np.array([[-1.0, -1, 0], [1, -1, 0], [0, 1, 0]]), np.array([[0, 1, 2]]))
    (img,) = views(model3d.png_bytes(*model((tri, TEAL)), size=SIZE, views=((0, 90),)), 1)
    widths = drawn(img).sum(axis=1)
    rows = np.flatnonzero(widths)
    assert widths[rows[0] + 2] < widths[rows[-1] - 2]  # narrow at the top, wide at the bottom


def test_png_depth_holds_across_chunks(monkeypatch):
    # a chunk per triangle pair: the lower square drawn after the upper one must not win
    monkeypatch.setattr(model3d, "PAIRS_PER_CHUNK", 500)
    parts = model((square(0.5), TEAL), (square(-0.5), SAND))
    top, bottom = views(model3d.png_bytes(*parts, size=SIZE, views=((0, 90), (0, -90))), 2)
    assert np.abs(top[SIZE // 2, SIZE // 2] - lit(TEAL, [0, 0, 1])).max() < 2
    assert np.abs(bottom[SIZE // 2, SIZE // 2] - lit(SAND, [0, 0, 1])).max() < 2


def test_png_default_views_two_per_row():
    parts = model((square(0.5), TEAL), (square(-0.5), SAND))
    with Image.open(io.BytesIO(model3d.png_bytes(*parts, size=SIZE))) as im:
        assert im.size == (2 * SIZE, 2 * SIZE)  # four views, two rows of two
        img = np.asarray(im.convert("RGB"))
    for k in range(4):  # something drawn in each
        view = img[(k // 2) * SIZE:(k // 2 + 1) * SIZE, (k % 2) * SIZE:(k % 2 + 1) * SIZE]
        assert drawn(view).mean() > 0.05


@pytest.mark.parametrize("size", [15, 4097])
def test_png_size_out_of_range_is_refused(size):
    parts = model((square(0.0), TEAL))
    with pytest.raises(ExportError, match=f"16 to 4096 pixels wide, got {size}"):
        model3d.png_bytes(*parts, size=size)


def test_png_smallest_size_renders():
    parts = model((square(0.0), TEAL))
    with Image.open(io.BytesIO(model3d.png_bytes(*parts, size=16, views=((0, 90),)))) as im:
        assert im.size == (32, 16)


def depth_oracle(xy, depth, big):
    """Owner triangle per pixel (-1: none) from first principles: a pixel centre's barycentric
    weights solved as a linear system, inside when all are >= 0, the largest interpolated
    depth wins, ties to the first triangle; and a mask of the pixels too near an edge or a tie
    to call."""
    q = np.stack(np.meshgrid(np.arange(big) + 0.5, np.arange(big) + 0.5), -1).reshape(-1, 2)
    best = np.full(len(q), -np.inf)
    owner = np.full(len(q), -1)
    unsure = np.zeros(len(q), bool)
    for k, (corners, d) in enumerate(zip(xy, depth)):
        m = np.array([corners[1] - corners[0], corners[2] - corners[0]]).T
        if abs(np.linalg.det(m)) < 1e-9:
            continue
        w12 = np.linalg.solve(m, (q - corners[0]).T).T
        w = np.column_stack([1 - w12.sum(axis=1), w12])
        inside = (w >= 0).all(axis=1)
        unsure |= (np.abs(w) < 1e-6).any(axis=1) & (w >= -1e-6).all(axis=1)
        z = w @ d
        unsure |= inside & (np.abs(z - best) < 1e-9)
        win = inside & (z > best)
        best[win], owner[win] = z[win], k
    return owner, unsure


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("chunk", [7, 2_000_000])
def test_depth_buffer_keeps_the_nearest_triangle_at_every_pixel(seed, chunk, monkeypatch):
    monkeypatch.setattr(model3d, "PAIRS_PER_CHUNK", chunk)
    rng = np.random.default_rng(seed)
    big = 24
    xy = rng.uniform(0.5, big - 0.5, (14, 3, 2))
    xy[0] = [[5.3, 5.3], [5.9, 5.4], [5.4, 5.9]]  # smaller than a pixel, around one centre
    xy[1] = [[3.0, 3.0], [3.0, 3.0], [9.0, 9.0]]  # degenerate: covers nothing
    xy[2] = [[big - 3.0, 2.2], [big + 6.0, 4.1], [big - 2.5, 12.3]]  # past the right edge
    xy[3] = [[1.2, 0.2], [1.8, 0.3], [1.3, 0.8]]  # around pixel 1 only (alone in a chunk of 7)
    depth = rng.uniform(-1, 1, (14, 3))  # tilted: triangles pass through one another
    depth[0] = depth[3] = 2.0  # the small ones in front
    covered, tri, _ = model3d._depth_buffer(xy, depth, big)
    got = np.full(big * big, -1)
    got[covered] = tri
    want, unsure = depth_oracle(xy, depth, big)
    assert (got[~unsure] == want[~unsure]).all()
    assert got[5 * big + 5] == 0 and got[1] == 3 and (want >= 0).sum() > big * big / 3


def test_depth_ties_go_to_the_first_triangle_however_chunked(monkeypatch):
    # two coplanar squares of different colours over one another: the first one drawn shows,
    # with one chunk for all or a chunk per triangle
    parts = model((square(0.0), TEAL), (square(0.0), SAND))
    pictures = []
    for chunk in (2_000_000, 300):
        monkeypatch.setattr(model3d, "PAIRS_PER_CHUNK", chunk)
        pictures.append(model3d.png_bytes(*parts, size=SIZE, views=((0, 90),)))
        (img,) = views(pictures[-1], 1)[:1]
        assert np.abs(img[SIZE // 2, SIZE // 2] - lit(TEAL, [0, 0, 1])).max() < 2
    assert pictures[0] == pictures[1]


def test_png_frames_any_model_whatever_its_place_and_units():
    # the same two squares, moved far from the origin and scaled to 1/100: the same picture
    parts = model((square(0.5), TEAL), (square(-0.5), SAND))
    moved = (parts[0] / 100 + [10.0, -5.0, 3.0], parts[1], parts[2])
    look = dict(size=SIZE, views=((0, 90), (30, 40)))
    first, second = (views(model3d.png_bytes(*p, **look), 2) for p in (parts, moved))
    for a, b in zip(first, second):
        assert np.abs(a.astype(int) - b).max() <= 2


def test_png_shading_is_lambert_from_the_light_with_ambient():
    # a colour whose lit value is close to a rounding boundary: the light's direction must be
    # a unit vector for the value to come out right
    colour = (250, 122, 18)
    parts = model((square(0.0), colour))
    (img,) = views(model3d.png_bytes(*parts, size=SIZE, views=((0, 90),)), 1)[:1]
    centre = img[SIZE // 2 - 4:SIZE // 2 + 4, SIZE // 2 - 4:SIZE // 2 + 4].reshape(-1, 3)
    assert (centre == np.round(lit(colour, [0, 0, 1]))).all()
    # a face turned to the light is at full colour, a face edge-on to it at the ambient 35 %
    light = model3d.LIGHT / np.linalg.norm(model3d.LIGHT)
    assert lit(colour, light) == pytest.approx(colour)


def test_png_odd_number_of_views_leaves_the_last_cell_white():
    parts = model((square(0.5), TEAL), (square(-0.5), SAND))
    with Image.open(io.BytesIO(model3d.png_bytes(*parts, size=SIZE,
                                                 views=((0, 90), (0, -90), (0, 45))))) as im:
        img = np.asarray(im.convert("RGB"))
    assert img.shape == (2 * SIZE, 2 * SIZE, 3)
    assert (img[SIZE:, SIZE:] == 255).all()


def test_png_default_size_is_480_per_view():
    parts = model((square(0.0), TEAL))
    with Image.open(io.BytesIO(model3d.png_bytes(*parts, views=((0, 90),)))) as im:
        assert im.size == (960, 480)


@pytest.mark.parametrize("seed", range(3))
def test_depth_buffer_clips_triangles_at_every_edge_of_the_image(seed):
    # triangles reaching past each edge, and wholly outside on each side: each paints the
    # pixels of the image whose centres it covers, and nothing else
    rng = np.random.default_rng(seed)
    big = 16
    xy = rng.uniform(-big / 2, 1.5 * big, (24, 3, 2))
    left = np.array([[-9.0, 3.0], [-2.0, 12.0], [-4.0, 6.0]])  # 2 px or more away
    xy[0], xy[1] = left, big - left * [1, -1] - [0, big]  # wholly left, wholly right
    xy[2], xy[3] = left[:, ::-1], big - left[:, ::-1] * [-1, 1] - [big, 0]  # above, below
    depth = rng.uniform(-1, 1, (24, 3))
    covered, tri, _ = model3d._depth_buffer(xy, depth, big)
    got = np.full(big * big, -1)
    got[covered] = tri
    want, unsure = depth_oracle(xy, depth, big)
    assert (got[~unsure] == want[~unsure]).all()
    assert not np.isin(got, range(4)).any()


@pytest.mark.parametrize("turn", range(3))
@pytest.mark.parametrize("diagonal", [0, 1])
def test_depth_buffer_leaves_no_gap_on_an_edge_through_pixel_centres(turn, diagonal):
    # a square with its corners on pixel centres, cut along a diagonal into two triangles
    # (each with its vertices turned so the diagonal is each of its edges in turn): every
    # pixel centre in the closed square is covered, on its sides and on the diagonal too
    big = 12
    corners = np.array([[2.5, 2.5], [10.5, 2.5], [10.5, 10.5], [2.5, 10.5]])
    corners = np.roll(corners, diagonal, axis=0)
    halves = np.array([[0, 1, 2], [2, 3, 0]])
    xy = corners[np.roll(halves, turn, axis=1)]
    covered, tri, _ = model3d._depth_buffer(xy, np.zeros((2, 3)), big)
    cols, rows = np.meshgrid(range(2, 11), range(2, 11))
    assert sorted(covered.tolist()) == sorted((rows * big + cols).ravel().tolist())
    # the diagonal's pixels go to the first triangle (a tie), the rest to the one holding them
    first = cols + rows <= 12 if diagonal else cols >= rows
    owner = dict(zip(covered.tolist(), tri.tolist()))
    assert [owner[r * big + c] for r, c in zip(rows.ravel(), cols.ravel())] == \
        np.where(first, 0, 1).ravel().tolist()


def test_png_largest_size_renders(monkeypatch):
    # the largest size the refusal names is allowed (each view a stand-in: drawn at 4096 px a
    # view holds gigabytes)
    monkeypatch.setattr(model3d, "_view", lambda *args: Image.new("RGB", (2, 2), "red"))
    parts = model((square(0.0), TEAL))
    with Image.open(io.BytesIO(model3d.png_bytes(*parts, size=4096, views=((0, 90),)))) as im:
        assert im.size == (8192, 4096)


def test_png_views_are_drawn_twice_as_large_and_halved_with_lanczos(monkeypatch):
    # each view drawn without supersampling at twice the size, then halved by the filter's
    # definition: the PNG's view, to within rounding (other filters differ by 10 or more)
    parts = model((square(0.5), TEAL), (square(-0.5, x=0.7), SAND))
    look = dict(views=((20, 25), (200, -60)))
    small = views(model3d.png_bytes(*parts, size=SIZE, **look), 2)
    monkeypatch.setattr(model3d, "SUPERSAMPLE", 1)
    large = views(model3d.png_bytes(*parts, size=2 * SIZE, **look), 2, 2 * SIZE)
    for got, twice in zip(small, large):
        assert np.abs(got.astype(int) - lanczos_halved(twice)).max() <= 1


def test_depth_buffer_draws_a_lone_triangle_over_the_last_pixel():
    # one triangle around the centre of the last pixel, reaching past the image's corner: that
    # pixel is drawn (the triangle's box, clipped to the image, is that pixel alone)
    big = 8
    xy = big - np.array([[[0.9, 0.9], [-4.0, 0.9], [0.9, -4.0]]])
    covered, tri, _ = model3d._depth_buffer(xy, np.zeros((1, 3)), big)
    assert covered.tolist() == [big * big - 1] and tri.tolist() == [0]


def test_depth_buffer_draws_no_pixel_outside_a_triangles_box():
    # slivers so thin that their barycentric weights are rounding noise, which takes pixel
    # centres on a sliver's line, even past its end, for inside; yet a triangle draws no pixel
    # outside its box: one ending a quarter pixel right of column 62's centres, its box
    # clipped to the image's last column, and one wholly left of the image
    big = 64
    slivers = np.array([
        [[63.751620452537146, 7.218742386768315], [105.15930389207364, -2.086176041217823],
         [98.28076051646093, -0.5404656875608567]],
        [[-0.8480617845833467, 47.782418490758715], [-40.29366194156568, 35.727610785348084],
         [-31.93462051576808, 38.28218307195363]]])
    for xy in slivers:
        covered, _, _ = model3d._depth_buffer(xy[None], np.zeros((1, 3)), big)
        centres = np.column_stack([covered % big, covered // big]) + 0.5
        assert ((centres >= xy.min(axis=0)) & (centres <= xy.max(axis=0))).all()
