"""What a web job's result depends on besides its spec: the code that runs it. A job's cache
key (``jobs.JobSpec.key``) holds ``code_version()``, so a changed source file or preset gives
new keys and a development change never serves an old kit."""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path

from .. import __version__


def tree_hash(folders) -> str:
    """sha256 hex of the files under ``folders`` (their paths relative to their folder, in
    sorted order, and their bytes), leaving out compiled Python (``__pycache__``, ``.pyc``)."""
    digest = hashlib.sha256()
    for n, folder in enumerate(Path(f) for f in folders):
        found = sorted((p.relative_to(folder).as_posix(), p) for p in folder.rglob("*")
                       if p.is_file() and "__pycache__" not in p.parts and p.suffix != ".pyc")
        for name, path in found:
            data = path.read_bytes()
            digest.update(f"{n}:{name}:{len(data)}\n".encode("utf-8", "surrogateescape"))
            digest.update(data)
    return digest.hexdigest()


@functools.cache
def code_version() -> str:
    """What a job's result depends on besides its spec: weave-cut's version and a hash of the
    installed package's files and of the presets folder (``presets.templates_dir``), read once
    per process (2 MB, some milliseconds), so a development change does not serve old kits."""
    from .. import presets

    package = Path(__file__).resolve().parent.parent
    return f"{__version__}+{tree_hash([package, presets.templates_dir()])}"
