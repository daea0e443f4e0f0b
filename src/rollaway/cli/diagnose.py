"""``rollaway diagnose``: which physical effect is the paper's model missing?"""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli.bench_common import load_plugins


def diagnose(
    data: str = typer.Argument(..., help="measurement CSV (see 'rollaway compare --help')"),
    params: Optional[str] = typer.Option(None, "--params", help="parameter set name or TOML file (default: paper)"),
    effect_file: List[str] = typer.Option([], "--effect-file", help="Python file with extra candidate effects"),
    json_out: Optional[str] = typer.Option(None, "--json", help="write the diagnosis as JSON here"),
    report: Optional[str] = typer.Option(None, "--report", help="write a self-contained HTML report here"),
) -> None:
    """Calibrate μ_d and h, fit every catalogue effect jointly, rank by BIC and leave-one-test-out
    cross-validation, and say which effect is missing (or 'none') with the evidence."""
    from rollaway.bench.diagnose import diagnose as run
    from rollaway.bench.measurements import load_measurements

    load_plugins(effect_file)
    d = load_measurements(data)
    for note in d.notes:
        typer.echo(f"note: {note}", err=True)
    diag = run(d, params)
    typer.echo(diag.summary())
    if json_out:
        diag.to_json(json_out)
        typer.echo(f"json: {json_out}")
    if report:
        diag.report(report)
        typer.echo(f"report: {report}")


def register(app: typer.Typer) -> None:
    app.command("diagnose")(diagnose)
