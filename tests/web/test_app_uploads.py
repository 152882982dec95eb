"""Uploads are read in a job process, never in the server's: a reader that runs out of memory
or crashes ends that process and the upload is refused (4xx, the reader's own message), the
server goes on answering, and nothing is kept until a drawing reads."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest

from weavecut import mesh_io
from weavecut.web import uploads
from weavecut.web.queues import open_queue

from tests.web_app import make_client

ROOT = Path(__file__).resolve().parents[2]
HEART = (ROOT / "templates" / "recipes" / "heart.svg").read_bytes()


def grid_obj(m: int) -> bytes:
    """A valid flat mesh of 2 (m-1)^2 triangles, megabytes of OBJ: reading it takes far more
    memory than its bytes."""
    rows = [f"v {i} {j} 0\n" for i in range(m) for j in range(m)]
    for i in range(m - 1):
        for j in range(m - 1):
            a = i * m + j + 1
            rows += [f"f {a} {a + m + 1} {a + m}\n", f"f {a} {a + 1} {a + m + 1}\n"]
    return "".join(rows).encode()


def kept(tmp_path) -> list[str]:
    folder = tmp_path / "app" / "uploads"
    return sorted(p.name for p in folder.iterdir()) if folder.is_dir() else []


def test_the_server_process_never_reads_an_upload(served, tmp_path, monkeypatch):
    called = []

    def huge(*args, **kwargs):  # a reader gone wrong: a huge allocation
        called.append(args)
        return bytearray(1 << 46)

    monkeypatch.setattr(uploads, "check", huge)
    monkeypatch.setattr(mesh_io, "read_valid_mesh", huge)
    response = served.post("/upload", content=HEART)
    assert response.status_code == 200, response.text
    assert response.json()["id"] == hashlib.sha256(HEART).hexdigest()
    assert called == []  # the job process read it, with the real readers
    assert kept(tmp_path) == [hashlib.sha256(HEART).hexdigest() + s for s in (".kind", ".svg")]


@pytest.mark.parametrize("data", [
    b"<svg xmlns='http://www.w3.org/2000/svg'></svg>",
    b"<svg xmlns='http://www.w3.org/2000/svg'><path d='M0 0 L10 0 L10'/></svg>",
    b"v 0 0 0\nv 1 0 0\nf 1 2 9\n",
    b"0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n",
])
def test_a_hostile_upload_gets_the_readers_own_message(served, tmp_path, data):
    with pytest.raises(uploads.UploadError) as read_here:  # the oracle: the reader itself
        uploads.check(data, uploads.sniff(data))
    response = served.post("/upload", content=data)
    assert response.status_code == read_here.value.status == 400
    assert response.text == read_here.value.message
    assert kept(tmp_path) == []


def test_a_reader_past_the_memory_limit_is_refused_and_the_server_goes_on(tmp_path, cwd):
    big = grid_obj(250)
    assert len(big) < uploads.MAX_BYTES
    uploads.check(big, ".obj")  # it reads, given the memory: the limit refuses it
    queue = open_queue(None, workers=1, cpu_seconds=60, memory_mb=40, waiting=2)
    with make_client(tmp_path, queue) as client:
        response = client.post("/upload", content=big)
        assert response.status_code in (413, 422), response.text
        assert "memory" in response.text and "\n" not in response.text
        assert "Traceback" not in response.text
        assert kept(tmp_path) == []
        after = client.post("/upload", content=HEART)  # the server and its queue go on
        assert after.status_code == 200, after.text
        assert client.get("/").status_code == 200
    assert kept(tmp_path) == [hashlib.sha256(HEART).hexdigest() + s for s in (".kind", ".svg")]
