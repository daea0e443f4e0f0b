from rollaway.cli import run

run()
