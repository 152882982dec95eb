"""Guards of the web app that no test failed without (each disabled once by
``tests/hand_audit/guards.py``, #34): a test that only wanted "some 4xx" passed on another
refusal further on. Each request here must be refused for its own reason, in words."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.web_app import written
from weavecut.web.jobs import JobResult, JobSpec, run_job

ROOT = Path(__file__).resolve().parents[2]


def test_more_parameters_than_a_form_has_are_refused_as_too_many(recording, tmp_path):
    many = "&".join(f"p{i}=1" for i in range(65))  # not "unknown parameter 'p0'"
    response = recording.get(f"/strands/check?{many}")
    assert response.status_code == 400
    assert response.json()["errors"] == {"form": "65 parameters; a form of strands has at "
                                                 "most 64"}
    same = "&".join(["size=2cm"] * 65)  # not "size is given twice"
    response = recording.get(f"/strands/preview.svg?input=pentagon&{same}")
    assert response.status_code == 400
    assert response.text == "66 parameters; a form of strands has at most 64"
    assert recording.queue.specs == []
    assert written(tmp_path, tmp_path / "app") == []


def test_a_parameter_given_twice_is_refused_but_formats_add_up(recording):
    response = recording.get("/strands/preview.svg?input=pentagon&size=2cm&size=3cm")
    assert response.status_code == 400 and response.text == "size is given twice"
    assert response.headers["x-field"] == "size"
    response = recording.get("/strands/check?input=square-grid&laser-card=on"
                             "&formats=svg&formats=dxf")
    assert response.status_code == 200, response.text
    assert "--formats svg,dxf" in response.json()["command_line"]


def test_a_result_without_its_header_line_or_with_another_header_is_no_result():
    """A kept result cut before its body (no newline) once read as a whole result with an
    empty body; a header with a key missing or added is not one either."""
    whole = JobResult(True, b"<svg/>", "image/svg+xml", {"n": 1}, "", 200).to_bytes()
    head = whole.partition(b"\n")[0]
    with pytest.raises(ValueError, match="no header line"):
        JobResult.from_bytes(head)
    doc = json.loads(head)
    for other in ({k: v for k, v in doc.items() if k != "status"}, {**doc, "extra": 1},
                  [doc]):
        with pytest.raises(ValueError, match="wrong header"):
            JobResult.from_bytes(json.dumps(other).encode() + b"\n<svg/>")


def test_a_jobs_output_may_not_be_named_as_an_upload():
    spec = JobSpec("kit", "puzzle", ("up.svg",), files=(("up.svg", b"<svg/>"),),
                   output="up.svg")
    result = run_job(spec)
    assert (result.ok, result.status) == (False, 400)
    assert result.error == "the output 'up.svg' is an upload's name"


def test_a_kit_larger_than_a_web_job_returns_is_refused(monkeypatch):
    """The limit made small (a real kit over it takes minutes): the kit is refused with its
    size and the way to make it, not returned."""
    from weavecut.web import jobs

    monkeypatch.setattr(jobs, "MAX_BODY", 1 << 10)
    result = run_job(JobSpec("kit", "weave", ("square-grid", "--levels", "1")))
    assert (result.ok, result.status, result.body) == (False, 422, b"")
    assert result.error.startswith("the kit is ")
    assert result.error.endswith("; a web job returns at most 0 MB (run it with the weave-cut "
                                 "command)")


def test_a_long_query_is_refused_by_its_length_before_its_values(recording):
    long = "input=pentagon&layer=" + "x" * 20000  # not "layer: a value of at most 200 ..."
    response = recording.get(f"/strands/preview.svg?{long}")
    assert response.status_code == 400
    assert response.text == f"a query of {len(long):,} characters; at most 8,192"


def test_an_oversized_upload_is_refused_by_its_length_then_while_it_is_read(recording):
    """The declared length is refused before the body is read; without one, the body is
    refused as soon as it passes the limit, not once whole (the store's own check)."""
    from weavecut.web.uploads import MAX_BYTES

    big = b"v 0 0 0\n" * (MAX_BYTES // 8 + 1)
    response = recording.post("/upload", content=big)
    assert response.status_code == 413
    assert response.text == f"{len(big):,} bytes; an upload is at most {MAX_BYTES >> 20} MiB"

    def chunks():
        for _ in range(MAX_BYTES // 2**20 + 2):
            yield b"#" * 2**20

    response = recording.post("/upload", content=chunks())
    assert response.status_code == 413
    assert response.text == (f"more than {MAX_BYTES >> 20} MiB; an upload is at most "
                             f"{MAX_BYTES >> 20} MiB")


def test_each_example_drawing_and_mesh_is_told_by_its_bytes(tmp_path):
    """Every example file's format is known from its bytes alone (the upload's name is never
    read): a DXF (text and binary), a weave-cut JSON mesh, an SVG and an OBJ."""
    import ezdxf

    from weavecut.web.uploads import sniff

    for path in sorted(ROOT.joinpath("examples").iterdir()):
        if path.suffix in (".svg", ".dxf", ".obj", ".json"):
            assert sniff(path.read_bytes()) == path.suffix, path.name
    doc = ezdxf.new()
    doc.modelspace().add_line((0, 0), (10, 0))
    doc.saveas(tmp_path / "binary.dxf", fmt="bin")
    assert (tmp_path / "binary.dxf").read_bytes().startswith(b"AutoCAD Binary DXF")
    assert sniff((tmp_path / "binary.dxf").read_bytes()) == ".dxf"


def test_a_read_job_reads_one_file_of_a_known_format_and_the_store_bounds_its_size(tmp_path):
    from weavecut.web.uploads import MAX_BYTES, Store, UploadError, read_job, read_spec

    svg = (ROOT / "examples" / "heart.svg").read_bytes()
    assert read_job(read_spec(svg, ".svg")).ok
    for files in ((("a.svg", svg), ("b.svg", svg)), (("a.txt", svg),), ()):
        result = read_job(JobSpec("read", "upload", (), files))
        assert (result.ok, result.status) == (False, 400)
        assert result.error == "a read job reads one .svg, .dxf, .obj or .json file"
    with pytest.raises(UploadError) as caught:
        Store(tmp_path).screen(b"#" * (MAX_BYTES + 1))
    assert caught.value.status == 413
    assert caught.value.message == (f"{MAX_BYTES + 1:,} bytes; an upload is at most "
                                    f"{MAX_BYTES >> 20} MiB")


def test_a_queue_needs_a_worker_and_a_closed_queue_runs_nothing(tmp_path):
    import asyncio

    from weavecut.web.local_queue import LocalQueue

    for workers, waiting in ((0, 4), (1, -1)):
        with pytest.raises(ValueError, match="at least one worker and no negative wait"):
            LocalQueue(workers=workers, cpu_seconds=10, memory_mb=500, waiting=waiting,
                       folder=tmp_path)
    queue = LocalQueue(workers=1, cpu_seconds=10, memory_mb=500, waiting=0, folder=tmp_path)

    async def closed_then_run():
        await queue.close()
        await queue.run(JobSpec("kit", "stats", ("pentagon",)))

    with pytest.raises(RuntimeError, match="the job queue is closed"):
        asyncio.run(closed_then_run())
