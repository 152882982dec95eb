"""The kit's woven 3-D model in the web app: ``GET /{command}/model.glb`` answers the very
``.glb`` of the kit's ZIP (the same job, the same cache), a bad value 400 and an unknown
command 404 as the other routes, a kit without a model 404 (``summary.json`` says which kits
have one); the viewer's scripts are the kit page's own, served by the app."""

from __future__ import annotations

import io
import zipfile

import pytest

from weavecut.kitpage.viewer import STATIC as VIEWER

SQUARE = "input=square-grid&size=27cm"


@pytest.mark.slow
@pytest.mark.parametrize(("command", "query", "member"), [
    ("strands", SQUARE, "strands-3d.glb"),
    ("puzzle", "levels=2&size=20cm", "puzzle/puzzle-3d.glb"),
])
def test_the_model_is_the_glb_of_the_kit_byte_for_byte(served, command, query, member):
    model = served.get(f"/{command}/model.glb?{query}")
    assert model.status_code == 200, model.text
    assert model.headers["content-type"] == "model/gltf-binary"
    kit = zipfile.ZipFile(io.BytesIO(served.get(f"/{command}.zip?{query}").content))
    glbs = [n for n in kit.namelist() if n.endswith(".glb")]
    assert glbs == [member]
    assert model.content == kit.read(member) and model.content[:4] == b"glTF"
    assert served.get(f"/{command}/summary.json?{query}").json()["model"] is True


def test_a_kit_without_a_model_answers_404_and_its_summary_says_so(served):
    """summary.json's ``model`` is False: the page then asks for no model (its 404 is a
    console error in the browser)."""
    response = served.get("/weave/model.glb?input=square-grid&levels=2")
    assert response.status_code == 404 and "no 3-D model" in response.text
    assert served.get("/weave/summary.json?input=square-grid&levels=2").json()["model"] is False


def test_a_bad_value_is_400_and_an_unknown_command_404(recording):
    response = recording.get(f"/strands/model.glb?{SQUARE}&levels=two")
    assert response.status_code == 400 and response.headers["x-field"] == "levels"
    assert recording.get(f"/nope/model.glb?{SQUARE}").status_code == 404
    assert recording.queue.specs == []


def test_the_app_serves_the_kit_pages_viewer_scripts(recording):
    page = recording.get("/strands").text
    for name in ("three.min.js", "viewer.js"):
        assert f'<script src="/static/viewer/{name}" defer>' in page
        served = recording.get(f"/static/viewer/{name}")
        assert served.status_code == 200
        assert served.content == (VIEWER / name).read_bytes()
        assert "script-src 'self'" in served.headers["content-security-policy"]
