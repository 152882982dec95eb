"""Reading and validating a million faces: OBJ read and validation throughput, with peers run
in the same process on the same file or mesh.

Two OBJ files of about a million faces, written by weave-cut: the 1000 x 1000 square grid
(short integer coordinates) and the square grid 100 x 100 after three snub steps (pentagons,
coordinates written with ``repr``, 17 digits). Peers for the read: ``numpy.loadtxt`` of the
same numbers (the vertex and face blocks as two uniform tables, no validation of the OBJ
rules), numpy's C parser over the bare numbers (``np.fromstring``) and trimesh's OBJ loader
when installed. Peer for validation: GEOS validity
(``shapely.is_valid``) of every face alone, which the check used to run on every face.

    python benchmarks/bench_mesh_io.py [--repeat 3]

Targets (the engine's speed work): OBJ read of a million faces <= 1 s, validation <= 3 s.
"""

from __future__ import annotations

import argparse
import io
import tempfile
import time
from pathlib import Path

import numpy as np
import shapely

from weavecut import inputs
from weavecut.mesh import Mesh
from weavecut.mesh_io import read_mesh, write_mesh
from weavecut.subdivision import subdivide
from weavecut.validation import validate


def best_of(fn, repeat: int) -> tuple[float, float]:
    """Best wall and best CPU seconds of ``repeat`` runs (the CPU time is steadier on a
    shared machine)."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        fn()
        wall, cpu = min(wall, time.perf_counter() - w), min(cpu, time.process_time() - c)
    return wall, cpu


def loadtxt_peer(path: Path) -> None:
    """numpy.loadtxt of the vertex block and the face block, each a uniform table."""
    data = path.read_bytes()
    v0, f0 = data.index(b"\nv "), data.index(b"\nf ")
    np.loadtxt(io.BytesIO(data[v0 + 1:f0]), usecols=(1, 2, 3))
    np.loadtxt(io.BytesIO(data[f0 + 1:]), dtype=np.int64,
               usecols=range(1, len(data[f0 + 1:data.index(b"\n", f0 + 1)].split())))


def fromstring_peer(path: Path) -> None:
    """numpy's C number parser over the same numbers (the v block as floats, the f block as
    whole numbers): no lines, no rules, no messages; the floor a numpy reader can reach."""
    data = path.read_bytes()
    v0, f0 = data.index(b"\nv ") + 1, data.index(b"\nf ") + 1
    np.fromstring(data[v0:f0].replace(b"v", b" "), sep=" ")
    np.fromstring(data[f0:].replace(b"f", b" "), dtype=np.int64, sep=" ")


def peers(path: Path) -> dict:
    found = {"numpy.loadtxt (two uniform tables)": lambda: loadtxt_peer(path),
             "numpy.fromstring (the numbers only)": lambda: fromstring_peer(path)}
    try:
        import trimesh

        found["trimesh OBJ loader"] = lambda: trimesh.load(path, process=False)
    except ImportError:
        pass
    return found


def row(name: str, faces: int, wall: float, cpu: float, ours: float | None = None) -> None:
    ratio = "" if ours is None else f"   weave-cut / peer = {ours / cpu:.2f}"
    print(f"  {name:36s} {wall:7.3f} s wall {cpu:7.3f} s CPU {faces / cpu:>12,.0f} faces/s"
          f"{ratio}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    meshes = {"square-grid:1000x1000": inputs.get("square-grid:1000x1000"),
              "square-grid:100x100, snub level 3": subdivide(inputs.get("square-grid:100x100"),
                                                           3)[-1].mesh}
    with tempfile.TemporaryDirectory() as folder:
        for name, mesh in meshes.items():
            path = Path(folder) / "m.obj"
            write_mesh(mesh, path)
            size = path.stat().st_size / 2**20
            print(f"\n{name}: {mesh.n_faces:,} faces, {mesh.n_vertices:,} vertices, "
                  f"OBJ {size:.0f} MiB (best of {args.repeat})")
            wall, ours = best_of(lambda: read_mesh(path), args.repeat)
            row("weave-cut read_mesh", mesh.n_faces, wall, ours)
            for peer, fn in peers(path).items():
                row(peer, mesh.n_faces, *best_of(fn, args.repeat), ours)
            fresh = lambda: Mesh(mesh.vertices, mesh.face_offsets, mesh.face_indices)  # noqa
            wall, ours = best_of(lambda: validate(fresh()), args.repeat)
            row("weave-cut validate", mesh.n_faces, wall, ours)
            polygons = lambda: shapely.polygons(shapely.linearrings(  # noqa: E731
                mesh.vertices[mesh.face_indices], indices=mesh.half_edge_face))
            row("shapely.is_valid of every face", mesh.n_faces,
                *best_of(lambda: shapely.is_valid(polygons()), args.repeat), ours)
    print("\ntargets: read <= 1 s, validate <= 3 s per million faces")


if __name__ == "__main__":
    main()
