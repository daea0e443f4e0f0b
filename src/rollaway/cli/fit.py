"""``rollaway fit``: refit with effects added and watch the error fall (the error ladder; :func:`rollaway.fit`)."""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.identify_common import DATA_HELP, FORMAT_HELP, columns_option, manifest_option, window_option, load_data, load_plugins, prepare_outputs, parse_effects, write_outputs


def fit(
    data: str = typer.Argument(..., metavar="DATA", help=DATA_HELP),
    effect: List[str] = typer.Option(..., "--effect", metavar="EFFECT", help="effect to add: NAME or NAME=param=start,... "
                                                           "(repeatable, in ladder order)"),
    params: Optional[str] = opt.params_option(),
    effect_file: List[str] = typer.Option([], "--effect-file", metavar="FILE", help="Python file defining Effect subclasses"),
    plot: Optional[str] = typer.Option(None, "--plot", metavar="FILE", help="draw the ladder and before/after curves to this PNG"),
    report: Optional[str] = typer.Option(None, "--report", metavar="FILE", help="write a self-contained HTML report here"),
    json_out: Optional[str] = typer.Option(None, "--json", metavar="FILE", help="write the ladder and parameters as JSON here"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help=FORMAT_HELP),
    columns: List[str] = columns_option(),
    manifest: Optional[str] = manifest_option(),
    window_s: Optional[float] = window_option(),
    save_model: Optional[str] = opt.SAVE_MODEL,
) -> None:
    """Error ladder: paper defaults → calibrated baseline → + each effect (each rung calibrated), with the
    fitted parameters, 95 % intervals and bound warnings."""
    from rollaway.api import fit as run

    from rollaway.cli.output import REPORT_FORMATS
    from rollaway.errors import check_choice
    check_choice(fmt, REPORT_FORMATS, "--format")
    prepare_outputs(report=report, json_out=json_out, plot=plot, save_model=save_model)
    load_plugins(effect_file)
    effects = parse_effects(effect)
    d = load_data(data, columns, manifest, window_s)
    start = {f"{n}.{k}": v for n, vals in effects.items() for k, v in vals.items()}
    ladder = run(d, list(effects), params=params, start=start)
    write_outputs(ladder, report=report, json_out=json_out, plot=plot, fmt=fmt)
    if save_model:
        typer.echo(f"model: {ladder.save_model(save_model, data)} (use it with --params)")


def register(app: typer.Typer) -> None:
    app.command("fit")(fit)
