"""Typer options shared by several commands (same flag, same help, everywhere)."""
from typing import Optional

import typer

DIRECTION = typer.Option("downhill", "--direction", metavar="DIRECTION", help="vehicle facing 'downhill' or 'uphill'")
MU_DRUM: Optional[float] = typer.Option(None, "--mu", help="shoe/drum friction μ_d [–] (default: the set's, 0.4)")
T0_C: Optional[float] = typer.Option(None, "--t0-C", help="drum temperature when the lever is applied [°C]")
DT_S = typer.Option(600.0, "--dt-s", help="time step of the printed series [s]")
MODEL_HELP = "parameter set name, parameter file or model file (.toml; default: paper)"


def params_option(help: str = MODEL_HELP):
    """``--params MODEL``: the drum model of a command (one flag, one metavar everywhere)."""
    return typer.Option(None, "--params", metavar="MODEL", help=help)


def uncertainty_option(help: str = "draw N parameter vectors from the model file's covariance: roll-away "
                                   "probability"):
    """``--uncertainty N``: draws from a model file's covariance."""
    return typer.Option(None, "--uncertainty", metavar="N", help=help)


PARAMS: Optional[str] = params_option()
UNCERTAINTY: Optional[int] = uncertainty_option()
SEED = typer.Option(None, "--seed", min=0, metavar="N", help="random seed of the --uncertainty draws (default 0)")
FORMAT = typer.Option("table", "--format", metavar="FORMAT", help="csv | json | table")
SAVE_MODEL: Optional[str] = typer.Option(
    None, "--save-model", metavar="FILE",
    help="write the calibrated model (effects, fitted values, covariance, provenance) as TOML for --params of "
         "every command")


def only_with(mode: str, **given) -> None:
    """UserError for options given without the mode that uses them (never silently ignored).

    *mode* names the option or mode that uses them ("--analytic"); *given* maps each flag to its value,
    None (or False, or an empty list) when it was not given."""
    from rollaway.errors import UserError
    used = [flag for flag, v in given.items() if v is not None and v is not False and v != [] and v != ()]
    if used:
        one = len(used) == 1
        raise UserError(f"{', '.join(used)} {'is' if one else 'are'} used only with {mode}; add {mode.split(' (')[0]} "
                        f"or leave {'it' if one else 'them'} out")
