"""``rollaway diagnose``: which physical effect is the paper's model missing? (:func:`rollaway.diagnose`)"""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.identify_common import FORMAT_HELP, load_data, load_plugins, prepare_outputs, write_outputs


def diagnose(
    data: str = typer.Argument(..., metavar="DATA_CSV", help="measurement CSV (see 'rollaway compare --help')"),
    params: Optional[str] = opt.params_option(),
    effect_file: List[str] = typer.Option([], "--effect-file", metavar="FILE", help="Python file with extra candidate effects"),
    json_out: Optional[str] = typer.Option(None, "--json", metavar="FILE", help="write the diagnosis as JSON here"),
    report: Optional[str] = typer.Option(None, "--report", metavar="FILE", help="write a self-contained HTML report here"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help=FORMAT_HELP),
    save_model: Optional[str] = opt.SAVE_MODEL,
    noise_torque_Nm: Optional[float] = typer.Option(None, "--noise-torque-Nm", min=0.0, metavar="NM",
                                                    help="torque noise σ of the instrument [N·m] (default: "
                                                         "estimated from the data)"),
    noise_temp_C: Optional[float] = typer.Option(None, "--noise-temp-C", min=0.0, metavar="CELSIUS",
                                                 help="drum-temperature noise σ of the instrument [°C] (default: "
                                                      "estimated from the data)"),
) -> None:
    """Calibrate μ_d, h and each test's T_0, select catalogue effects forward (BIC and K-fold
    cross-validation by test), and say which effects are missing (or 'none') with the evidence."""
    from rollaway.api import diagnose as run

    from rollaway.cli.output import REPORT_FORMATS
    from rollaway.errors import check_choice
    check_choice(fmt, REPORT_FORMATS, "--format")
    prepare_outputs(report=report, json_out=json_out, save_model=save_model)
    load_plugins(effect_file)
    diag = run(load_data(data), params=params, noise_torque_Nm=noise_torque_Nm or None, noise_temp_C=noise_temp_C or None)
    write_outputs(diag, report=report, json_out=json_out, fmt=fmt)
    if save_model:
        typer.echo(f"model: {diag.save_model(save_model)} (paper chain + the verdict's effects; use it with --params)")


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
