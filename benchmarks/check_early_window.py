"""Check: ending the classification window early changes no label and no roll-away time.

    python benchmarks/check_early_window.py [--n 300] [--seed 0]

Draws --n points from the boundary band of the 10 000-point benchmark grid
(benchmarks/bench_sweep.py) plus combined-limit points (random grade, occupants, facing, brake
margin 0.9–1.5 and tyre margin 0.9–1.1), simulates each with the early end
(``simulate(s)``) and with the full window (``simulate(s, full_window=True)``), and prints how
many outcomes and roll-away times (to 1 µs) differ, and the integrated time of both.
Exit code 1 on any difference.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))


def band_points(n: int, rng) -> list:
    from bench_sweep import GRID
    from rollaway.hold.scenario import preset_scenarios
    from rollaway.sweep import grid_spec
    from rollaway.sweep.analytic import analytic_pass, point_changes
    from rollaway.sweep.runner import select_for_simulation
    spec = grid_spec(preset_scenarios("fmvss135")[0], GRID, simulate="band", band=(0.95, 1.08), source="early")
    band = select_for_simulation(analytic_pass(spec.base, spec.points, spec.band), "band")
    rows = [r._asdict() for r in band.itertuples(index=False)]
    return [spec.base.replace(**point_changes(rows[i])) for i in rng.choice(len(rows), min(n, len(rows)), replace=False)]


def combined_points(n: int, rng) -> list:
    from rollaway.hold import min_brake_margin, tyre_adhesion_margin
    from rollaway.hold.scenario import preset_scenarios
    base = preset_scenarios("fmvss135")[0].replace(duration_s=30.0, initial_drum_temp_C=27.0)
    out = []
    for _ in range(n):
        g, occ = float(rng.uniform(5, 50)), int(rng.integers(0, 6))
        d = str(rng.choice(["downhill", "uphill"]))
        s = base.replace(grade_pct=g, occupants=occ, direction=d)
        m1, m2 = (float(min_brake_margin(s.params, f, g, d, occ, 30.0, initial_temp_C=27.0)) for f in (300, 400))
        f = 300 + (rng.uniform(0.9, 1.5) - m1) * 100 / (m2 - m1)
        tam = float(tyre_adhesion_margin(s.params, g, d, occ))
        out.append(s.replace(hand_force_N=max(f, 0.0),
                             tyre_road_mu=s.params.tyre_road_mu * rng.uniform(0.9, 1.1) / tam))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=300, help="points in all (half band, half combined limits)")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    from rollaway.sim import simulate
    rng = np.random.default_rng(args.seed)
    points = band_points(args.n // 2, rng) + combined_points(args.n - args.n // 2, rng)
    diff, t_early, t_full, counts = 0, 0.0, 0.0, {}
    for s in points:
        early, full = simulate(s), simulate(s, full_window=True)
        t_early += early.integrated_time_s
        t_full += full.integrated_time_s
        counts[full.outcome] = counts.get(full.outcome, 0) + 1
        same_t = (early.rollaway_time_s is None) == (full.rollaway_time_s is None) and \
            (early.rollaway_time_s is None or abs(early.rollaway_time_s - full.rollaway_time_s) < 1e-6)
        if early.outcome != full.outcome or not same_t:
            diff += 1
            print(f"DIFFERS {s.grade_pct:.2f}% {s.direction} occ {s.occupants} F {s.hand_force_N:.1f} "
                  f"mu_r {s.tyre_road_mu:.4f}: early {early.outcome} {early.rollaway_time_s} full {full.outcome} "
                  f"{full.rollaway_time_s} (slip {early.slip_ratio} / {full.slip_ratio})")
    print(f"points {len(points)}  outcomes (full window) {counts}")
    print(f"labels or roll-away times differing: {diff}")
    print(f"integrated time: early {t_early:.1f} s, full window {t_full:.1f} s ({t_early / t_full:.2f}×)")
    return 1 if diff else 0


if __name__ == "__main__":
    sys.exit(main())
