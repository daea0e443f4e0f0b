"""Run a sweep: analytic pass over every point, MuJoCo where asked, results safe on disk.

1. The analytic pass computes every point at once (:mod:`rollaway.sweep.analytic`).
2. The points to simulate are chosen by the spec's mode: ``band`` (near the boundary),
   ``all`` or ``none``.  Those already in the output folder's journal are skipped: a rerun
   continues an interrupted sweep.
3. The rest go to an executor (local processes or Dask); each finished point is journalled
   at once; the table is written before the first simulation, consolidated every
   ``CONSOLIDATE_EVERY_S``, at the end and on Ctrl-C or SIGTERM.

The output folder is locked for the run and fingerprinted (:mod:`rollaway.sweep.folder`).
"""
from __future__ import annotations

import json
import signal
import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from rollaway.sweep.analytic import analytic_pass, point_changes, with_rollaway_probability
from rollaway.sweep.executors import make_executor, make_task, scenario_to_dict
from rollaway.sweep.folder import FolderLock, check_fingerprint, clear_outputs, fingerprint
from rollaway.sweep.spec import SweepSpec, point_hashes
from rollaway.sweep.store import Journal, drop_records, write_table
from rollaway.sweep.table import build_table

CONSOLIDATE_EVERY_S = 30.0


@dataclass
class SweepResult:
    table: pd.DataFrame
    out_dir: Path
    n_points: int
    n_to_simulate: int
    n_resumed: int            # simulations found in the journal (not run again)
    n_run: int                # simulations run now
    wall_time_s: float
    analytic_wall_s: float
    interrupted: bool = False
    files: list[Path] = field(default_factory=list)

    @property
    def n_failed(self) -> int:
        return int((self.table["error"] != "").sum())

    @property
    def n_disagree(self) -> int:
        return int((self.table["agree"] == False).sum())  # noqa: E712

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import sweep_html
        return sweep_html(self)


def select_for_simulation(analytic: pd.DataFrame, mode: str) -> pd.DataFrame:
    ok = analytic["error"] == ""
    if mode == "none":
        return analytic.iloc[0:0]
    if mode == "all":
        return analytic[ok]
    return analytic[ok & analytic["in_band"]]


@contextmanager
def _sigterm_as_interrupt():
    """SIGTERM (a polite kill) takes the Ctrl-C path: cancel, journal, consolidate."""
    def handler(signum, frame):
        raise KeyboardInterrupt
    try:
        old = signal.signal(signal.SIGTERM, handler)
    except ValueError:  # not the main thread
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)


class _Progress:
    """A rich progress bar with ETA on stderr; silent when quiet or not a terminal."""

    def __init__(self, total: int, enabled: bool):
        self.bar = None
        if enabled and total and sys.stderr.isatty():
            from rich.console import Console
            from rich.progress import (BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn,
                                       TimeRemainingColumn)
            self.bar = Progress(TextColumn("simulating"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                                TextColumn("ETA"), TimeRemainingColumn(), console=Console(stderr=True),
                                transient=False)
            self.task = self.bar.add_task("sim", total=total)
            self.bar.start()

    def advance(self) -> None:
        if self.bar is not None:
            self.bar.advance(self.task)

    def stop(self) -> None:
        if self.bar is not None:
            self.bar.stop()


def _write_manifest(spec: SweepSpec, out: Path, n_sim: int) -> None:
    man = {"sweep": str(spec.source), "description": spec.description, "base": spec.base.name,
           "parameter_set": spec.base.params.name, "simulate": spec.simulate, "band": list(spec.band),
           "n_points": len(spec.points), "n_to_simulate": n_sim}
    (out / "manifest.json").write_text(json.dumps(man, indent=1) + "\n", encoding="utf-8")


def run_sweep(spec: SweepSpec, out_dir: str | Path, *, workers: int | None = None, dask_address: str | None = None,
              simulate: str | None = None, progress: bool = True, simulate_fn=None, plots: bool = True,
              retry_failed: bool = False, fresh: bool = False, log=None,
              uncertainty: int | None = None) -> SweepResult:
    """Run *spec*, writing into *out_dir*; resumes from the journal already there.

    The folder is locked for the run (a second sweep into it is refused) and must hold this
    spec's points or nothing (:mod:`rollaway.sweep.folder`); *fresh* deletes what it holds first.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with FolderLock(out):
        if fresh:
            clear_outputs(out)
        check_fingerprint(out, fingerprint(point_hashes(spec.base, spec.points)), spec.source, len(spec.points))
        return _run_locked(spec, out, workers=workers, dask_address=dask_address, simulate=simulate,
                           progress=progress, simulate_fn=simulate_fn, plots=plots, retry_failed=retry_failed,
                           log=log or (lambda msg: None), uncertainty=uncertainty)


def _run_locked(spec: SweepSpec, out: Path, *, workers, dask_address, simulate, progress, simulate_fn, plots,
                retry_failed, log, uncertainty=None) -> SweepResult:
    start = time.perf_counter()
    t0 = time.perf_counter()
    analytic = analytic_pass(spec.base, spec.points, spec.band)
    if uncertainty:
        analytic = with_rollaway_probability(analytic, spec.base, uncertainty)
    analytic_wall = time.perf_counter() - t0
    to_sim = select_for_simulation(analytic, simulate or spec.simulate)
    _write_manifest(spec, out, len(to_sim))

    journal = Journal(out)
    records = journal.load()
    if journal.damaged:
        log(f"{out / 'journal.jsonl'}: dropped {journal.damaged} damaged line(s); their points are simulated again")
    if retry_failed:
        failed = {pid for pid, r in records.items() if r.get("error")}
        drop_records(out, failed)
        records = {pid: r for pid, r in records.items() if pid not in failed}
    todo = to_sim[~to_sim["point_id"].isin(records.keys())]
    n_resumed = len(to_sim) - len(todo)
    log(f"{len(analytic)} points (analytic pass {analytic_wall * 1000:.0f} ms); {len(to_sim)} to simulate"
        + (f", {n_resumed} already done (resuming)" if n_resumed else ""))

    if len(todo):       # a table from the start: a run killed before the first consolidation still leaves one
        write_table(build_table(analytic, records, analytic_wall), out)
    base = scenario_to_dict(spec.base)
    tasks = (make_task(r.point_id, base, point_changes(r._asdict())) for r in todo.itertuples(index=False))
    interrupted, n_run = False, 0
    bar = _Progress(len(todo), progress)
    executor = make_executor(len(todo), workers, dask_address, simulate_fn) if len(todo) else None
    last = time.perf_counter()

    def record(rec: dict) -> None:
        nonlocal n_run, last
        if rec["point_id"] in records:
            return
        journal.append(rec)
        records[rec["point_id"]] = rec
        n_run += 1
        bar.advance()
        if time.perf_counter() - last > CONSOLIDATE_EVERY_S:
            write_table(build_table(analytic, records, analytic_wall), out)
            last = time.perf_counter()

    try:
        with _sigterm_as_interrupt():
            if executor is not None:
                for rec in executor.run(tasks):
                    record(rec)
    except KeyboardInterrupt:
        interrupted = True
        if executor is not None:
            executor.cancel()
            for rec in executor.finished():
                record(rec)
    finally:
        bar.stop()
        if executor is not None:
            executor.close()
        journal.close()
    if interrupted:     # a Ctrl-C between a journal line and its record: the journal on disk is the truth
        records.update({k: v for k, v in Journal(out).load().items() if k not in records})

    table = build_table(analytic, records, analytic_wall)
    files = list(write_table(table, out))
    if plots and not interrupted:
        from rollaway.sweep.plots import make_plots
        files += make_plots(table, spec, out / "plots")
    return SweepResult(table=table, out_dir=out, n_points=len(table), n_to_simulate=len(to_sim),
                       n_resumed=n_resumed, n_run=n_run, wall_time_s=time.perf_counter() - start,
                       analytic_wall_s=analytic_wall, interrupted=interrupted, files=files)
