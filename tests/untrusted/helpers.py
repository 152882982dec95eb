"""What every untrusted-input test checks: a clean refusal, strict JSON, well-formed XML."""

from __future__ import annotations

import json
import os
import xml.etree.ElementTree as ET
from pathlib import Path

from click.testing import CliRunner

from weavecut.cli import cli


def run(*args, **kwargs):
    return CliRunner().invoke(cli, [str(a) for a in args], **kwargs)


def refused(result, *needles: str, status=(1,)) -> str:
    """The one-line error of a clean refusal; it contains every needle."""
    assert result.exit_code in status, (result.exit_code, result.output)
    assert result.exception is None or isinstance(result.exception, SystemExit), \
        result.exception
    out = result.output
    assert "Traceback" not in out and "internal error" not in out, out
    assert "Usage:" not in out or status != (1,), out  # a nested command's usage never shows
    errors = [ln for ln in out.splitlines() if ln.startswith("Error")]
    assert len(errors) == 1, out
    for needle in needles:
        assert needle in errors[0], (needle, errors[0])
    return errors[0]


def strict_json(text: str | bytes):
    """json.loads that refuses NaN and Infinity, as every other JSON reader does."""
    def no_constants(name):
        raise ValueError(f"{name} is not JSON")
    return json.loads(text, parse_constant=no_constants)


def well_formed_xml(path: Path) -> ET.Element:
    return ET.fromstring(Path(path).read_bytes())


def files_under(folder: Path) -> set[str]:
    return {str(Path(d, f).relative_to(folder)) for d, _, fs in os.walk(folder) for f in fs}
