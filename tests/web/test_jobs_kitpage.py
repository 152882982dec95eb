"""Every kit explains itself: a command without --html (subdivide, figure) gets its kit page in
the ZIP, written after the command as --html writes it: a picture and a link for every file
it wrote, and the command line that writes the same files; its other files are the CLI's."""

from __future__ import annotations

import html
import re
import shlex

import pytest

from weavecut.web.jobs import PAGE, JobSpec, run_job

from tests.web.test_jobs import cli_files, unzip

SPECS = [JobSpec("kit", "subdivide", ("pentagon", "--levels=3", "--earlier-levels")),
         JobSpec("kit", "figure", ("square-grid-weaving",))]


@pytest.mark.parametrize("spec", SPECS, ids=lambda s: s.command)
def test_a_command_without_html_gets_its_kit_page(spec, tmp_path):
    result = run_job(spec)
    assert result.ok, result.error
    zipped = unzip(result.body)
    assert PAGE in zipped
    page = zipped.pop(PAGE).decode("utf-8")
    made = cli_files(spec, tmp_path)
    assert zipped == made  # the other files byte for byte
    for name in made:
        if not name.startswith("."):
            assert f'href="{name}"' in page and f'src="{name}"' in page, name
    shown = html.unescape(re.search(r"<code>weave-cut (.*?)</code>", page).group(1))
    assert ["weave-cut", *shlex.split(shown)] == ["weave-cut", "-q", spec.command, *spec.args,
                                                   "-o", shown.split()[-1]]
    assert "weave-cut-job" not in page and "/tmp" not in page  # no trace of the job's folder
    assert unzip(run_job(spec).body)[PAGE] == page.encode("utf-8")  # same job, same page
