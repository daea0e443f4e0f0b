"""A second selection step beside the first step's runner-up, for :mod:`rollaway.identify.diagnose`.

Forward selection is greedy: the first step keeps the candidate with the lowest BIC, and the second step only looks
beside it.  Where two first effects are close (a friction law and a lining modulus law falling with temperature
differ only through the self-energising factor) and a second effect is also in the data, the one that wins the first
step may be the one that absorbed part of the second (friction's change of the downhill/uphill ratio taking part
of a creep), and beside it the second effect no longer passes.  The pair that explains the data is then never
fitted.  :func:`runner_up_path` takes the second step beside the runner-up too — a beam of two at the first step,
taken only where the greedy path stopped at one effect — and returns it where it finds a pair that beats the
greedy verdict by the selection's own bar on BIC and on held-out tests.  The pair then faces every later test of
a pair (exchange, elimination, its own evidence: :mod:`rollaway.identify.partner`), like one the greedy path found.
Where the greedy path found nothing at all although the drum leaves structure, :func:`pair_path` fits every pair at
once — two effects can each be hidden by the free drum alone and together explain the data — and
:func:`reformed_alone` asks the one effect a pair's own-evidence test leaves for evidence of its own.
"""
from __future__ import annotations

import itertools

import numpy as np

from rollaway.identify.selection import (BIC_THRESHOLD, SCREEN_ITERATIONS, cv_score, forward_step, has_per_test,
                                         per_test_signature)

LOOKAHEAD_BIC = 20.0         # [assumed] step-1 runners-up within this BIC of the best are given a second step: twice
                             # the selection's bar, the most a missed second effect was measured to shift the first
                             # step's order (two-effect held-out campaigns: friction ahead of a true modulus law by
                             # 11.4 beside a missed creep)
LOOKAHEAD_TOP = 1            # at most this many runners-up are given a second step
PAIR_BIC = 2.0 * BIC_THRESHOLD   # a pair with no single step behind it clears the selection's bar once per effect
PAIR_TOP = 3                 # the pairs of lowest BIC whose held-out error is computed


def runners_up(first_cands: list, first: str, base_cv, params) -> list:
    """The step-1 candidates within :data:`LOOKAHEAD_BIC` of *first*'s that passed the first step themselves (BIC below
    the bar, held-out error below the drum alone's *base_cv*), fitted with the brake parameters of *params*, best
    first; at most :data:`LOOKAHEAD_TOP`."""
    best = next((c for c in first_cands if c.effect == first), None)
    if best is None or base_cv is None:
        return []
    free = set(getattr(params, "free", ()))
    return [c for c in first_cands
            if c is not best and c.delta_bic < BIC_THRESHOLD and c.delta_bic - best.delta_bic < LOOKAHEAD_BIC
            and c.cv_score is not None and c.cv_score < base_cv and c.fit.jacobian is not None
            and set(c.fit.model.free) <= free][:LOOKAHEAD_TOP]


def runner_up_path(data, params, names, first_cands: list, base_cv, chosen: list[str], current, cur_cv, nq,
                   held_brake=()):
    """Where the second step beside the one selected effect *chosen* (fit *current*, held-out error *cur_cv* or None)
    added nothing: the second step beside each runner-up of the first (:func:`runners_up`).  A pair found there
    must lower BIC below *current*'s by more than :data:`~rollaway.identify.selection.BIC_THRESHOLD` and predict
    held-out tests better than *current* (and than the runner-up alone: the step's own test).
    Returns (the runner-up's candidate, :func:`~rollaway.identify.selection.forward_step`'s answer beside it with
    only those pairs passing, *current*'s held-out error), or None."""
    ups = runners_up(first_cands, chosen[0], base_cv, params) if len(chosen) == 1 else []
    if not ups:
        return None
    for up in ups:
        cands, strong, passing, up_cv = forward_step(data, params, names, up.fit, [up.effect], 2,
                                                     per_test_signature(up.fit, nq), held_brake=held_brake)
        passing = [c for c in passing if c.fit.bic - current.bic < BIC_THRESHOLD]
        if not passing:
            continue
        if cur_cv is None:
            cur_cv = float(cv_score(data, chosen, params, current).sum())
        passing = [c for c in passing if c.cv_score < cur_cv]
        if passing:
            return up, (cands, strong, passing, up_cv), cur_cv
    return None


def pair_path(data, params, names, base, base_cv):
    """Where no single effect passes the first step although the calibrated drum *base* leaves structure: every pair
    of *names* (none with values per test) fitted at once with the brake parameters of *params*.  Two effects whose
    signatures pull the free drum opposite ways (a creep that lowers the torque with time beside a modulus law that
    raises it as the drum cools) can each leave the drum's BIC almost unchanged alone, and together explain the data
    — a beam as wide as the catalogue at the first step, taken only where the greedy path found nothing.  Every pair
    is screened (:data:`~rollaway.identify.selection.SCREEN_ITERATIONS`), the :data:`PAIR_TOP` lowest in BIC are
    refitted to convergence, and the first of them in BIC is returned when it lowers BIC below *base*'s by more than
    :data:`PAIR_BIC` and predicts held-out tests better than the drum alone (error *base_cv*, computed where None),
    by a paired log-score difference beyond :data:`~rollaway.identify.ambiguity.HELDOUT_SE` standard errors (a pair
    with no step behind it must be preferred, not merely not ruled out): (its fit, its held-out error, *base_cv*),
    else None.  It then faces every later test of a pair (exchange, elimination, its
    own evidence: :mod:`rollaway.identify.partner`)."""
    from rollaway.identify.workers import fit_all
    singles = [n for n in names if not has_per_test(n)]
    pairs = list(itertools.combinations(singles, 2))
    if not pairs or base.jacobian is None:
        return None
    screened = fit_all(data, [(list(p), params, dict(start=base.values, max_iterations=SCREEN_ITERATIONS))
                              for p in pairs])                       # a ranking fit each, then the best converged
    top = sorted((f for f in screened if np.isfinite(f.bic)), key=lambda f: f.bic)[:PAIR_TOP]
    fits = fit_all(data, [(list(f.effects), params, dict(start=f.values)) for f in top])
    ranked = sorted((f for f in fits if f.jacobian is not None and f.bic - base.bic < PAIR_BIC), key=lambda f: f.bic)
    if not ranked:
        return None
    if base_cv is None:
        base_cv = float(cv_score(data, [], params, base).sum())
    from rollaway.identify.ambiguity import HELDOUT_SE, heldout_difference
    for f in ranked[:PAIR_TOP]:
        cv = float(cv_score(data, list(f.effects), params, f).sum())
        elpd, se = heldout_difference(base, f)
        if cv < base_cv and elpd > HELDOUT_SE * se:
            return f, cv, base_cv
    return None


def reformed_alone(data, params, name: str, base, base_cv) -> bool:
    """True when effect *name* re-formed (its hook as a linear spline of its covariate, no functional form:
    :func:`rollaway.identify.shape.flexible_effect`) lowers BIC below the calibrated drum *base*'s by more than the
    selection's bar and predicts held-out tests better (error below *base_cv*): the evidence of its own that the one
    effect left of a :func:`pair_path` pair needs — its catalogue form did not pass the first step alone."""
    from rollaway.effects import get_effect
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.shape import covariate_of, flexible_effect, shape_hook
    eff = get_effect(name)
    found = shape_hook(eff)
    flex = None if found is None else flexible_effect(eff, covariate_of(base, found[1]))
    if flex is None:
        return False
    fit = calibrate(data, [flex], params, start=base.values)
    if fit.jacobian is None or fit.bic - base.bic >= BIC_THRESHOLD:
        return False
    return float(cv_score(data, [flex], params, fit).sum()) < base_cv


__all__ = ["LOOKAHEAD_BIC", "LOOKAHEAD_TOP", "PAIR_BIC", "PAIR_TOP", "pair_path", "reformed_alone", "runner_up_path",
           "runners_up"]
