"""``python -m weavecut.kitpage OUT PAGE...``: a page at OUT linking the kit pages PAGE...
(``make run`` writes ``build/index.html`` with it), recorded in its folder's build manifest
like every file weave-cut writes there."""

import sys
from pathlib import Path

from ..manifest import file_hash, record_manifest
from . import write_index

if len(sys.argv) < 2:
    sys.exit("usage: python -m weavecut.kitpage OUT PAGE...")
out = Path(sys.argv[1])
write_index(out, "weave-cut builds", sorted(Path(p) for p in sys.argv[2:]))
record_manifest(out.parent, {out.name: file_hash(out)})
