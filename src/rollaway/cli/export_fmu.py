"""``rollaway export-fmu``: the drum model as an FMI 2.0 co-simulation FMU for Simulink, Dymola, OpenModelica, ..."""
from __future__ import annotations

from typing import Optional

import typer

from rollaway.cli import options as opt


def export_fmu(
    out: str = typer.Argument(..., metavar="OUT.fmu", help="the FMU file to write"),
    params: Optional[str] = opt.params_option("the model: parameter set name, parameter file or model file "
                                              "(.toml, e.g. from 'diagnose --save-model'; default: paper)"),
    stop_time_s: float = typer.Option(3600.0, "--stop-time-s", help="stop time of the FMU's default experiment [s]"),
    fmi_version: str = typer.Option("2.0", "--fmi-version", metavar="VERSION",
                                    help="2.0 (every importing tool) or 3.0"),
) -> None:
    """Export the drum model as an FMI 2.0 (or 3.0) co-simulation FMU that runs without rollaway.

    The chain and the model's catalogue effects are compiled C (gcc) with the model's values baked in;
    parameters hand_force_N, initial_drum_temp_C, ambient_temp_C, facing_uphill; outputs torque_Nm (one rear
    drum), drum_temp_C, clamp_force_N, lining_temp_C; time = time since the lever was applied.
    """
    from rollaway.errors import UserError
    from rollaway.export import export_fmu as run
    if not (stop_time_s > 0 and stop_time_s < float("inf")):
        raise UserError(f"--stop-time-s {stop_time_s:g} must be a positive number of seconds, e.g. 3600")
    path = run(params or "paper", out, stop_time_s=stop_time_s, fmi_version=fmi_version)
    typer.echo(f"wrote {path} (FMI {fmi_version} co-simulation, 64-bit Linux binary and C sources; check it with "
               f"'python -m fmpy validate {path}')")


def register(app: typer.Typer) -> None:
    app.command("export-fmu")(export_fmu)
