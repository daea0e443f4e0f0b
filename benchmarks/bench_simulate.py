"""Speed with honesty: run each scenario in the fast (event-driven) and fixed-step modes.

    python benchmarks/bench_simulate.py                   # every scenarios/*.toml
    python benchmarks/bench_simulate.py scenarios/hot-parking-1h.toml --repeat 3

Prints, per scenario: both verdicts, wall times (best of --repeat for the fast mode), their
ratio, the roll-away times and their difference (target ≤ 1 s), and the displacement of
held cars in the fixed run (the creep over the whole duration, target ≤ 1 mm per hour).
Both modes use the same model, 1 ms step and 20 ms brake update; the fixed mode integrates
every step.  Wall times are also printed in reference units (benchmarks/reference.py, the
time of 300 000 raw mj_step calls of a plain car, measured in the same run).  Exit code 1 if a verdict differs or a roll-away time differs by more than 1 s.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from rollaway.hold.scenario import load_scenario
from rollaway.sim import simulate

ROOT = Path(__file__).resolve().parents[1]


def _fmt(v, spec=".3f"):
    return "-" if v is None else format(v, spec)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenarios", nargs="*", type=Path, help="scenario TOML files (default: scenarios/*.toml)")
    ap.add_argument("--repeat", type=int, default=3, help="fast-mode repetitions, best wall time is shown")
    args = ap.parse_args(argv)
    files = args.scenarios or sorted((ROOT / "scenarios").glob("*.toml"))
    head = (f"{'scenario':24s} {'duration_s':>10s} {'fast':>10s} {'fixed':>10s} {'fast_wall_s':>11s} "
            f"{'fixed_wall_s':>12s} {'ratio':>7s} {'t_roll_fast':>11s} {'t_roll_fixed':>12s} {'diff_s':>8s} "
            f"{'fixed_creep_mm':>14s}")
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from reference import reference_unit_s
    unit = reference_unit_s()
    print(f"reference unit: {unit:.3f} s (300 000 raw mj_step of a plain car); wall times also in units")
    print(head + f" {'fast_units':>10s} {'fixed_units':>11s}")
    bad = 0
    for f in files:
        s = load_scenario(f)
        fast = min((simulate(s, mode="fast") for _ in range(max(args.repeat, 1))), key=lambda r: r.wall_time_s)
        fixed = simulate(s, mode="fixed")
        diff = None
        if fast.rollaway_time_s is not None and fixed.rollaway_time_s is not None:
            diff = fast.rollaway_time_s - fixed.rollaway_time_s
        ok = fast.outcome == fixed.outcome and (diff is None or abs(diff) <= 1.0)
        bad += not ok
        creep = fixed.max_displacement_m * 1e3 if fixed.outcome == "held" else None
        print(f"{s.name:24s} {s.duration_s:10.0f} {fast.outcome:>10s} {fixed.outcome:>10s} "
              f"{fast.wall_time_s:11.3f} {fixed.wall_time_s:12.2f} {fixed.wall_time_s / fast.wall_time_s:7.0f} "
              f"{_fmt(fast.rollaway_time_s):>11s} {_fmt(fixed.rollaway_time_s):>12s} {_fmt(diff, '+.4f'):>8s} "
              f"{_fmt(creep, '.4f'):>14s} {fast.wall_time_s / unit:10.4f} {fixed.wall_time_s / unit:11.3f}"
              f"{'' if ok else '  MISMATCH'}", flush=True)
    print("all verdicts agree, roll-away times within 1 s" if not bad else f"{bad} scenario(s) disagree")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
