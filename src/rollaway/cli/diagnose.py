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
    save_model: Optional[str] = typer.Option(None, "--save-model", metavar="FILE.toml",
                                             help="write the calibrated model (effects, fitted values, covariance, "
                                                  "provenance) for --params of every command"),
) -> None:
    """Calibrate μ_d and h, fit every catalogue effect jointly, rank by BIC and leave-one-test-out
    cross-validation, and say which effect is missing (or 'none') with the evidence."""
    from rollaway.identify.diagnose import diagnose as run

    prepare_outputs(report=report, json_out=json_out, save_model=save_model)
    load_plugins(effect_file)
    diag = run(load_data(data), params)
    write_outputs(diag, report=report, json_out=json_out)
    if save_model:
        from rollaway.identify.export import save_fit
        typer.echo(f"model: {save_fit(diag.refined, save_model, data, 'diagnose')} (paper chain + the verdict's "
                   f"effects; use it with --params)")


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
