"""``run_job``: a web job makes byte for byte the files of the same command typed in an empty
folder (the oracle: a real ``python -m weavecut`` process), zipped so that the same job gives
the same bytes; errors answer the command's own one-line message with 400 or 422."""

from __future__ import annotations

import io
import json
import subprocess
import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import pytest
from hypothesis import given, strategies as st

from weavecut import __version__
from weavecut.web.jobs import JobResult, JobSpec, code_version, command_line, run_job

pytestmark = pytest.mark.slow  # whole kits through the job queue, against the command line's

ROOT = Path(__file__).resolve().parents[2]
HEART = (ROOT / "examples" / "heart.svg").read_bytes()

KITS = {
    "strands paper model": JobSpec("kit", "strands", ("square-grid", "--size", "27cm")),
    "strands laser card": JobSpec("kit", "strands", ("square-grid", "--laser-card",
                                                     "--palette", "maritime-4")),
    "puzzle of an upload": JobSpec("kit", "puzzle", ("upload-heart.svg", "--cell", "39mm",
                                                     "--levels", "2", "--size", "30cm"),
                                   files=(("upload-heart.svg", HEART),)),
}


def cli_files(spec: JobSpec, folder: Path) -> dict[str, bytes]:
    """What ``weave-cut`` writes for ``spec`` in the empty ``folder`` holding its uploads."""
    for name, data in spec.files:
        (folder / name).write_bytes(data)
    proc = subprocess.run([sys.executable, "-m", "weavecut", *command_line(spec)], cwd=folder,
                          capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    uploads = {n for n, _ in spec.files}
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*")
            if p.is_file() and p.name not in uploads}


def unzip(body: bytes) -> dict[str, bytes]:
    with zipfile.ZipFile(io.BytesIO(body)) as zf:
        assert zf.testzip() is None
        return {i.filename: zf.read(i) for i in zf.infolist()}


@pytest.mark.parametrize("name", KITS)
def test_a_kit_holds_the_files_the_command_line_writes(name, tmp_path):
    spec = KITS[name]
    result = run_job(spec)
    assert result.ok and result.status == 200 and result.media_type == "application/zip"
    files = cli_files(spec, tmp_path)
    assert "index.html" in files  # the kit page comes with it
    zipped = unzip(result.body)
    assert sorted(zipped) == sorted(files)
    for path, data in files.items():
        assert zipped[path] == data, path
    assert result.summary and not result.error


def test_the_summary_is_what_the_command_printed_as_json(tmp_path):
    spec = KITS["strands laser card"]
    for n, data in spec.files:
        (tmp_path / n).write_bytes(data)
    printed = subprocess.run([sys.executable, "-m", "weavecut", *command_line(spec)],
                             cwd=tmp_path, capture_output=True, text=True, check=True).stdout
    summary = run_job(spec).summary
    assert summary == json.loads(printed)
    assert summary["sheets"] >= 1 and summary["cut_minutes"] > 0


def test_the_same_job_gives_the_same_zip_bytes():
    spec = KITS["strands paper model"]
    first, second = run_job(spec).body, run_job(spec).body
    assert first == second
    with zipfile.ZipFile(io.BytesIO(first)) as zf:
        infos = zf.infolist()
    assert [i.filename for i in infos] == sorted(i.filename for i in infos)
    for info in infos:
        assert info.date_time == (1980, 1, 1, 0, 0, 0)
        assert info.external_attr >> 16 == 0o100644 and info.create_system == 3
        assert info.extra == b"" and info.comment == b""
    # the local headers too: no extra field (a 30-byte header, then the name, then the data)
    for info in infos:
        header = first[info.header_offset:info.header_offset + 30]
        assert int.from_bytes(header[28:30], "little") == 0


def test_a_preview_is_the_picture_preview_draws(tmp_path):
    strands = run_job(JobSpec("preview", "strands", ("square-grid",)))
    assert strands.ok and strands.media_type == "image/svg+xml"
    assert ElementTree.fromstring(strands.body).tag == "{http://www.w3.org/2000/svg}svg"
    subprocess.run([sys.executable, "-m", "weavecut", "-q", "strands", "square-grid",
                    "--preview", "-o", "preview.svg"], cwd=tmp_path, check=True)
    assert strands.body == (tmp_path / "preview.svg").read_bytes()
    puzzle = run_job(JobSpec("preview", "puzzle", ("--levels", "3")))
    subprocess.run([sys.executable, "-m", "weavecut", "-q", "puzzle", "--levels", "3",
                    "--preview", "-o", "preview"], cwd=tmp_path, check=True)
    assert puzzle.body == (tmp_path / "preview" / "puzzle-preview.svg").read_bytes()


def test_a_command_that_prints_gives_its_json():
    result = run_job(JobSpec("kit", "stats", ("pentagon", "--levels", "2")))
    zipped = unzip(result.body)
    assert list(zipped) == ["stats.json"]
    assert json.loads(zipped["stats.json"]) == result.summary
    assert [row["faces"] for row in result.summary["levels"]] == [1, 5, 25]  # F' = sum of n_f


@pytest.mark.parametrize("spec, status, words", [
    (JobSpec("kit", "strands", ("square-grid", "--size", "27")), 400, "has no unit"),
    (JobSpec("kit", "strands", ("square-grid", "--sise", "27cm")), 400, "--size"),
    (JobSpec("kit", "levels", ("pentagon", "--levels", "16", "--size", "16384")), 422,
     "needs about"),
    (JobSpec("kit", "nosuch", ()), 400, "unknown command"),
    (JobSpec("kit", "build", ("jigsaw-50cm-poplar",)), 400, "unknown command"),
    (JobSpec("cake", "strands", ()), 400, "unknown job kind"),
    (JobSpec("kit", "strands", ("square-grid", "-o", "x.pdf")), 400, "set by the job"),
    (JobSpec("kit", "strands", ("square-grid", "--json")), 400, "set by the job"),
    (JobSpec("kit", "strands", ("square-grid", "--html=x.html")), 400, "set by the job"),
    (JobSpec("kit", "strands", ("square-grid", "-n", "2")), 400, "long names"),
    (JobSpec("kit", "strands", ("/etc/passwd",)), 400, "never a path"),
    (JobSpec("kit", "strands", ("square-grid", "--palette=../x.toml")), 400, "never a path"),
    (JobSpec("kit", "puzzle", ("up.svg",), files=(("../up.svg", b"<svg/>"),)), 400,
     "plain file name"),
    (JobSpec("kit", "puzzle", (), output="index.html"), 400, "plain file name"),
    (JobSpec("kit", "puzzle", ("nothing.svg",)), 422, "nothing.svg"),
])
def test_errors_answer_the_commands_own_message(spec, status, words):
    result = run_job(spec)
    assert not result.ok and result.status == status and result.body == b""
    assert words in result.error and "\n" not in result.error
    assert "Traceback" not in result.error


def test_the_message_is_the_one_the_command_line_prints(tmp_path):
    spec = JobSpec("kit", "strands", ("square-grid", "--size", "27"))
    proc = subprocess.run([sys.executable, "-m", "weavecut", *command_line(spec)],
                          cwd=tmp_path, capture_output=True, text=True)
    assert proc.returncode == 2
    assert f"Error: {run_job(spec).error}" in proc.stderr


def test_a_job_leaves_no_folder_and_restores_the_working_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path))
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", None)
    cwd, argv = Path.cwd(), list(sys.argv)
    run_job(KITS["puzzle of an upload"])
    run_job(JobSpec("kit", "strands", ("square-grid", "--size", "27")))  # refused
    assert list(tmp_path.iterdir()) == []
    assert Path.cwd() == cwd and sys.argv == argv


def test_key_depends_on_every_part_and_on_the_uploads_bytes_only():
    base = JobSpec("kit", "puzzle", ("up.svg",), files=(("up.svg", b"<svg/>"),))
    variants = [JobSpec("preview", "puzzle", ("up.svg",), files=base.files),
                JobSpec("kit", "strands", ("up.svg",), files=base.files),
                JobSpec("kit", "puzzle", ("up.svg", "--levels", "3"), files=base.files),
                JobSpec("kit", "puzzle", ("up.svg",), files=(("up.svg", b"<SVG/>"),)),
                JobSpec("kit", "puzzle", ("up.svg",), files=base.files, output="p")]
    keys = {base.key(), *(v.key() for v in variants)}
    assert len(keys) == 1 + len(variants)
    assert all(len(k) == 64 and int(k, 16) >= 0 for k in keys)
    same = JobSpec("kit", "puzzle", ("up.svg",), files=((("up.svg"), bytes(b"<svg/>")),))
    assert same.key() == base.key()


def test_key_is_sha256_of_the_canonical_json():
    import hashlib

    spec = JobSpec("kit", "stats", ("pentagon",), files=(("a.svg", b"x"),))
    doc = ('{"args":["pentagon"],"command":"stats","files":[["a.svg","'
           + hashlib.sha256(b"x").hexdigest() + '"]],"kind":"kit","output":"","version":"'
           + code_version() + '"}')
    assert code_version().startswith(__version__ + "+")
    assert spec.key() == hashlib.sha256(doc.encode()).hexdigest()


@given(st.booleans(), st.binary(max_size=300), st.text(max_size=30),
       st.dictionaries(st.text(max_size=8), st.integers() | st.text(max_size=8), max_size=4),
       st.integers(100, 599))
def test_a_result_survives_its_encoding(ok, body, error, summary, status):
    result = JobResult(ok, body, "image/svg+xml", summary, error, status)
    assert JobResult.from_bytes(result.to_bytes()) == result
