"""The modules a fresh interpreter holds after running some code: for tests that a path leaves
a heavy library unloaded (how long loading takes is for benchmarks/, not tests)."""

from __future__ import annotations

import json
import subprocess
import sys


def modules_after(code: str) -> set[str]:
    """``sys.modules`` of a new ``python -c code`` once the code has run."""
    code += "\nimport json as _json, sys as _sys\nprint(_json.dumps(sorted(_sys.modules)))\n"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    return set(json.loads(out.splitlines()[-1]))
