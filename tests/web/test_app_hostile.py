"""Hostile requests answer 4xx, never 500, and write nothing outside the app's folder: paths
in every parameter, a path as the input, huge numbers, wrong types, 1,000 parameters, a huge
query, oversized, empty, malformed and random uploads."""

from __future__ import annotations

import hashlib
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from weavecut.web import forms, queries
from weavecut.web.uploads import MAX_BYTES

from tests.web_app import written

ROOT = Path(__file__).resolve().parents[2]
PATHS = ["../../etc/passwd", "/etc/passwd", "..\\..\\boot.ini", "palette.toml",
         "~/.ssh/id_rsa", "x\x00y", "file:///etc/passwd", ".hidden"]
STRANGE = ["1e999", "-1e308", "nan", "inf", "9" * 150, "[]", "{}", "--help", "-o",
           "true false", "0x10", "<script>"]


def keys():
    return [(n, f.key) for n in forms.COMMANDS for f in forms.fields(n)]


def query(name: str, key: str, value: str) -> dict:
    """``key=value`` with the page's starting input, so only ``value`` can be refused."""
    start = forms.STARTING.get(name)
    return {**(dict([start]) if start and start[0] != key else {}), key: value}


@pytest.mark.parametrize(("name", "key"), keys())
def test_a_path_in_any_parameter_is_refused(recording, tmp_path, name, key):
    for value in PATHS:
        for route in ("check", "preview.svg"):
            response = recording.get(f"/{name}/{route}", params=query(name, key, value))
            assert 400 <= response.status_code < 500, (key, value, response.text)
    assert recording.queue.specs == []
    assert written(tmp_path, tmp_path / "app") == []


@pytest.mark.parametrize(("name", "key"), keys())
def test_strange_values_answer_4xx_or_a_job(recording, name, key):
    for value in STRANGE:
        response = recording.get(f"/{name}/check", params=query(name, key, value))
        assert response.status_code in (200, 400), (key, value)
        if response.status_code == 200:  # a value the command takes (a layer named "[]")
            assert queries.parse(name, list(query(name, key, value).items())).args
    for spec in recording.queue.specs:
        assert not any(a.startswith("-o") or a == "--help" for a in spec.args)


def test_the_input_is_a_built_in_name_or_an_upload(recording):
    for value in ["../../etc/passwd", "/etc/passwd", "pentagon/../x", "pentagon.svg",
                  "upload:../../etc/passwd", "upload:" + "0" * 64, "square-grid:3x3;rm",
                  "--help", "-"]:
        response = recording.get("/strands/preview.svg", params={"input": value})
        assert response.status_code == 400, value
        assert response.headers["x-field"] == "input"


def test_many_parameters_and_long_queries_are_refused(recording, tmp_path):
    many = "&".join(f"p{i}=1" for i in range(1000))
    assert recording.get(f"/strands/preview.svg?{many}").status_code == 400
    assert recording.get(f"/strands?{many}").status_code == 400
    same = "&".join(["size=2cm"] * 1000)
    assert recording.get(f"/strands/check?input=pentagon&{same}").status_code == 400
    long = "input=pentagon&layer=" + "x" * 20000
    assert recording.get(f"/strands/preview.svg?{long}").status_code == 400
    assert recording.queue.specs == []
    assert written(tmp_path, tmp_path / "app") == []


def test_an_upload_is_kept_under_its_hash(recording, tmp_path):
    heart = (ROOT / "templates" / "recipes" / "heart.svg").read_bytes()
    response = recording.post("/upload", content=heart,
                              headers={"content-type": "text/plain",
                                       "x-file-name": "../../evil.sh"})
    assert response.status_code == 200
    ident = response.json()["id"]
    assert ident == hashlib.sha256(heart).hexdigest()
    assert written(tmp_path, tmp_path / "app") == []
    kept = sorted(p.name for p in (tmp_path / "app" / "uploads").iterdir())
    assert kept == [f"{ident}.kind", f"{ident}.svg"]  # the upload, and what kind of kit it is
    response = recording.get(f"/puzzle/preview.svg?input=upload:{ident}&cell=39mm&levels=2")
    assert response.status_code == 200
    spec = recording.queue.specs[-1]
    assert spec.args[0] == f"upload-{ident}.svg"
    assert spec.files == ((f"upload-{ident}.svg", heart),)


@pytest.mark.parametrize(("data", "status", "says"), [
    (b"", 400, "empty"),
    (b"\x89PNG\r\n\x1a\n" + bytes(100), 400, "not a drawing"),
    (b"<svg xmlns='http://www.w3.org/2000/svg'></svg>", 400, "no outlines"),
    (b"<svg xmlns='http://www.w3.org/2000/svg'><path d='M0 0 L10 0 L10'/></svg>", 400, ""),
    (b"0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n", 400, ""),
    (b"v 0 0 0\nv 1 0 0\nf 1 2 9\n", 400, ""),
    (b"{\"format\": \"weave-cut-mesh\", \"vertices\": [[0, 0]]", 400, ""),
    (b"<?xml version='1.0'?><!DOCTYPE svg [<!ENTITY x SYSTEM 'file:///etc/passwd'>]>"
     b"<svg xmlns='http://www.w3.org/2000/svg'><text>&x;</text></svg>", 400, ""),
])
def test_a_malformed_upload_is_refused_in_one_line(recording, tmp_path, data, status, says):
    response = recording.post("/upload", content=data)
    assert response.status_code == status
    assert says in response.text and "\n" not in response.text.strip()
    assert "Traceback" not in response.text and str(tmp_path) not in response.text
    assert "root:" not in response.text
    assert not (tmp_path / "app" / "uploads").exists() or not any(
        (tmp_path / "app" / "uploads").iterdir())


def test_an_oversized_upload_is_413(recording, tmp_path):
    big = b"v 0 0 0\n" * (MAX_BYTES // 8 + 1)
    assert recording.post("/upload", content=big).status_code == 413

    def chunks():  # no content-length: the limit holds while reading
        for _ in range(MAX_BYTES // 2**20 + 2):
            yield b"#" * 2**20

    assert recording.post("/upload", content=chunks()).status_code == 413
    assert written(tmp_path, tmp_path / "app") == []


@settings(max_examples=40)
@given(st.binary(max_size=2000) | st.text(max_size=500).map(str.encode))
def test_random_uploads_never_crash(tmp_path_factory, data):
    from tests.web_app import Recording, make_client

    root = tmp_path_factory.mktemp("random")
    with make_client(root, Recording()) as client:
        response = client.post("/upload", content=data)
    assert response.status_code in (200, 400, 413), response.text
    if response.status_code == 200:
        assert (root / "app" / "uploads").is_dir()
