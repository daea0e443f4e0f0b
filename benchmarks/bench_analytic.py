"""Benchmark: the analytic pass of large sweeps, and the 2 000 000-point sweep's time and memory.

    python benchmarks/bench_analytic.py [--points 1000000] [--full]

Prints the wall time of the point ids and of the analytic pass over ``--points`` points, each as
a ratio to a reference measured in the same run (``np.sort`` of as many random floats), so the
figures compare across machines.  ``--full`` also runs ``rollaway sweep`` on the documented
maximum (2 000 000 points, ``simulate = "none"``, plots included) in a child process and prints
its wall time and peak memory (targets here: ≤ 30 s, ≤ 1 GB).
"""
from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

BIG = """base_preset = "fmvss135"
simulate = "none"
[grid]
grade_pct = { start = 0, stop = 50, num = 1000 }
hand_force_N = { start = 100, stop = 600, num = 1000 }
"""


def best_of(fn, repeat=3) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--full", action="store_true", help="also time the 2e6-point sweep through the CLI")
    args = ap.parse_args()

    from rollaway.hold.scenario import preset_scenarios
    from rollaway.sweep.analytic import analytic_pass
    from rollaway.sweep.spec import grid_spec, point_ids

    base = preset_scenarios("fmvss135")[0]
    n_force = max(args.points // 2000, 1)
    spec = grid_spec(base, {"grade_pct": {"start": 0, "stop": 50, "num": 1000},
                            "hand_force_N": {"start": 100, "stop": 600, "num": n_force},
                            "direction": ["uphill", "downhill"]}, simulate="none")
    n = len(spec.points)
    x = np.random.default_rng(0).random(n)
    ref = best_of(lambda: np.sort(x))
    ids = best_of(lambda: point_ids(base, spec.points))
    ana = best_of(lambda: analytic_pass(base, spec.points, spec.band))
    print(f"{n} points; reference np.sort: {ref * 1000:.0f} ms")
    print(f"point ids:     {ids * 1000:6.0f} ms = {ids / ref:5.1f} x reference")
    print(f"analytic pass: {ana * 1000:6.0f} ms = {ana / ref:5.1f} x reference")
    if args.full:
        with tempfile.TemporaryDirectory() as d:
            (Path(d) / "big.toml").write_text(BIG)
            t = time.perf_counter()
            subprocess.run([sys.executable, "-m", "rollaway", "sweep", str(Path(d) / "big.toml"), "--out",
                            str(Path(d) / "out"), "--quiet"], check=True, stdout=subprocess.DEVNULL)
            wall = time.perf_counter() - t
            peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
        print(f"2 000 000-point sweep (CLI, plots included): {wall:.1f} s = {wall / ref:.0f} x reference, "
              f"peak memory {peak_mb:.0f} MB")


if __name__ == "__main__":
    main()
