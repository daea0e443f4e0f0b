"""``python -m rollaway``: the command line, as the ``rollaway`` script (:mod:`rollaway.cli`)."""
from rollaway.cli import run

run()
