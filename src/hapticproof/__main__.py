"""``python -m hapticproof`` runs the command-line interface."""

from hapticproof.cli import main

raise SystemExit(main())
