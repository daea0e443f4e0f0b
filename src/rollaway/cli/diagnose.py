"""``rollaway diagnose``: which physical effect is the paper's model missing?"""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.identify_common import DATA_HELP, FORMAT_HELP, columns_option, manifest_option, window_option, load_data, load_plugins, prepare_outputs, write_outputs


def diagnose(
    data: str = typer.Argument(..., metavar="DATA", help=DATA_HELP),
    params: Optional[str] = opt.params_option(),
    effect_file: List[str] = typer.Option([], "--effect-file", metavar="FILE", help="Python file with extra candidate effects"),
    json_out: Optional[str] = typer.Option(None, "--json", metavar="FILE", help="write the diagnosis as JSON here"),
    report: Optional[str] = typer.Option(None, "--report", metavar="FILE", help="write a self-contained HTML report here"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help=FORMAT_HELP),
    columns: List[str] = columns_option(),
    manifest: Optional[str] = manifest_option(),
    window_s: Optional[float] = window_option(),
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
    from rollaway.identify.diagnose import diagnose as run

    from rollaway.cli.output import REPORT_FORMATS
    from rollaway.errors import check_choice
    check_choice(fmt, REPORT_FORMATS, "--format")
    prepare_outputs(report=report, json_out=json_out, save_model=save_model)
    load_plugins(effect_file)
    diag = run(load_data(data, columns, manifest, window_s), params, noise_torque_Nm=noise_torque_Nm or None, noise_temp_C=noise_temp_C or None)
    write_outputs(diag, report=report, json_out=json_out, fmt=fmt)
    if save_model:
        from rollaway.identify.export import save_fit
        typer.echo(f"model: {save_fit(diag.refined, save_model, data, 'diagnose')} (paper chain + the verdict's "
                   f"effects; use it with --params)")


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
