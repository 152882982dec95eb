"""``python -m weavecut`` runs the CLI."""

from weavecut.cli import main

main()
