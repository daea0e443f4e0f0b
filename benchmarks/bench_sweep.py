"""Benchmark: a 10 000-point sweep, analytic everywhere, MuJoCo on the boundary band.

    python benchmarks/bench_sweep.py [--workers N] [--dask ADDRESS] [--out DIR]

Grid: grade 0–48 % (25) × occupants 1–5 (5) × hand force 150–600 N (20) × facing up/downhill (2)
× μ_d 0.35/0.45 (2) = 10 000 points on the FMVSS 135 base (300 s hold from 200 °C).  Starts
from an empty output folder (no resume) and prints wall time and points per second.
Target on a 2-core machine: ≤ 2 minutes.
"""
from __future__ import annotations

import argparse
import os
import shutil
import tempfile
import time

GRID = {"grade_pct": {"start": 0, "stop": 48, "num": 25}, "occupants": [1, 2, 3, 4, 5],
        "hand_force_N": {"start": 150, "stop": 600, "num": 20}, "direction": ["uphill", "downhill"],
        "mu_drum": [0.35, 0.45]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=None, help="local processes (default: every core)")
    ap.add_argument("--dask", default=None, help="dask.distributed scheduler address")
    ap.add_argument("--out", default=None, help="output folder (default: a temporary one, deleted)")
    ap.add_argument("--plots", action="store_true", help="also draw the plots (not timed by default)")
    ap.add_argument("--band", type=float, nargs=2, default=(0.95, 1.08), metavar=("LOW", "HIGH"),
                    help="margin band simulated in MuJoCo (default: the sweep default, 0.95 1.08)")
    args = ap.parse_args()

    import sys
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from reference import reference_unit_s
    unit = reference_unit_s()
    t_import = time.perf_counter()
    from rollaway.hold.scenario import preset_scenarios
    from rollaway.sweep import grid_spec, run_sweep
    import sys
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from reference import reference_unit_s
    unit = reference_unit_s()
    t_import = time.perf_counter() - t_import

    spec = grid_spec(preset_scenarios("fmvss135")[0], GRID, simulate="band", band=tuple(args.band),
                      source="bench-10k")
    out = args.out or tempfile.mkdtemp(prefix="rollaway-bench-")
    shutil.rmtree(out, ignore_errors=True)
    res = run_sweep(spec, out, workers=args.workers, dask_address=args.dask, plots=args.plots, progress=True)
    t = res.table
    n_sim = int(t["simulated"].sum())
    sim_wall = t.loc[t["simulated"], "wall_time_s"]
    print(f"points                 {res.n_points}")
    print(f"cores                  {os.cpu_count()}  workers {args.workers or ('dask' if args.dask else os.cpu_count())}")
    print(f"analytic pass          {res.analytic_wall_s * 1000:.1f} ms for all {res.n_points} points")
    print(f"simulated (band {spec.band[0]:g}–{spec.band[1]:g})  {n_sim} points "
          f"({100 * n_sim / res.n_points:.1f} %), {sim_wall.mean() * 1000:.0f} ms each on average")
    print(f"failed                 {res.n_failed}")
    dis = t["simulated"] & ((t["analytic_outcome"] == "held") != (t["sim_outcome"] == "held"))
    print(f"MuJoCo vs analytic (brake + tyres) verdicts differ at {int(dis.sum())} points, smaller margin in "
          f"[{t.loc[dis, 'margin'].min():.4f}, {t.loc[dis, 'margin'].max():.4f}]" if dis.any() else
          "MuJoCo and the analytic check (brake + tyres) agree at every simulated point")
    print(f"paper's check disagrees {res.n_disagree}")
    print(f"wall time              {res.wall_time_s:.1f} s (+ {t_import:.1f} s imports)")
    print(f"points per second      {res.n_points / res.wall_time_s:.0f}")
    print(f"reference unit         {unit:.2f} s (300 000 raw mj_step of a plain car, this run)")
    print(f"sweep in units         {res.wall_time_s / unit:.1f}  (target ≤ 15)")
    print(f"simulations per second {n_sim / res.wall_time_s:.1f}")
    if not args.out:
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
