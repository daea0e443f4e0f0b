"""What a second effect must show beyond the first, for :mod:`rollaway.identify.partner`.

A second effect that lowers BIC beside a first may only be absorbing the first's form mismatch.  It must predict
held-out tests better than the first *re-formed* (its hook as a linear spline, :func:`beyond_reform`) and than the
first written with a second term of its own law (:func:`beyond_second_term`).  Both use one paired held-out rule
(:func:`heldout_preference`): per test, both channels, a margin in standard errors of the paired difference, and
refitted folds where the linearised leave-one-test-out cannot be trusted.
"""
from __future__ import annotations

import numpy as np

from rollaway.identify.calibrate import FitResult, calibrate
from rollaway.identify.workers import fit_all
from rollaway.uncertainty.heldout import loto_residuals
from rollaway.identify.selection import BIC_THRESHOLD, REFORM_ITERATIONS, SECOND_EFFECT_SE

TEST_WIN = 1.0      # a test counts as better predicted when its held-out log score is higher by more than 1 [assumed]
SECOND_TERM_STARTS = (0.2, 5.0)   # a second term's time constants start at these multiples of the first's [assumed]


def beyond_reform(data, params, chosen: list[str], current: FitResult, two: FitResult, refree=(),
                  also=()) -> dict | None:
    """Does the fit *two* (the effect *chosen* plus a second one) predict held-out tests better than
    the first effect re-formed — its hook changed by a linear spline of its covariate
    (:func:`rollaway.identify.shape.flexible_effect`), no second effect?  A partner that only absorbs a
    mis-formed first effect's misfit does not: then it is no discovery.  *current*: a fit whose prediction
    gives the first effect's covariate (lining temperature, …) and the start values.

    Returns None when the first effect has no flexible form (nothing to compare), else
    ``{"passes", "heldout_elpd", "heldout_se", "better_tests", "worse_tests", "channels"}``: *passes* when the
    held-out log score of the two-effect model beats the re-formed one by more than :data:`SECOND_EFFECT_SE`
    standard errors of the paired per-test difference (and by more than
    :data:`rollaway.identify.ambiguity.SMALL_ELPD`), in more tests (folds) than it loses — a test counts as won
    or lost when its log score differs by more than :data:`TEST_WIN`; a tie counts for neither (two fits that
    both predict a test to the noise say nothing about it, and "better" by 0.2 must not carry a majority) —, by
    more than SMALL_ELPD also without its most favourable test (with a handful of tests one test's
    misfit can carry the sum and inflate the standard error the rule is measured in), and neither channel
    (drum temperature, torque) predicts worse beyond :data:`rollaway.identify.ambiguity.HELDOUT_SE` of its
    own standard errors.

    *refree*: brake parameters the drum calibration held at their assumed values although the data test
    them ("not needed" without any effect), or held because the logs cannot tell them from another (the gap, a
    thicker lining in eq. (16b)): both compared fits free them.  A brake parameter that was not
    needed by the bare drum can be needed once the first effect is in, and a second effect that stands in
    for it (a gap or a radial contraction for a lining of another thickness) is then no discovery; with them
    freed, the second effect must also still lower BIC below :data:`BIC_THRESHOLD` against the first effect alone
    (``delta_bic_refreed``).  *also*: more fit jobs ``(effects, params, kwargs)`` run in the same batch on the
    machine's cores, their fits returned as ``"also"``."""
    from rollaway.effects import get_effect
    from rollaway.identify.shape import covariate_of, flexible_effect, shape_hook
    if len(chosen) != 1 or two.jacobian is None:
        return None
    eff = get_effect(chosen[0])
    found = shape_hook(eff)
    flex = None if found is None else flexible_effect(eff, covariate_of(current, found[1]))
    if flex is None:
        return None
    refree = [n for n in refree if n not in getattr(params, "free", ())]
    delta_bic = None
    jobs = []
    if refree:
        from rollaway.identify.model import DrumPlan
        params = DrumPlan(params.params, tuple(params.free) + tuple(refree))
        jobs = [(two.effects, params, dict(start=two.values)), (chosen, params, dict(start=current.values))]
    done = fit_all(data, jobs + [([flex], params, dict(start=current.values, max_iterations=REFORM_ITERATIONS))]
                   + list(also))                                                       # side by side
    *refit, reform = done[:len(jobs) + 1]
    if refit:
        two, one = refit
        if two.jacobian is None:
            return None
        delta_bic = two.bic - one.bic
    if reform.jacobian is None:
        return None
    out = heldout_preference(data, two, reform)
    out.update(reform_effect=flex.name, delta_bic_refreed=delta_bic, also=done[len(jobs) + 1:])
    out["passes"] = bool(out["passes"] and (delta_bic is None or delta_bic < BIC_THRESHOLD))
    return out


def beyond_second_term(data, params, first: str, second: str, pair: FitResult, also=(), give_up: bool = False
                       ) -> dict | None:
    """Does *second* still add beside *first* written with a second term of its own law
    (:func:`rollaway.effects.second_term.second_term`: one more amplitude and time constant)?  A cable relaxation
    beside a lining creep can write a creep that follows a power law of time: two exponentials of any kind
    approximate it, and a spline of time on a handful of tests predicts them worse than the two (each segment's
    slope trades with the cooling the drum parameters also fit).  *first* with its second term (started with the
    time constants at :data:`SECOND_TERM_STARTS` times the first's in *pair*, the better fit by BIC kept) is fitted
    alone and beside *second*; the three must lower BIC below :data:`BIC_THRESHOLD` against the two and predict
    held-out tests better (:func:`heldout_preference`, ``"passes"``; ``"delta_bic"``; ``"term"``: its name).  None
    where *first* has no second term or a fit fails.  *also*: more fit jobs ``(effects, params, kwargs)`` the caller
    asks for next, run in the batch of the second term's starts (kept for that call by
    :mod:`rollaway.identify.memo`).  *give_up*: the three are fitted only as far as they can still come below the
    BIC bar (:func:`rollaway.identify.solver.futile`; the answer, not its numbers, is what the caller reads)."""
    from rollaway.effects import get_effect
    from rollaway.effects.second_term import has_second_term, second_term
    eff = get_effect(first)
    if not has_second_term(eff) or pair.jacobian is None:
        return None
    two = second_term(eff)
    jobs = []
    for m in SECOND_TERM_STARTS:
        start = dict(pair.values)
        for p in eff.parameters:
            v = float(pair.values.get(f"{first}.{p.name}", p.initial))
            start[f"{two.name}.{p.name}"] = min(max(v * m, p.lower), p.upper) if p.unit == "s" else p.initial
        jobs.append(([first, two], params, dict(start=start)))
    fits = [f for f in fit_all(data, jobs + list(also))[:len(jobs)] if f.jacobian is not None]
    if not fits:
        return None
    term = min(fits, key=lambda f: f.bic)
    three = calibrate(data, [first, two, second], params, start={**pair.values, **term.values},
                      give_up_bic=term.bic + BIC_THRESHOLD if give_up else None)
    if three.jacobian is None:
        return None
    out = heldout_preference(data, three, term)
    out.update(term=two.name, delta_bic=float(three.bic - term.bic))
    out["passes"] = bool(out["passes"] and out["delta_bic"] < BIC_THRESHOLD)
    return out


def heldout_preference(d, two: FitResult, reform: FitResult, also=()) -> dict:
    """Held-out comparison of *two* against *reform* (:func:`beyond_reform`'s rule, without its BIC condition).
    Where *two* has per-test values that *reform* lacks, within each test (:func:`within_tests`).

    The held-out residuals are first the linearised leave-one-test-out (:func:`rollaway.uncertainty.heldout.
    loto_residuals`); a comparison that passes on them is decided again on refitted folds
    (:func:`rollaway.identify.refit_heldout.refit_loto_residuals`, ``"heldout": "refitted"``): a flexible form on
    few tests has directions one test alone informs, where the linear step, and the advantage it gives the pair,
    can be spurious; only the folds whose linear step fails its check are refitted (``"refitted_folds"``, per fit).
    One that fails on them stays failed: the second effect is then not named either way.  *also*: calibrations the
    caller asks for next when the comparison passes, run beside the refitted folds
    (:func:`~rollaway.identify.refit_heldout.refit_loto_residuals`)."""
    from rollaway.identify.refit_heldout import refit_loto_residuals
    out = preference(d, two, reform, [loto_residuals(reform), loto_residuals(two)])
    out["heldout"] = "linearised"
    if out["passes"]:
        held, refitted = refit_loto_residuals([reform, two], also)
        if any(refitted):
            out = {**preference(d, two, reform, held), "heldout": "refitted", "refitted_folds": refitted,
                   "linearised": {k: out[k] for k in ("heldout_elpd", "heldout_se", "better_tests")}}
    return out


def preference(d, two: FitResult, reform: FitResult, held: list[np.ndarray]) -> dict:
    """:func:`heldout_preference`'s rule on the held-out residuals *held* of [*reform*, *two*]."""
    from rollaway.identify.ambiguity import HELDOUT_SE, SMALL_ELPD
    n = len(d)
    out = {"channels": {}}
    per = {}
    within = _own_level_channels(two) - _own_level_channels(reform)
    for key, r in (("reform", held[0]), ("two", held[1])):
        if within:
            r = within_tests(d, r, within)
        r2 = r ** 2
        per[key] = {"temperature": np.bincount(d.test_index, r2[:n], d.n_tests),
                    "torque": np.bincount(d.test_index, r2[n:], d.n_tests)}
    ok = True
    for ch in ("temperature", "torque"):
        diff = -0.5 * (per["two"][ch] - per["reform"][ch])        # > 0: the two effects predict better
        se = float(np.sqrt(diff.size * np.var(diff, ddof=1))) if diff.size > 1 else np.inf
        out["channels"][ch] = {"heldout_elpd": float(diff.sum()), "heldout_se": se}
        ok &= diff.sum() > -HELDOUT_SE * se
    total = sum(-0.5 * (per["two"][ch] - per["reform"][ch]) for ch in ("temperature", "torque"))
    se = float(np.sqrt(total.size * np.var(total, ddof=1))) if total.size > 1 else np.inf
    better, worse = int((total > TEST_WIN).sum()), int((total < -TEST_WIN).sum())
    out.update(heldout_elpd=float(total.sum()), heldout_se=se, better_tests=better, worse_tests=worse,
               tests=int(total.size),
               per_test=[float(x) for x in total],
               passes=bool(ok and total.sum() > max(SECOND_EFFECT_SE * se, SMALL_ELPD) and better > worse
                           and total.sum() - total.max() > SMALL_ELPD))
    return out


def refit_words(pref: dict) -> str:
    """What :func:`heldout_preference` refitted, in words ("" when the linearised comparison stood)."""
    if pref.get("heldout") != "refitted":
        return ""
    n_reform, n_two = pref["refitted_folds"]
    lin = pref["linearised"]
    return (f" (held-out tests refitted where a linear step failed its check: {n_reform} of the re-formed fit's, "
            f"{n_two} of the pair's; linearised {lin['heldout_elpd']:+.1f} ± {lin['heldout_se']:.1f})")


def _own_level_channels(fit: FitResult) -> set[str]:
    """The channels in which an effect of *fit* with values per test (a zero offset per test) sets each test's own
    level: the torque, and the drum temperature where such an effect changes it."""
    per_test = [e for e in fit.model.effects if any(p.per_test for p in e.parameters)]
    return ({"torque"} | ({"temperature"} if any(e.touches_temperature() for e in per_test) else set())
            if per_test else set())


def within_tests(d, r: np.ndarray, channels: set[str]) -> np.ndarray:
    """Standardised residuals *r* ([temperature | torque]) less each test's mean in *channels*.  A fit with per-test
    values refits the held-out test's own values (its level) from that test itself: compared with a fit without
    them, only what the residuals do within each test is a fair held-out comparison."""
    n = len(d)
    r = np.array(r, float, copy=True)
    counts = np.maximum(np.bincount(d.test_index, minlength=d.n_tests), 1)
    for ch, off in (("temperature", 0), ("torque", n)):
        if ch in channels:
            part = r[off:off + n]
            part -= (np.bincount(d.test_index, part, d.n_tests) / counts)[d.test_index]
    return r


__all__ = ["SECOND_TERM_STARTS", "TEST_WIN", "beyond_reform", "beyond_second_term", "heldout_preference",
           "preference", "refit_words", "within_tests"]
