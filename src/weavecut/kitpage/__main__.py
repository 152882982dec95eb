"""``python -m weavecut.kitpage OUT PAGE...``: a page at OUT linking the kit pages PAGE...
(``make run`` writes ``build/index.html`` with it)."""

import sys
from pathlib import Path

from . import write_index

if len(sys.argv) < 2:
    sys.exit("usage: python -m weavecut.kitpage OUT PAGE...")
write_index(sys.argv[1], "weave-cut builds", sorted(Path(p) for p in sys.argv[2:]))
