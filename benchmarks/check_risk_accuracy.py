"""Measured accuracy of the fleet-risk estimators on reference cases with truths computed independently.

    python benchmarks/check_risk_accuracy.py [--seeds N]

Truths come from root finding and quadrature on the hold check (``tests/risk/truths.py``), never from
rollaway.risk.  Prints, per case and method: the coverage of the 95 % intervals over N seeds, the
median and worst relative error, the median relative half-width and the mean cars evaluated.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
HEAD = ('grade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = {force}\nduration_s = 300\n'
        'initial_drum_temp_C = 200\n')


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=40)
    args = ap.parse_args()
    from rollaway.risk import load_population
    from rollaway.risk.estimators import estimate
    from tests.risk.truths import rate_mu_uniform, rate_two_normals

    cases = [("μ_d uniform [0.3, 0.6], 250 N", HEAD.format(force=250) + "[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n",
              rate_mu_uniform(0.3, 0.6, 250.0), [("mc", 4000)]),
             ("μ_d N(0.42, 0.03), F N(400, 40)", HEAD.format(force=400) +
              "[vary]\nmu_drum = { normal = [0.42, 0.03] }\nhand_force_N = { normal = [400, 40] }\n",
              rate_two_normals(0.42, 0.03, 400.0, 40.0), [("is", 1_000_000), ("subset", 200_000)]),
             ("μ_d N(0.45, 0.037), F N(400, 37)", HEAD.format(force=400) +
              "[vary]\nmu_drum = { normal = [0.45, 0.037] }\nhand_force_N = { normal = [400, 37] }\n",
              rate_two_normals(0.45, 0.037, 400.0, 37.0), [("is", 1_000_000), ("auto", 1_000_000)])]
    with tempfile.TemporaryDirectory() as d:
        for name, text, truth, methods in cases:
            path = Path(d) / "p.toml"
            path.write_text(text, encoding="utf-8")
            pop = load_population(path)
            for method, samples in methods:
                seeds = range(args.seeds if method != "subset" else max(args.seeds // 4, 5))
                es = [estimate(pop, method, samples, seed=s) for s in seeds]
                p = np.array([e.total.probability for e in es])
                lo = np.array([e.total.ci95[0] for e in es])
                hi = np.array([e.total.ci95[1] for e in es])
                cover = np.mean((lo <= truth) & (truth <= hi))
                rel = np.abs(p / truth - 1)
                print(f"{name:34s} truth {truth:.4g}  {method:6s} seeds {len(es):3d}  coverage {cover:5.1%}  "
                      f"error median {np.median(rel):.1%} max {rel.max():.1%}  "
                      f"half-width {np.median((hi - lo) / 2 / truth):.1%}  cars {np.mean([e.samples for e in es]):.0f}")


if __name__ == "__main__":
    main()
