"""``python -m kreisel`` runs the command line."""

from .cli import run

run()
