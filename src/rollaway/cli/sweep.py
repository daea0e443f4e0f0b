"""``rollaway sweep SWEEP.toml``: map where a design holds and where it rolls away (:func:`rollaway.sweep`)."""
from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from rollaway.cli import options as opt

from rollaway.cli.output import REPORT_FORMATS, echo_json
from rollaway.errors import UserError, check_choice


def summary_dict(res) -> dict:
    """The sweep's outcome as data: counts per verdict, failures, disagreements, files."""
    t = res.table
    return {"points": res.n_points, "hold": int((t["verdict"] == "hold").sum()),
            "roll": int((t["verdict"] == "roll").sum()), "failed": res.n_failed,
            "simulated": int(t["simulated"].sum()), "simulated_now": res.n_run, "resumed": res.n_resumed,
            "disagree": res.n_disagree, "wall_time_s": res.wall_time_s, "files": [str(f) for f in res.files]}


def _summary(res) -> None:
    t = res.table
    n_sim = int(t["simulated"].sum())
    typer.echo(f"{res.n_points} points: {int((t['verdict'] == 'hold').sum())} hold, "
               f"{int((t['verdict'] == 'roll').sum())} roll away, {res.n_failed} failed; "
               f"{n_sim} simulated in MuJoCo ({res.n_run} now, {res.n_resumed} from an earlier run)")
    if res.n_disagree:
        typer.echo(f"{res.n_disagree} points where the paper's 1D check disagrees (see the 'disagreement' column), e.g.:")
        for text in t.loc[t["agree"] == False, "disagreement"].drop_duplicates().head(3):  # noqa: E712
            typer.echo(f"  - {text}")
    if res.n_failed:
        first = t.loc[t["error"] != "", "error"].iloc[0]
        typer.echo(f"warning: {res.n_failed} points failed (see the 'error' column), e.g.: {first}", err=True)
    typer.echo(f"wall time {res.wall_time_s:.1f} s ({res.n_points / max(res.wall_time_s, 1e-9):.0f} points/s)")
    for f in res.files:
        typer.echo(f"wrote {f}")


def sweep(
    spec_path: str = typer.Argument(..., metavar="SWEEP_TOML", help="sweep spec (see scenarios/sweeps/)"),
    out: Optional[str] = typer.Option(None, "--out", metavar="FOLDER", help="output folder (default: ./<spec name>-results); "
                                      "rerun with the same folder to continue an interrupted sweep"),
    workers: Optional[int] = typer.Option(None, "--workers", metavar="N", help="local worker processes (default: every core)"),
    dask: Optional[str] = typer.Option(None, "--dask", metavar="ADDRESS",
                                       help="send the simulations to this dask.distributed scheduler, "
                                            "e.g. tcp://10.0.0.5:8786"),
    simulate: Optional[str] = typer.Option(None, "--simulate", metavar="MODE", help="band | all | none (default: the spec's, band)"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
    no_plots: bool = typer.Option(False, "--no-plots", help="skip the PNG maps and design chart"),
    retry_failed: bool = typer.Option(False, "--retry-failed", help="simulate again the points that failed before"),
    params: Optional[str] = opt.params_option("drum model of every point: a set name, parameter "
                                         "file or model file (.toml); replaces the base's set, keeps its T_0"),
    uncertainty: Optional[int] = opt.uncertainty_option("add each point's roll-away probability "
                                              "from N draws of the model's covariance (slow: one risk per point)"),
    fmt: str = typer.Option("text", "--format", metavar="FORMAT", help="text | json (the summary on stdout)"),
    fresh: bool = typer.Option(False, "--fresh", help="delete the results of an earlier sweep in --out and start over"),
) -> int:
    """Analytic margin of every point, MuJoCo near the hold/roll boundary; table + maps in the output folder.

    Exit 0 when the sweep completes (failed points are rows with an 'error'), 130 when interrupted.
    """
    from rollaway.api import sweep as run_sweep
    from rollaway.cli.inputs import expect_sweep
    from rollaway.sweep import load_sweep
    from rollaway.sweep.spec import SIMULATE_MODES

    if simulate is not None:
        check_choice(simulate, SIMULATE_MODES, "--simulate mode")
    if workers is not None and workers < 1:
        raise UserError(f"--workers {workers} must be ≥ 1 (default: one per core)")
    if workers is not None and dask:
        raise UserError("--workers sets local processes; with --dask the cluster's workers run the points — "
                        "give one or the other")
    check_choice(fmt, REPORT_FORMATS, "--format")
    if simulate == "none":
        opt.only_with("--simulate band or all (the MuJoCo runs)", **{"--workers": workers, "--dask": dask,
                                                                   "--retry-failed": retry_failed})
    expect_sweep(spec_path)
    spec = load_sweep(spec_path)
    out_dir = Path(out) if out else Path(f"{spec.name}-results")
    log = (lambda msg: None) if quiet else (lambda msg: typer.echo(msg, err=True))
    res = run_sweep(spec, out_dir, model=params, workers=workers, dask_address=dask, simulate=simulate, progress=not quiet,
                    plots=not no_plots, retry_failed=retry_failed, fresh=fresh, log=log, uncertainty=uncertainty)
    if res.interrupted:
        done = int(res.table["simulated"].sum())
        typer.echo(f"interrupted: {res.n_run} simulations finished this run, {done} of {res.n_to_simulate} in "
                   f"total are in {out_dir}; run the same command again to continue", err=True)
        return 130
    if fmt == "json":
        echo_json(summary_dict(res))
    else:
        _summary(res)
    return 0


def register(app: typer.Typer) -> None:
    app.command("sweep")(sweep)
