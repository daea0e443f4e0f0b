"""``rollaway diagnose``: which physical effect is the paper's model missing? (:func:`rollaway.diagnose`)"""
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
    free: List[str] = typer.Option([], "--free", metavar="NAME",
                                   help="brake parameter to fit (repeat; replaces the automatic choice): mu_drum, "
                                        "u6_slope_m_per_N, u6_offset_m, shoe_arm_ratio, heat_transfer_W_m2K, "
                                        "ambient_temp_C"),
    fix: List[str] = typer.Option([], "--fix", metavar="NAME", help="brake parameter to hold at its value (repeat)"),
    check_calibration: int = typer.Option(0, "--check-calibration", min=0, metavar="N",
                                          help="refit N synthetic campaigns of your test design and print how often "
                                               "the 5-95 % band holds the truth (about 2 s each)"),
) -> None:
    """Calibrate your drum (the brake parameters these data identify, each test's T_0), then select
    catalogue effects forward (BIC and leave-one-test-out prediction) for what it leaves, and say which
    effects are missing (or 'none') with the evidence and an identifiability report."""
    from rollaway.api import diagnose as run

    from rollaway.cli.output import REPORT_FORMATS
    from rollaway.errors import check_choice
    check_choice(fmt, REPORT_FORMATS, "--format")
    for flag, sigma in (("--noise-torque-Nm", noise_torque_Nm), ("--noise-temp-C", noise_temp_C)):
        if sigma is not None and sigma <= 0:
            from rollaway.errors import UserError
            raise UserError(f"{flag} {sigma:g}: the instrument's noise σ must be > 0; leave {flag} out to estimate "
                            f"it from the data")
    prepare_outputs(report=report, json_out=json_out, save_model=save_model)
    load_plugins(effect_file)
    diag = run(load_data(data, columns, manifest, window_s), params=params, noise_torque_Nm=noise_torque_Nm,
               noise_temp_C=noise_temp_C, free=free or None, fix=fix)
    write_outputs(diag, report=report, json_out=json_out, fmt=fmt)
    if check_calibration:
        from rollaway.uncertainty.calibration_check import check_calibration as check, words
        typer.echo(words(check(diag, check_calibration)), err=fmt == "json")
    if save_model:
        typer.echo(f"model: {diag.save_model(save_model, data)} (your drum + the verdict's effects; use it with "
                   f"--params)", err=fmt == "json")


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
