"""Held-out accuracy of the fleet-risk rates: populations the risk code was not written against.

    python benchmarks/check_risk_heldout.py [--seeds N] [--method auto]

Truths from ``tests/risk/heldout_truths.py`` (the hold package's closed forms, scipy roots and
quadrature; no rollaway.risk code).  Prints per case: the truth, the method used, how many of the N
seeds' 95 % intervals hold the truth, the median and worst relative error, the median relative
half-width, the cars evaluated and the median wall time.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))


def cases():
    from scipy import optimize, stats

    from tests.risk.heldout_truths import BASE, fails_margin, force_threshold, rate_force_and, rate_one

    z6 = float(stats.norm.isf(1e-6))
    out = []
    base = {**BASE, "mu_drum": 0.4}
    out.append(("F normal tail, 1 ppm", base,
                {"hand_force_N": {"normal": [force_threshold(base) + z6 * 35, 35]}}, None, 1e-6))
    mu_star = optimize.brentq(lambda m: float(fails_margin({"mu_drum": m}).ravel()[0]), 0.05, 1.0, xtol=1e-14)
    out.append(("μ_d uniform from a lower spec limit, 1 ppm", BASE,
                {"mu_drum": {"uniform": [(mu_star - 0.6e-6) / (1 - 1e-6), 0.6]}}, None, 1e-6))
    for d in ("uphill", "both"):
        b = {**BASE, "hand_force_N": 300, "direction": d}
        sd = optimize.brentq(lambda s: np.log(rate_one("grade_pct", {"normal": [0, s]}, b)) - np.log(1e-6),
                             3, 12, xtol=1e-6)
        out.append((f"grade N(0, {sd:.2f}) facing {d}: fails at both ends", b,
                    {"grade_pct": {"normal": [0, sd]}}, None, rate_one("grade_pct", {"normal": [0, sd]}, b)))
    mu, f = {"uniform": [0.33, 0.6]}, {"normal": [420, 40]}
    for rho in (0.0, -0.5, 0.6):
        corr = [{"between": ["mu_drum", "hand_force_N"], "rho": rho}] if rho else None
        out.append((f"μ_d uniform, F normal, ρ = {rho}", BASE, {"mu_drum": mu, "hand_force_N": f}, corr,
                    rate_force_and("mu_drum", mu, f, BASE, rho)))
    occ = {"choice": [0, 1, 2, 3, 4, 5], "weights": [.3, .3, .2, .1, .05, .05]}
    b = {**BASE, "direction": "both", "mu_drum": 0.4}
    w = np.array(occ["weights"])
    th = [force_threshold({**b, "occupants": o}) for o in occ["choice"]]
    mean = optimize.brentq(lambda m: np.log(np.dot(w, stats.norm.cdf((np.array(th) - m) / 30))) - np.log(1e-6),
                           250, 500)
    out.append(("occupants choice + F normal, both", b, {"occupants": occ, "hand_force_N": {"normal": [mean, 30]}},
                None, float(np.dot(w, stats.norm.cdf((np.array(th) - mean) / 30)))))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=40)
    ap.add_argument("--method", default="auto")
    args = ap.parse_args()
    from rollaway.risk.estimators import estimate
    from rollaway.risk.population import population_from_mapping

    print("| case | truth | method | intervals holding the truth | error: median / worst | half-width | cars | s/run |")
    print("|---|---|---|---|---|---|---|---|")
    for label, base, vary, corr, truth in cases():
        pop = population_from_mapping({**base, "vary": vary, **({"correlation": corr} if corr else {})},
                                      where="heldout.toml")
        rows = []
        for s in range(args.seeds):
            t0 = time.perf_counter()
            e = estimate(pop, args.method, 1_000_000, s)
            lo, hi = e.total.ci95
            rows.append((e.total.probability / truth - 1, lo <= truth <= hi, (hi - lo) / 2 / truth, e.samples,
                         time.perf_counter() - t0))
        r = np.array(rows, float)
        print(f"| {label} | {truth:.4g} | `{e.method}` | {int(r[:, 1].sum())} / {args.seeds} | "
              f"{np.median(np.abs(r[:, 0])):.1%} / {np.max(np.abs(r[:, 0])):.1%} | {np.median(r[:, 2]):.1%} | "
              f"{int(np.mean(r[:, 3]))} | {np.median(r[:, 4]):.2f} |", flush=True)


if __name__ == "__main__":
    main()
