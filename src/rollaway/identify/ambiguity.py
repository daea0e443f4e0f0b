"""Effect sets the bench data cannot tell apart, and the test that would.

:func:`rivals` reads the first selection step: a candidate with ΔBIC below the threshold (its held-out
prediction is judged against the selected effect's, not against the drum alone: with few tests each one left
out is an extrapolation, and all of them may predict worse than the drum) is *not ruled out* by the data when

* its BIC is within :data:`INDISTINGUISHABLE_BIC` of the selected effect's and the held-out
  prediction does not prefer the selected one (:func:`heldout_difference`), or
* the two criteria disagree: BIC prefers the selected effect but the held-out prediction prefers
  the candidate (by any amount) — the data then give no consistent answer.  A candidate short of the threshold
  but below :data:`WEAK_BIC` (strong evidence against the drum alone) is a rival on this ground only: a verdict
  the held-out tests predict worse than such a candidate is not a finding the data back
  (held-out campaign 547 of ``tests.identify.heldout_names``: lining creep 7.8 BIC better than a quadratic friction
  law the held-out tests gave 87 % of the weight).

The held-out comparison is the paired difference of the per-test leave-one-test-out log scores
(Gaussian log score, :func:`rollaway.uncertainty.heldout.loto_scores`) with its standard error
√(n·var(d)) over the n tests (Vehtari, Gelman & Gabry 2017, "Practical Bayesian model evaluation
using leave-one-out cross-validation and WAIC", Stat. Comput. 27, §5.2 "standard error of the
difference"); "prefers" means a difference beyond :data:`HELDOUT_SE` standard errors (as a Student-t tail with
tests − 1 dof: :func:`preference_margin`) and beyond :data:`SMALL_ELPD` (with a handful of tests a consistent small
difference has a tiny standard error).

The test that would separate two of them is :func:`rollaway.identify.separating_test.tell_apart`.
"""
from __future__ import annotations

import math

import numpy as np

from rollaway.identify.solver import FUTILE_MARGIN
from rollaway.identify.selection import BIC_THRESHOLD
from rollaway.identify.separating_test import tell_apart
from rollaway.uncertainty.heldout import loto_scores

INDISTINGUISHABLE_BIC = 6.0   # "positive" evidence at most (Kass & Raftery 1995): no choice on BIC alone
HELDOUT_SE = 2.0              # a held-out preference beyond 2 standard errors of the paired difference
SMALL_ELPD = 4.0              # ... and beyond 4 in log score: below it the difference is small and its standard
                              # error unreliable (Sivula, Magnusson & Vehtari 2020, "Uncertainty in Bayesian
                              # leave-one-out cross-validation based model comparison", §5; the loo CV-FAQ)
MAX_RIVALS = 2                # at most this many alternatives are named beside the verdict
WEAK_BIC = -6.0               # "strong" evidence (Kass & Raftery 1995: 2·Δln L of 6–10) but short of the selection's
                              # −10: named beside a "none" verdict as a weak alternative, never as the verdict [assumed]
WEAK_BIC_HELD = -2.0          # ... or "positive" evidence (2·Δln L of 2–6) where the effect's fit holds brake parameters
                              # the bare drum freed to imitate it (it explains the data with fewer of them) [assumed]
WEAK_TOP = 3                  # step-1 candidates examined for a weak alternative


def heldout_difference(a, b) -> tuple[float, float]:
    """(Δ, se): Δ = elpd(b) − elpd(a) of the leave-one-test-out Gaussian log scores (positive: *b* predicts
    held-out tests better) and the standard error of the paired per-test difference."""
    d = -0.5 * (loto_scores(b) - loto_scores(a))
    n = d.size
    se = math.sqrt(n * float(np.var(d, ddof=1))) if n > 1 else math.inf
    return float(d.sum()), se


def preference_margin(fit, se: float) -> float:
    """How far a held-out difference must go before it "prefers" (:data:`HELDOUT_SE` standard errors, the normal
    tail it stands for taken from Student's t with tests − 1 dof: a standard error from n paired per-test
    differences is itself uncertain — with 2 tests the 2σ bar is 13.9σ, with 4 it is 3.9σ, with 8 2.5σ), and at
    least :data:`SMALL_ELPD`."""
    from rollaway.scipy_direct import special_functions    # norm.cdf and t.ppf without scipy.stats's start
    sf = special_functions()
    n = int(getattr(fit.data, "n_tests", 0))
    k = max(HELDOUT_SE, float(sf.stdtrit(n - 1, sf.ndtr(HELDOUT_SE)))) if n > 1 else math.inf
    return max(k * se, SMALL_ELPD)


def not_ruled_out(a, b) -> bool:
    """True when the held-out prediction does not prefer fit *a* over fit *b* beyond :func:`preference_margin`
    (:func:`heldout_difference`)."""
    elpd, se = heldout_difference(a, b)
    return elpd > -preference_margin(a, se)


def rivals(best, candidates: list, threshold: float, inflation: float = 1.0) -> list[dict]:
    """The step-1 candidates the data do not rule out against *best* (module docstring), best first:
    ``{"kind": "rival", "effects", "delta_bic" (against best), "heldout_elpd", "heldout_se", "why", "fit"}``.
    *inflation*: the variance inflation of *best*'s autocorrelated residuals (≥ 1,
    :func:`rollaway.identify.intervals.ess_inflation`); a BIC difference counts every sample as independent, so it
    is divided by it (the effective sample size's share) before it is compared."""
    out = []
    if best.fit.jacobian is None:
        return out
    for c in candidates:
        weak = c.delta_bic >= threshold           # short of the selection's threshold: a rival only where the
        if c is best or c.delta_bic >= WEAK_BIC or (c.cv_score is None and not weak) or c.fit.jacobian is None:
            continue                              # held-out prediction prefers it
        dbic = (c.delta_bic - best.delta_bic) / max(inflation, 1.0)
        elpd, se = heldout_difference(best.fit, c.fit)
        if not weak and dbic < INDISTINGUISHABLE_BIC and elpd > -preference_margin(best.fit, se):
            why = (f"BIC within {INDISTINGUISHABLE_BIC:g} ({dbic:+.1f}) and the held-out prediction does not prefer "
                   f"either (Δ log score {elpd:+.1f} ± {se:.1f})")
        elif elpd > 0:
            why = (f"BIC prefers {best.effect} by {dbic:.1f} but the held-out prediction prefers {c.effect} "
                   f"(Δ log score {elpd:+.1f} ± {se:.1f}): the evidence disagrees")
        else:
            continue
        out.append({"kind": "rival", "effects": [c.effect], "delta_bic": float(dbic), "heldout_elpd": elpd,
                    "heldout_se": se, "why": why, "fit": c.fit})
    out.sort(key=lambda r: r["delta_bic"])
    return out[:MAX_RIVALS]


def set_rivals(data, plan, names: list[str], chosen: list[str], current, inflation: float = 1.0,
               screen_iterations: int = 6) -> list[dict]:
    """A verdict of several effects *chosen* (fit *current*): the sets with one of them exchanged for another
    catalogue effect that the data do not rule out — BIC within :data:`INDISTINGUISHABLE_BIC` (divided by the
    residual variance *inflation*, as :func:`rivals`) and a held-out prediction that does not prefer *current*
    beyond :func:`preference_margin`; or, as :func:`rivals` counts it, BIC short of the selection's own bar
    (:data:`~rollaway.identify.selection.BIC_THRESHOLD`) against *current* where the held-out prediction prefers
    the exchanged set (the evidence disagrees).  Screened with *screen_iterations* iterations from *current*'s values (with the brake
    parameters held at them, another law cannot be compared: μ_d and the eq. (24) law were fitted to the first), then
    refitted.  At most :data:`MAX_RIVALS`, best first, each as :func:`rivals` gives them plus
    ``"verdict_effects"`` (*chosen*)."""
    from rollaway.effects import get_effect
    from rollaway.identify.workers import fit_all
    if current.jacobian is None:
        return []
    k = max(inflation, 1.0)
    swaps = [chosen[:i] + [new] + chosen[i + 1:] for i in range(len(chosen)) for new in names
             if new not in chosen and not get_effect(new).per_test_parameters()]
    bar = current.bic - BIC_THRESHOLD * k + FUTILE_MARGIN          # beyond it the screen cannot pass: abandoned
    screens = fit_all(data, [(t, plan, dict(start=current.values, statistics=False, max_iterations=screen_iterations,
                                            give_up_bic=bar)) for t in swaps])
    trials = [t for t, fit in zip(swaps, screens)
              if (fit.bic - current.bic) / k < -BIC_THRESHOLD]       # a loose screen
    out = []
    for trial, fit in zip(trials, fit_all(data, [(t, plan, dict(start=current.values)) for t in trials])):
        dbic = (fit.bic - current.bic) / k
        if fit.jacobian is None or dbic >= -BIC_THRESHOLD:
            continue
        elpd, se = heldout_difference(current, fit)
        margin = preference_margin(current, se)
        if elpd <= -margin or (dbic >= INDISTINGUISHABLE_BIC and elpd <= 0.0):
            continue
        if dbic >= INDISTINGUISHABLE_BIC:
            why = (f"BIC prefers the verdict by {dbic:.1f} but the held-out prediction prefers "
                   f"{' + '.join(trial)}")
        else:
            why = ((f"BIC within {INDISTINGUISHABLE_BIC:g} ({dbic:+.1f})" if dbic > -INDISTINGUISHABLE_BIC else
                    f"BIC lower than the verdict's by {-dbic:.1f}")
                   + (" and the held-out prediction prefers it" if elpd > margin else
                      " and the held-out prediction does not prefer either"))
        out.append({"kind": "rival", "effects": list(trial), "delta_bic": float(dbic), "heldout_elpd": elpd,
                    "heldout_se": se, "fit": fit, "verdict_effects": list(chosen),
                    "why": why + f" (Δ log score {elpd:+.1f} ± {se:.1f})"
                           + (": the evidence disagrees" if dbic >= INDISTINGUISHABLE_BIC else "")})
    return sorted(out, key=lambda a: a["delta_bic"])[:MAX_RIVALS]


def closest(base, candidates: list, base_cv, threshold: float, validity: dict, noise_torque_Nm: float,
            shapes: dict | None = None) -> list[dict]:
    """Where structure remains that no catalogue form clears: the candidates of the first step that point at
    the physics — ΔBIC below *threshold* against the calibrated drum *base* and better held-out prediction
    (*base_cv*); when none predicts better (with few tests each one left out is an extrapolation), those with
    the ΔBIC alone, saying so — the best :data:`MAX_RIVALS` by BIC (two forms that both leave structure are not ranked by
    the evidence between them); each ``{"kind": "closest", "effects", "delta_bic" (against the drum alone),
    "heldout_elpd", "heldout_se" (against the drum alone), "why", "tell_apart", "fit", "clears"}``.  With two, the
    test that would tell them apart; with one, where it departs most from the drum alone.

    *shapes*: ``{effect: (shape-free fit, clears the structure)}`` of candidates also fitted shape-free
    (:func:`rollaway.identify.shape.candidate_shapes`).  A candidate is then judged by the better of its two forms
    by BIC; one whose shape-free form clears the structure (and predicts held-out tests better than the drum) joins
    them and ranks before those that leave it: the quantity it changes explains the data, in a shape the catalogue
    does not write.
    ``"shape_fit"`` then holds the shape-free fit, and the test that would tell two apart compares their better
    forms.  Where fewer than :data:`MAX_RIVALS` predict held-out tests better, a form BIC prefers far beyond them
    joins them (:func:`_bic_beyond_heldout`; ``"bands": False``, no ``"shape_fit"``)."""
    if base.jacobian is None:
        return []
    shapes = shapes or {}

    def better(c):                                    # (fit, ΔBIC, shape-free form cleared the structure)
        s = shapes.get(c.effect)
        if s is not None and s[0].bic < c.fit.bic:
            return s[0], float(s[0].bic - base.bic), bool(s[1])
        return c.fit, float(c.delta_bic), False

    forms = {c.effect: better(c) for c in candidates if c.fit.jacobian is not None}
    strong = [c for c in candidates if c.effect in forms and forms[c.effect][1] < threshold]
    cleared = {c.effect for c in strong if forms[c.effect][2] and heldout_difference(base, forms[c.effect][0])[0] > 0}
    ok = [c for c in strong if c.cv_score is not None and base_cv is not None and c.cv_score < base_cv]
    held_out_against = not ok and not cleared      # none predicts held-out tests better (few tests: each left out
    pool = ok or [c for c in strong if c.effect not in cleared]           # is an extrapolation)
    pool = [c for c in strong if c.effect in cleared and c not in pool] + pool
    ranked = sorted(pool, key=lambda c: (c.effect not in cleared, forms[c.effect][1]))[:MAX_RIVALS]
    bic_only = _bic_beyond_heldout(ranked, strong, forms) if ok else []
    out = []
    for c in ranked + bic_only:
        elpd, se = heldout_difference(base, c.fit)
        why = (f"ΔBIC {c.delta_bic:.1f} and held-out log score {elpd:+.1f} ± {se:.1f} against the drum alone"
               + (" (the held-out prediction does not support it)" if held_out_against or c in bic_only else ""))
        a = {"kind": "closest", "effects": [c.effect], "delta_bic": float(c.delta_bic), "heldout_elpd": elpd,
             "heldout_se": se, "fit": c.fit, "clears": c.effect in cleared, "why": why,
             "form_delta_bic": forms[c.effect][1]}
        if c in bic_only:       # named on the evidence of every test together; drawn in the bands it is not
            a["bands"] = False
        if c.effect in shapes:
            fit = shapes[c.effect][0]
            dbic = float(fit.bic - base.bic)
            e2, se2 = heldout_difference(base, fit)
            if c not in bic_only:           # (a form of the model's own among the bands' forms: not this one)
                a["shape_fit"] = fit
            a["why"] += (f"; shape-free ΔBIC {dbic:.1f}, held-out {e2:+.1f} ± {se2:.1f}, "
                         + ("clears the structure" if c.effect in cleared else "leaves structure"))
        out.append(a)
    if not out:
        return []
    first = forms[out[0]["effects"][0]][0]
    other = forms[out[1]["effects"][0]][0] if len(out) > 1 else base
    words = tell_apart(first, other, validity, noise_torque_Nm)
    for a in out:
        a["tell_apart"] = words
    return out


def _bic_beyond_heldout(ranked: list, strong: list, forms: dict) -> list:
    """Candidates of *strong* that BIC prefers to every one of *ranked* (those the held-out tests support), up to
    :data:`MAX_RIVALS` in all: with a few tests, each one left out is an extrapolation (another T₀, a hand force
    beyond the others), and a form that explains all the tests together far better than the drum and than the
    supported ones is a closest effect too — named beside them, not weighed into the bands (its held-out score
    does not support it)."""
    if not ranked or len(ranked) >= MAX_RIVALS:
        return []
    bar = min(forms[c.effect][1] for c in ranked)
    more = [c for c in strong if c not in ranked and forms[c.effect][1] < bar - INDISTINGUISHABLE_BIC]
    return sorted(more, key=lambda c: forms[c.effect][1])[:MAX_RIVALS - len(ranked)]


def weak_alternatives(plan, base, candidates: list, validity: dict, noise_torque_Nm: float) -> list[dict]:
    """Effects a "none" verdict cannot rule out: the best :data:`WEAK_TOP` step-1 *candidates* (ΔBIC below
    :data:`INDISTINGUISHABLE_BIC` against the calibrated drum *base*: one the free drum imitates need not lower it),
    each compared fairly with the drum — refitted with the brake parameters of *plan*
    that it makes unnecessary held (backward elimination by BIC, μ_d always fitted; the bare drum freed them to
    imitate it: a loss with time at constant temperature takes the eq. (24) slope and offset) — and kept when that
    fit lowers BIC by more than −:data:`WEAK_BIC` (−:data:`WEAK_BIC_HELD` where it holds some of them: the effect
    then explains the data with fewer of the drum's parameters, which the BIC of the free drum does not see) and
    predicts held-out tests better (:func:`heldout_difference` above :data:`SMALL_ELPD`; beyond :data:`HELDOUT_SE`
    standard errors too for a candidate that did not lower BIC against the free drum) — or, where it lowers BIC
    beyond the verdict's own bar (:data:`~rollaway.identify.selection.BIC_THRESHOLD`), when the held-out prediction
    does not prefer the drum (beyond :func:`preference_margin`): the drum imitated it, and two tests cannot say
    which — with the test that would settle it (:func:`tell_apart`).  At most
    :data:`MAX_RIVALS`, best first: ``{"effects", "delta_bic", "heldout_elpd", "heldout_se", "why", "fit",
    "tell_apart", "weak": True, "held"}`` (*held*: the brake parameters its fit held)."""
    out = []
    if base.jacobian is None:
        return out
    for c in [c for c in candidates if c.delta_bic < INDISTINGUISHABLE_BIC][:WEAK_TOP]:
        fit = _held_where_unneeded(plan, c.effect, c.fit)
        held = [] if fit is None else [n for n in plan.free if n not in fit.model.free]
        if fit is None or fit.bic - base.bic >= (WEAK_BIC_HELD if held else WEAK_BIC):
            continue
        elpd, se = heldout_difference(base, fit)
        strong = fit.bic - base.bic < BIC_THRESHOLD      # the verdict's bar, met only with drum parameters held
        bar = SMALL_ELPD if c.delta_bic < 0.0 else max(SMALL_ELPD, HELDOUT_SE * se)   # no step-1 evidence: a clear
        if elpd <= (-preference_margin(base, se) if strong else bar):                  # held-out preference
            continue
        why = (f"with {c.effect} in the model{' ' + ', '.join(held) + ' need not be fitted and' if held else ''} BIC "
               f"drops by {base.bic - fit.bic:.1f} (selection needs {-(WEAK_BIC_HELD if held else WEAK_BIC):g} to "
               f"name it as an alternative{' with drum parameters held' if held else ''}, 10 as the verdict) and "
               f"held-out tests are predicted "
               + ("better" if elpd > SMALL_ELPD else "as well") + f" (Δ log score {elpd:+.1f} ± {se:.1f}): "
               f"suggested, not established" + ("" if not strong or elpd > SMALL_ELPD else
                                                 f" — the drum with {', '.join(held) or 'its parameters'} free "
                                                 f"imitates it, and the held-out tests cannot tell which"))
        out.append({"kind": "weak", "effects": [c.effect], "delta_bic": float(fit.bic - base.bic), "heldout_elpd": elpd,
                    "heldout_se": se, "why": why, "fit": fit, "weak": True, "held": held,
                    "tell_apart": tell_apart(base, fit, validity, noise_torque_Nm)})
    out.sort(key=lambda r: r["delta_bic"])
    return out[:MAX_RIVALS]


def _held_where_unneeded(plan, effect: str, fit):
    """*fit* (*effect* on the drum of *plan*) with the brake parameters it makes unnecessary held at their assumed
    values, one at a time while BIC drops; None without a Jacobian."""
    from rollaway.identify.model import DrumPlan
    from rollaway.identify.workers import fit_all
    free = list(plan.free)
    while len(free) > 1:
        names = [n for n in free if n != "mu_drum"]
        if not names:
            break
        trials = list(zip(fit_all(fit.data, [([effect], DrumPlan(plan.params, tuple(f for f in free if f != n)),
                                              dict(start={k: v for k, v in fit.values.items() if k != n}))
                                             for n in names]), names))      # side by side on the cores
        best, name = min(trials, key=lambda t: t[0].bic)
        if best.bic >= fit.bic:
            break
        free.remove(name)
        fit = best
    return fit if fit.jacobian is not None else None


def _closest_clause(alternatives: list[dict]) -> tuple[str, str]:
    """(what the closest effects' forms leave, what the data say between them) of :func:`closest`'s output."""
    names = [a["effects"][0] for a in alternatives]
    clear = [n for a, n in zip(alternatives, names) if a.get("clears")]
    words = alternatives[0]["tell_apart"]["words"]
    between = f"these data cannot tell them apart; {words}" if len(names) > 1 else ""
    gap = (abs(alternatives[1]["form_delta_bic"] - alternatives[0]["form_delta_bic"])
           if len(names) > 1 and all("form_delta_bic" in a for a in alternatives[:2]) else 0.0)
    if len(names) > 1 and alternatives[1].get("bands", True) is False:      # _bic_beyond_heldout's
        between = (f"BIC prefers {names[1]} (lower by {gap:.1f}), the held-out tests {names[0]} — with so few tests "
                   f"each one left out is an extrapolation; {words}")
    elif gap > INDISTINGUISHABLE_BIC:      # the tested conditions already separate them: no test to propose
        tested = alternatives[0]["tell_apart"].get("tested_difference_Nm")
        between = (f"these data tell them apart (BIC {gap:.1f} apart"
                   + (f"; torques up to {tested:.3g} N·m apart over the tested conditions" if tested else "")
                   + f"), yet each form leaves structure: {names[0]} is the nearer")
    if not clear:
        return "each leaves structure", between
    forms = "its catalogue form leaves" if len(names) == 1 else "each catalogue form leaves"
    if len(clear) == len(names):
        return (f"{forms} structure; shape-free, {' and '.join(clear)} clear{'s' if len(clear) == 1 else ''} it",
                between)
    rest = [n for n in names if n not in clear]
    return (f"{forms} structure; shape-free, {clear[0]} clears it, {rest[0]} does not",
            f"the data lean to {clear[0]}; {words}")


def alternative_words(verdict: str, alternatives: list[dict], named=()) -> list[str]:
    """The evidence lines of a verdict's alternatives (rivals, closest or weak), each set against the *named* effects
    (all of them; *verdict*, the first, where none are given)."""
    if not alternatives:
        return []
    kind = alternatives[0].get("kind")
    if kind == "closest":
        left, between = _closest_clause(alternatives)
        clear = any(a.get("clears") for a in alternatives)
        return [f"Closest in the catalogue: {' or '.join(a['effects'][0] for a in alternatives)} — "
                + "; ".join(f"{a['effects'][0]}: {a['why']}" for a in alternatives)
                + f".  {left[0].upper()}{left[1:]}"
                + (": the quantity a shape-free form changes explains the data, in a shape the catalogue does not "
                   "write (write that shape as a plugin and refit)" if clear else
                   ": they point at the physics, they do not explain it")
                + (f"; {between}." if between else ".")]
    return [f"{a['effects'][0]} is not ruled out: {a['why']}; {a['tell_apart']['words']}." if a.get("kind") == "weak"
            else f"{' + '.join(a.get('verdict_effects') or named or [verdict])} or {' + '.join(a['effects'])}: these data "
                 f"cannot tell them apart — {a['why']}; {a['tell_apart']['words']}." for a in alternatives]


def verdict_line(verdict: str, alternatives: list[dict], detection=(), structure: bool = False, named=()) -> str:
    """"A or B: these data cannot tell them apart; a test at … would" (or the verdict alone), A the *named* effects
    (all of them, "A1 + A2"; *verdict*, the first, where none are given); for a verdict
    ``none`` with the closest catalogue effects (:func:`closest`): "none explains …; closest: A or B"; for a bare
    ``none`` whose *detection* limits (:mod:`rollaway.identify.detection`) exceed typical sizes: what could hide; for
    a ``none`` whose residual keeps *structure* and no candidate points anywhere: that structure remains."""
    if not alternatives and verdict == "none" and structure:
        return ("none: structure remains that no catalogue effect explains (no candidate lowers BIC enough to point "
                "at one)")
    if not alternatives:
        from rollaway.identify.detection import blind
        missed = blind(detection) if verdict == "none" else []
        return (" + ".join(named) or verdict) + (f" (not found; these data could miss {len(missed)} of {len(detection)} effects at the "
                          f"size real drums show: {', '.join(missed[:3])}{', …' if len(missed) > 3 else ''}; "
                          f"see the detection limits)" if missed else "")
    if alternatives[0].get("kind") == "weak":
        names = " or ".join(a["effects"][0] for a in alternatives)
        return (f"none (suggested, not established: {names}); {alternatives[0]['tell_apart']['words']}")
    if alternatives[0].get("kind") == "closest":
        names = " or ".join(a["effects"][0] for a in alternatives)
        left, between = _closest_clause(alternatives)
        return (f"none: structure remains that no catalogue effect explains; closest: {names} ({left})"
                + (f"; {between}" if between else ""))
    names = " or ".join([" + ".join(alternatives[0].get("verdict_effects") or named or [verdict])]
                        + [" + ".join(a["effects"]) for a in alternatives])
    return f"{names}: these data cannot tell them apart; {alternatives[0]['tell_apart']['words']}"


__all__ = ["HELDOUT_SE", "INDISTINGUISHABLE_BIC", "SMALL_ELPD", "MAX_RIVALS", "WEAK_BIC", "WEAK_BIC_HELD",
           "alternative_words", "closest", "heldout_difference", "not_ruled_out", "preference_margin", "rivals",
           "set_rivals", "verdict_line", "weak_alternatives"]
