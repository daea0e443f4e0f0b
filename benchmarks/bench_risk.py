"""Benchmark: fleet roll-away rates, in reference units (``benchmarks/reference.py``) measured in the same run.

    python benchmarks/bench_risk.py [--quick]

Cases (speed targets in reference units, docs/fleet-risk.md):

* 10⁶ cars of the paper model, five varied inputs (``scenarios/populations/fmvss135-production.toml``),
  plain Monte Carlo: ≤ 2;
* 10⁶ cars of a calibrated model with two effects (lining creep, friction against temperature), its
  covariance and model error, three varied inputs: ≤ 10;
* a ~1 ppm rate (μ_d ~ N(0.45, 0.037), hand force ~ N(400, 37): 1.19 ppm by quadrature) with a ±30 %
  interval, method auto: ≤ 10.

Each case: best of two wall times, divided by the reference unit.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FMVSS_CASE = """grade_pct = 20
direction = "uphill"
occupants = 5
hand_force_N = 400
duration_s = 300
initial_drum_temp_C = 200
"""
RARE = FMVSS_CASE + """[vary]
mu_drum = { normal = [0.45, 0.037] }
hand_force_N = { normal = [400, 37] }
"""
CALIBRATED = 'params = "model.toml"\n' + FMVSS_CASE + """[vary]
hand_force_N = { normal = [400, 35] }
initial_drum_temp_C = { triangular = [27, 120, 300] }
occupants = { choice = [0, 1, 2, 3, 4, 5], weights = [0.3, 0.4, 0.15, 0.1, 0.03, 0.02] }
"""


def _calibrated_model(folder: Path) -> None:
    import numpy as np

    from rollaway.model.drum_model import Covariance, DrumModel
    from rollaway.model.model_file import save_model
    m = DrumModel("paper", ["lining_creep", "friction_temperature"],
                  {"lining_creep.relaxed_fraction": 0.12, "lining_creep.relaxation_time_s": 900.0,
                   "friction_temperature.mu_slope_per_K": -3e-4},
                  covariance=Covariance(("mu_drum", "lining_creep.relaxed_fraction",
                                         "friction_temperature.mu_slope_per_K"),
                                        np.diag([0.01 ** 2, 0.02 ** 2, 1e-4 ** 2])),
                  predictive={"model_error_rel_sd": 0.03, "model_error_dof": 8})
    save_model(m, folder / "model.toml")
    (folder / "pop.toml").write_text(CALIBRATED, encoding="utf-8")


def best_of(fn, repeat=2):
    out, best = None, float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t)
    return out, best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="10⁵ cars instead of 10⁶ (a smoke run)")
    args = ap.parse_args()
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from reference import reference_unit_s

    from rollaway.risk import load_population
    from rollaway.risk.estimators import estimate

    n = 100_000 if args.quick else 1_000_000
    unit = reference_unit_s()
    print(f"reference unit (300 000 raw mj_step): {unit:.2f} s")
    rows = []
    paper = load_population(ROOT / "scenarios" / "populations" / "fmvss135-production.toml")
    e, t = best_of(lambda: estimate(paper, "mc", n, seed=0))
    rows.append((f"{n} cars, paper model, 5 inputs, mc", t, 2.0, e))
    with tempfile.TemporaryDirectory() as d:
        _calibrated_model(Path(d))
        cal = load_population(Path(d) / "pop.toml")
        e, t = best_of(lambda: estimate(cal, "mc", n, seed=0))
        rows.append((f"{n} cars, calibrated 2-effect model, mc", t, 10.0, e))
        (Path(d) / "rare.toml").write_text(RARE, encoding="utf-8")
        rare = load_population(Path(d) / "rare.toml")
        e, t = best_of(lambda: estimate(rare, "auto", 1_000_000, seed=0))
        rows.append(("~1 ppm (truth 1.19 ppm), auto", t, 10.0, e))
    for name, t, target, e in rows:
        lo, hi = e.total.ci95
        print(f"{name:42s} {t:7.2f} s = {t / unit:5.2f} units (target ≤ {target:g})   "
              f"{e.total.probability * 1e6:10.4g} ppm [{lo * 1e6:.4g}, {hi * 1e6:.4g}] {e.method}, {e.samples} cars")


if __name__ == "__main__":
    main()
