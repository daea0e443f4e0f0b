"""The Typer application object and its lazy command group.

``rollaway --help`` and ``rollaway --version`` import no command module: the command list
and its one-line summaries are in :data:`COMMANDS`, and a command's module (with whatever it
imports: numpy, MuJoCo, pandas, matplotlib) is imported only when that command runs or its
own ``--help`` is asked for.  Every command module has a ``register(app)`` function.
"""
from __future__ import annotations

import importlib

import typer
from typer.core import TyperGroup

# name → one-line summary shown by ``rollaway --help`` (tests check it against the command's docstring)
COMMANDS = {
    "brake": "Drum temperature, normal force and torque of one drum over time.",
    "hold": "Analytic hold check of one parked car: verdict and margins.",
    "check": "Regulation hold checks (the CI gate); exit 1 if any fails.",
    "params": "List a parameter set: value, unit, source, assumed or not.",
    "paper": "Draw the analogues of the paper's Figures 9–14 as PNGs.",
    "simulate": "Simulate one scenario in MuJoCo: held, brake_slip or tyre_skid.",
    "sweep": "Map where a design holds and where it rolls away.",
    "compare": "Errors of the model against bench measurements, per test.",
    "diagnose": "Which physical effect is the paper's model missing?",
    "fit": "Error ladder: refit with effects added and watch the error fall.",
    "synth": "Write synthetic bench data from the model plus hidden effects.",
    "chart": "Design chart: least hand force against grade for drum models.",
    "export-fmu": "Export the drum model as an FMI 2.0 co-simulation FMU.",
    "risk": "Roll-away rate of a production fleet (ppm, 95 % interval), drivers and design.",
}


def load_command(name: str):
    """The click command of *name*, built from its module ``rollaway.cli.<name>``."""
    sub = typer.Typer(add_completion=False, pretty_exceptions_enable=False, rich_markup_mode=None)
    importlib.import_module(f"rollaway.cli.{name.replace('-', '_')}").register(sub)   # export-fmu: export_fmu
    from rollaway.cli.finite import refuse_non_finite
    cmd = typer.main.get_command(sub)
    refuse_non_finite(cmd)
    return cmd


class LazyGroup(TyperGroup):
    """A command group that imports a command's module only when that command is used."""

    def list_commands(self, ctx) -> list[str]:
        return list(COMMANDS)

    def get_command(self, ctx, cmd_name: str):
        if cmd_name in self.commands:
            return self.commands[cmd_name]
        if cmd_name not in COMMANDS:
            return None
        cmd = load_command(cmd_name)
        self.commands[cmd_name] = cmd
        return cmd

    def format_commands(self, ctx, formatter) -> None:
        limit = formatter.width - 6 - max(len(n) for n in COMMANDS)
        rows = [(n, h if len(h) <= limit else h[:limit - 3].rsplit(" ", 1)[0] + "...") for n, h in COMMANDS.items()]
        with formatter.section("Commands"):
            formatter.write_dl(rows)


app = typer.Typer(
    name="rollaway",
    cls=LazyGroup,
    help="Will this parked car roll away? Drum parking-brake model (Ishak et al. 2018) + MuJoCo simulator.\n\n"
         "'rollaway COMMAND --help' explains each command; the model is described in docs/model.md.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    rich_markup_mode=None,
)


def _version(value: bool) -> None:
    if value:
        from rollaway import __version__
        typer.echo(f"rollaway {__version__}")
        raise typer.Exit(0)


@app.callback()
def _main(version: bool = typer.Option(False, "--version", is_eager=True, callback=_version,
                                       help="print the version and exit")) -> None:
    """Will this parked car roll away?"""
