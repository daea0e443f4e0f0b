"""``rollaway compare``: the model against bench measurements, per test and overall, and where it fails."""
from __future__ import annotations

from typing import List, Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.identify_common import DATA_HELP, FORMAT_HELP, columns_option, manifest_option, window_option, load_data, load_plugins, prepare_outputs, parse_effects, write_outputs


def compare(
    data: str = typer.Argument(..., metavar="DATA", help=DATA_HELP),
    params: Optional[str] = opt.params_option(),
    effect: List[str] = typer.Option([], "--effect", metavar="EFFECT", help="add an effect: NAME or NAME=param=value,... "
                                                          "(repeatable; unset parameters take typical values)"),
    effect_file: List[str] = typer.Option([], "--effect-file", metavar="FILE", help="Python file defining Effect subclasses"),
    calibrated: bool = typer.Option(False, "--calibrate", help="fit μ_d, h and the effects' parameters first"),
    report: Optional[str] = typer.Option(None, "--report", metavar="FILE", help="write a self-contained HTML report here"),
    json_out: Optional[str] = typer.Option(None, "--json", metavar="FILE", help="write the errors and findings as JSON here"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help=FORMAT_HELP),
    columns: List[str] = columns_option(),
    manifest: Optional[str] = manifest_option(),
    window_s: Optional[float] = window_option(),
) -> None:
    """Errors of the model (paper defaults unless --calibrate) on both channels, per test and overall:
    RMSE, bias, worst error; residual trends and the tests/time ranges outside the noise band."""
    from rollaway.identify.compare import compare as run

    from rollaway.cli.output import REPORT_FORMATS
    from rollaway.errors import check_choice
    check_choice(fmt, REPORT_FORMATS, "--format")
    if not effect:
        opt.only_with("--effect NAME (compare adds only the effects it is given)", **{"--effect-file": effect_file})
    prepare_outputs(report=report, json_out=json_out)
    load_plugins(effect_file)
    effects = parse_effects(effect)
    cmp = run(load_data(data, columns, manifest, window_s), params, effects, calibrated=calibrated)
    write_outputs(cmp, report=report, json_out=json_out, fmt=fmt)


def register(app: typer.Typer) -> None:
    app.command("compare")(compare)
