"""``rollaway diagnose``: which physical effect is the paper's model missing?"""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli.identify_common import load_data, load_plugins, prepare_outputs, write_outputs


def diagnose(
    data: str = typer.Argument(..., help="measurement CSV (see 'rollaway compare --help')"),
    params: Optional[str] = typer.Option(None, "--params", help="parameter set name or TOML file (default: paper)"),
    effect_file: List[str] = typer.Option([], "--effect-file", help="Python file with extra candidate effects"),
    json_out: Optional[str] = typer.Option(None, "--json", help="write the diagnosis as JSON here"),
    report: Optional[str] = typer.Option(None, "--report", help="write a self-contained HTML report here"),
    noise_torque_Nm: Optional[float] = typer.Option(None, "--noise-torque-Nm", min=0.0,
                                                    help="torque noise σ of the instrument [N·m] (default: "
                                                         "estimated from the data)"),
    noise_temp_C: Optional[float] = typer.Option(None, "--noise-temp-C", min=0.0,
                                                 help="drum-temperature noise σ of the instrument [°C] (default: "
                                                      "estimated from the data)"),
) -> None:
    """Calibrate μ_d, h and each test's T_0, select catalogue effects forward (BIC and K-fold
    cross-validation by test), and say which effects are missing (or 'none') with the evidence."""
    from rollaway.identify.diagnose import diagnose as run

    prepare_outputs(report=report, json_out=json_out)
    load_plugins(effect_file)
    diag = run(load_data(data), params, noise_torque_Nm=noise_torque_Nm or None, noise_temp_C=noise_temp_C or None)
    write_outputs(diag, report=report, json_out=json_out)


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
