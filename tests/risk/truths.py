"""Independent truths for the risk tests: root finding and quadrature on the hold check, no rollaway.risk code."""
import numpy as np
from scipy import integrate, optimize, stats

from rollaway.hold import min_brake_margin, tyre_adhesion_margin
from rollaway.model.parameters import paper

CASE = dict(grade_pct=20.0, direction="uphill", occupants=5, duration_s=300.0)


def mu_threshold(force_N: float, temp_C: float = 200.0, case=CASE) -> float:
    """μ_d at which the least brake margin over the hold is exactly 1 (the margin rises with μ_d)."""
    def f(mu):
        return float(min_brake_margin(paper(), force_N, case["grade_pct"], case["direction"], case["occupants"],
                                      case["duration_s"], mu_drum=mu, initial_temp_C=temp_C)) - 1.0
    if f(1.1) < 0:
        return np.inf            # no μ_d below self-locking holds
    if f(1e-3) > 0:
        return 0.0
    return optimize.brentq(f, 1e-3, 1.1, xtol=1e-14)


def rate_mu_uniform(lo: float, hi: float, force_N: float) -> float:
    """Rate with μ_d uniform on [lo, hi] and everything else fixed: the measure of μ below the threshold."""
    return float(np.clip((mu_threshold(force_N) - lo) / (hi - lo), 0.0, 1.0))


def rate_two_normals(mu_mean, mu_sd, f_mean, f_sd) -> float:
    """Rate with μ_d and the hand force independent normals: ∫ P(μ < μ*(F)) φ(F) dF by quadrature."""
    def integrand(f):
        return stats.norm.cdf(mu_threshold(f), mu_mean, mu_sd) * stats.norm.pdf(f, f_mean, f_sd)
    lo, hi = f_mean - 9 * f_sd, f_mean + 9 * f_sd
    peak = optimize.minimize_scalar(lambda f: -np.log(integrand(f) + 1e-300), bounds=(lo, hi), method="bounded").x
    pieces = [integrate.quad(integrand, a, b, epsabs=0, epsrel=1e-10, limit=200)[0]
              for a, b in ((lo, peak - 3 * f_sd), (peak - 3 * f_sd, peak + 3 * f_sd), (peak + 3 * f_sd, hi))]
    return float(sum(pieces))


def tyre_margin(**kw) -> float:
    return float(tyre_adhesion_margin(paper(), kw["grade_pct"], kw["direction"], kw["occupants"]))


def misses_allowed(n: int) -> int:
    """Most misses of a 95 % interval in n independent tries before it is implausible (P < 0.2 %)."""
    return int(stats.binom.isf(0.002, n, 0.05))
