"""Guards of the web app that no test failed without (each disabled once by
``tests/hand_audit/guards.py``, #34): a test that only wanted "some 4xx" passed on another
refusal further on. Each request here must be refused for its own reason, in words."""

from __future__ import annotations

from tests.web_app import written


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
