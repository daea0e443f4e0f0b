"""Model selection for :mod:`rollaway.identify.diagnose`: residual structure, K-fold cross-validation
by test, and the forward, exchange and backward-elimination steps over candidate effects.

Every candidate is a calibrated :class:`~rollaway.identify.calibrate.FitResult` of the drum
model with some effects; ΔBIC ranks them, cross-validation (each held-out test predicted by a
model calibrated on the other tests) guards against effects that only fit noise.
"""
from __future__ import annotations

import math

from dataclasses import dataclass

import numpy as np

from rollaway.identify.workers import run_fits
from rollaway.identify.calibrate import FitResult, calibrate
from rollaway.identify.solver import FUTILE_MARGIN
from rollaway.bench.measurements import Measurements
from rollaway.bench.noise import Noise
from rollaway.identify.residuals import structure_tests
from rollaway.uncertainty.heldout import FOLDS, LOO_TESTS, folds, loto_residuals, loto_scores  # noqa: F401

BIC_THRESHOLD = -10.0        # "very strong" evidence (Kass & Raftery 1995)
CV_TOP = 3                   # cross-validate at most this many candidates per step
SCREEN_ITERATIONS = 6        # a ranking fit's MINPACK budget: SCREEN_ITERATIONS·(k + 1) residual calls
SECOND_EFFECT_SE = 1.0       # a second effect beats the re-formed first by > 1 SE of the held-out difference,
                             # better in more than half of the tests [assumed; 2 SE lost true pairs on 8 tests]
REFORM_ITERATIONS = 8        # Levenberg–Marquardt iterations per pass of the re-formed first effect (its BIC within
                             # 0.01 of the converged fit's on the cases measured, at half the cost)
REFIT_TOP = 2                # screened candidates refitted with the brake parameters free, per step


@dataclass
class Candidate:
    effect: str
    fit: FitResult
    delta_bic: float
    delta_aic: float
    cv_score: float | None = None       # Σ over held-out tests of Σ (residual/σ)², both channels
    cv_better_tests: int | None = None
    step: int = 1                       # forward-selection step in which it was tried
    plan: object = None                 # the parameter plan it was fitted with (its better one)

    def as_dict(self) -> dict:
        return {"effect": self.effect, "rmse_torque_Nm": self.fit.rmse_torque_Nm, "rmse_temp_C": self.fit.rmse_temp_C,
                "delta_bic": self.delta_bic, "delta_aic": self.delta_aic, "bic": self.fit.bic,
                "cv_score": self.cv_score, "cv_better_tests": self.cv_better_tests, "step": self.step,
                "parameters": self.fit.effect_parameters(self.effect), "warnings": self.fit.warnings}


def nested_shortfall(fit: FitResult, base: FitResult) -> str | None:
    """Why *fit*, which frees every parameter *base* frees and more, ends with less of the information criteria's
    likelihood than *base* (at its effect's neutral value it *is* *base*), or None where it does not:

    * ``"traded"``: its noise-weighted sum of squares is below *base*'s, yet BIC's likelihood is not.  A fit
      minimises the sum of squares weighted by the measured noise of both channels; BIC profiles each channel's own
      scale.  Where the torque misses by tens of σ, the fit gives up temperature fit for torque fit (each test's T₀
      moved by several σ to set its torque level) and BIC charges the temperature channel for it (a sigmoid modulus
      drop on 12-s tests at 100 Hz: the modulus law at +166 above the drum alone);
    * ``"short"``: its sum of squares is above *base*'s too: the fit stopped (its budget, another valley) before it
      came back to the drum it contains.

    Either way its ΔBIC above the drum alone is no evidence against the effect."""
    if not set(base.names) <= set(fit.names) or fit.k <= base.k:
        return None
    n = math.log(fit.n_temp + fit.n_torque)
    if (fit.bic - fit.k * n) - (base.bic - base.k * n) <= SHORTFALL_TOLERANCE:
        return None
    return "short" if weighted_chi2(fit) > weighted_chi2(base) + SHORTFALL_TOLERANCE else "traded"


SHORTFALL_WORDS = "above the drum it contains (its fit traded temperature for torque, or stopped short): no evidence"
SHORTFALL_TOLERANCE = 1.0    # −2 ln L (and the weighted sum of squares) above the nested model's: beyond a converged
                             # fit's digits


# -- structure ------------------------------------------------------------------------------
CLEARLY_ABOVE_NOISE = 1.5    # a residual variance this many times the noise's, at p < CLEARLY_P, is structure
CLEARLY_P = 0.025            # 0.05 over the two channels (Bonferroni): 0.05 each gave 3 % false structure on
                             # clean 15-min sets of 40 samples


def structure(fit: FitResult, nq: Noise, nt: Noise) -> dict:
    """Structure tests of both channels' residuals; ``structured`` also when a channel's residual
    variance is clearly above the noise estimate (ratio ≥ :data:`CLEARLY_ABOVE_NOISE` at p < :data:`CLEARLY_P`,
    where the per-test p < 0.001 would need more samples than a sparse bench gives)."""
    rt, rq = fit.residuals()
    kq = fit.effective_parameters.get("torque", len(fit.model.torque_parameters()))
    kt = fit.effective_parameters.get("temperature", len(fit.model.temperature_parameters()))
    out = {"torque": structure_tests(fit.data, rq, nq, kq, sigma=fit.data.torque_sigma_Nm),
           "temperature": structure_tests(fit.data, rt, nt, kt, sigma=fit.data.temp_sigma_C)}
    for ch in ("torque", "temperature"):
        ev = out[ch]["excess_variance"]
        if ev["ratio"] >= CLEARLY_ABOVE_NOISE and ev["p"] < CLEARLY_P:
            out[ch]["structured"] = True
            out[ch]["clearly_above_noise"] = True
    out["structured"] = out["torque"]["structured"] or out["temperature"]["structured"]
    return out


def per_test_signature(fit: FitResult, nq: Noise, within: bool = True) -> bool:
    """True when the torque residual is per-test offsets and nothing else: its test means differ
    (ANOVA p < STRUCTURE_P) and, with each test's mean removed, no structure is left.  Only then may a
    per-test (nuisance) effect stand in the model: otherwise its per-test values would absorb physics.
    *within* False: only that the test means differ (offsets left to take, whatever else is left)."""
    from rollaway.identify.residuals import STRUCTURE_P
    _, rq = fit.residuals()
    d = fit.data
    sig = np.broadcast_to(np.asarray(d.torque_sigma_Nm if d.torque_sigma_Nm is not None else nq.sigma, float),
                          (len(d),))
    kq = fit.effective_parameters.get("torque", len(fit.model.torque_parameters()))
    full = structure_tests(d, rq, nq, kq, sigma=sig)
    if full["test_offsets"]["p"] >= STRUCTURE_P or not within:
        return full["test_offsets"]["p"] < STRUCTURE_P
    w = 1.0 / sig ** 2
    mean = np.bincount(d.test_index, w * rq, d.n_tests) / np.maximum(np.bincount(d.test_index, w, d.n_tests), 1e-300)
    inner = structure_tests(d, rq - mean[d.test_index], nq, kq + d.n_tests, sigma=sig)
    return not any(inner[t]["p"] < STRUCTURE_P for t in ("autocorrelation", "time_profile"))


def has_per_test(effect_name: str) -> bool:
    from rollaway.effects import get_effect
    return any(p.per_test for p in get_effect(effect_name).parameters)


def weighted_chi2(fit: FitResult) -> float:
    return float((fit.rss_torque_weighted or 0.0) + (fit.rss_temp_weighted or 0.0))


# -- cross-validation -----------------------------------------------------------------------
def _restrict(values: dict, families: list[str], keep: np.ndarray) -> dict:
    out = dict(values)
    for f in families:
        if f in out and np.ndim(out[f]) == 1:
            out[f] = np.asarray(out[f])[keep]
    return out


def cv_score(data: Measurements, effects, params, start: FitResult) -> np.ndarray:
    """Leave-one-test-out prediction error (K folds by test beyond :data:`LOO_TESTS` tests): per
    held-out test, Σ (residual/σ)² of both channels under the model calibrated on the other tests,
    only the held-out test's own T_0 and per-test values fitted to it.

    Linearised at the full fit (*start*, which must carry its Jacobian): with J the projected
    Jacobian and r the standardised residual, leaving out the rows g moves the globals by
    (JᵀJ − J_gᵀJ_g)⁻¹·J_gᵀ·r_g, so the held-out residual is r_g + J_g·(JᵀJ − J_gᵀJ_g)⁻¹·J_gᵀ·r_g
    (the exact result for a model linear in its parameters; Woodbury, so no refit and no n×n
    matrix).  Falls back to refitting each fold when the fit has no Jacobian."""
    if start.jacobian is None or not start.names:
        return _cv_refit(data, effects, params, start)
    d = start.data
    loo = loto_residuals(start)
    return np.bincount(np.concatenate([d.test_index, d.test_index]), loo * loo, d.n_tests)


def _cv_refit(data: Measurements, effects, params, start: FitResult) -> np.ndarray:
    """K-fold by test with a refit per fold (warm-started at *start*)."""
    scores = np.zeros(data.n_tests)
    fams = start.model.per_test_parameters()
    glob = start.model.parameter_names()
    for held in folds(data.n_tests):
        out = np.isin(data.test_index, held)
        keep = np.setdiff1d(np.arange(data.n_tests), held)
        train, test = data.subset(~out), data.subset(out)
        fit = calibrate(train, effects, params, start=_restrict(start.values, fams, keep), statistics=False)
        vals = {n: fit.values[n] for n in glob}
        vals.update(_restrict(start.values, fams, np.asarray(held)))
        pred = calibrate(test, effects, params, free=[], start=vals, statistics=False)
        r = np.concatenate([(test.drum_temp_C - pred.prediction.drum_temp_C) / test.temp_sigma_C,
                            (test.torque_Nm - pred.prediction.torque_Nm) / test.torque_sigma_Nm])
        scores[np.asarray(held)] = np.bincount(np.concatenate([test.test_index, test.test_index]), r * r,
                                               test.n_tests)
    return scores


# -- the steps ---------------------------------------------------------------------------
def forward_step(data, params, names, current: FitResult, chosen: list[str], step: int,
                 per_test_ok: bool = True, screen: bool = False, held_brake=()):
    """Fit every remaining candidate on top of *current*; cross-validate the strong ones.  Effects
    with per-test parameters are tried only when *per_test_ok* (:func:`per_test_signature`).
    After the first step (whose table reports every candidate's ΔBIC) a screen that cannot come within
    :data:`BIC_THRESHOLD` of *current* is given up (:func:`rollaway.identify.solver.futile`).
    *screen*: fit the candidates with the brake parameters held, then refit the best few jointly
    (faster, but an effect the calibrated drum has partly absorbed can be missed).  *held_brake*: brake
    parameters the drum calibration held as not needed; a candidate that changes the law of some of them (the
    cooling law, eq. (24)'s displacement) is fitted with those free (:func:`own_channel_plan`) and with them held,
    and ranked by the better of the two."""
    start = {k: v for k, v in current.values.items()}
    held, n_held = _held_plan(params, current) if screen else (params, 0)
    tried, calls, plans = [], [], []
    for name in names:
        if name in chosen or (not per_test_ok and has_per_test(name)):
            continue
        own = own_channel_plan(params, name, held_brake)
        for plan in ((own,) if own is params else (own, params)):     # a law the bare drum held: freed, and held
            if has_per_test(name) and held is params:      # per-test fits are the costly ones: screen them
                h, k = _held_plan(plan, current)
                calls.append((_per_test_screen, (chosen + [name], h, plan), dict(start=start)))
            elif held is params:                            # a short joint fit ranks; the best few are finished below
                h, k = plan, 0
                bar = {} if step == 1 else {"give_up_bic": current.bic + BIC_THRESHOLD + FUTILE_MARGIN}
                calls.append((calibrate, (chosen + [name], plan), dict(start=start, max_iterations=SCREEN_ITERATIONS,
                                                                       **bar)))
            else:
                h, k = held, n_held
                calls.append((calibrate, (chosen + [name], held), dict(start=start)))     # brake parameters held
            tried.append(name)
            plans.append((h, k, plan))
    every = [Candidate(name, fit, fit.bic + k * np.log(2 * len(data)) * (h is not params) - current.bic,
                       fit.aic + 2 * k * (h is not params) - current.aic, step=step)
             for name, (h, k, _), fit in zip(tried, plans, run_fits(data, calls))]
    plan_of, cands = {}, []
    for c, (_, _, plan) in sorted(zip(every, plans), key=lambda t: t[0].delta_bic):
        if c.effect not in plan_of:                     # each effect by its better plan
            plan_of[c.effect] = c.plan = plan
            cands.append(c)
    top = [c for c in cands[:REFIT_TOP] if held is not params or not has_per_test(c.effect)]
    for c, fit in zip(top, run_fits(data, [(calibrate, (chosen + [c.effect], plan_of[c.effect]),
                                            dict(start=c.fit.values)) for c in top])):
        c.fit = fit                                             # the best few refitted with the brake parameters free
        c.delta_bic, c.delta_aic = c.fit.bic - current.bic, c.fit.aic - current.aic
    cands.sort(key=lambda c: c.delta_bic)
    strong = [c for c in cands if c.delta_bic < BIC_THRESHOLD and c.fit.jacobian is not None
              or c.delta_bic < BIC_THRESHOLD and held is params][:CV_TOP]
    cur_cv = None
    if strong:
        cur_scores = cv_score(data, chosen, params, current)
        cur_cv = float(cur_scores.sum())
        for c in strong:
            s = cv_score(data, chosen + [c.effect], plan_of[c.effect], c.fit)
            c.cv_score = float(s.sum())
            c.cv_better_tests = int((s < cur_scores).sum())
    passing = [c for c in strong if c.cv_score is not None and c.cv_score < cur_cv]
    return cands, strong, passing, cur_cv


def own_channel_plan(params, name: str, held_brake=()):
    """*params* with the brake parameters of *held_brake* (held as not needed by the bare drum) whose law the effect
    *name* changes freed (:attr:`rollaway.model.drum_parameters.FreeParameter.law`: the hook whose input that law
    sets).  The bare drum held them under a model without the effect: an effect that changes the cooling law
    (radiation) is compared with h and T_amb free, since with the convective h held at a value the bare drum agreed
    with, no added cooling can fit (the convection it must give back is held); one that changes the lining
    displacement (a cable that loses a displacement, not a fraction) with eq. (24)'s slope and offset free, since
    the share of the torque such a loss takes at each hand force is set by them.  *params* itself when there are
    none."""
    from rollaway.effects import get_effect
    from rollaway.identify.model import DrumPlan
    from rollaway.model.drum_parameters import FREE_PARAMETERS
    if not held_brake or not isinstance(params, DrumPlan):
        return params
    hooks = set(get_effect(name).overridden_hooks())
    add = tuple(n for n in held_brake if FREE_PARAMETERS[n].law in hooks and n not in params.free)
    return DrumPlan(params.params, params.free + add) if add else params


def _per_test_screen(data, effects, held, params, start):
    """A per-test effect's screen: fitted with the brake parameters *held*, then with those of *params* free."""
    fit = calibrate(data, effects, held, start=start)
    return calibrate(data, effects, params, start=fit.values, statistics=True)


def _held_plan(params, current: FitResult):
    """The plan of *current* with its brake parameters held at their fitted values (for screening)."""
    from rollaway.model.drum_parameters import apply
    from rollaway.identify.model import DrumPlan
    free = current.model.free
    if not isinstance(params, DrumPlan) or not free:
        return params, 0
    return DrumPlan(apply(params.params, {n: current.values[n] for n in free}), ()), len(free)


def exchange(data, params, names, chosen, current, struct, nq, nt, rounds: int = 1, known=()):
    """Stepwise exchange: replace a selected effect by an unselected one while BIC improves and the
    residual stays as clean (forward selection can pick an effect that absorbs part of a later one).
    *known*: the candidates of the forward step that added the last selected effect (:func:`forward_step`): a
    swap of that last effect is their own effect set, and where one was fitted with *params* its fit ranks the
    swap (the step compared them all already) instead of a new screen."""
    swaps = []
    last = {tuple(chosen[:-1] + [c.effect]): c.fit for c in known if c.plan == params}
    for _ in range(rounds):
        best = None
        per_test_ok = per_test_signature(current, nq)
        swaps_tried = [(i, new) for i in range(len(chosen)) for new in names
                       if new not in chosen and not (has_per_test(new) and not per_test_ok)]
        trials = [chosen[:i] + [new] + chosen[i + 1:] for i, new in swaps_tried]
        todo = [t for t in trials if tuple(t) not in last]
        done = dict(zip(map(tuple, todo), run_fits(data, [
            (calibrate, (t, params), dict(start=current.values, statistics=False, max_iterations=SCREEN_ITERATIONS,
                                          give_up_bic=current.bic + FUTILE_MARGIN))
            for t in todo])))
        fits = [last[tuple(t)] if tuple(t) in last else done[tuple(t)] for t in trials]
        last = {}                             # a later round starts from a swapped selection
        for (i, new), fit in zip(swaps_tried, fits):
            if fit.bic < current.bic - 2.0 and (best is None or fit.bic < best[2].bic):
                best = (i, new, fit)
        if best is None:
            break
        i, new, _ = best
        trial = chosen[:i] + [new] + chosen[i + 1:]
        fit = calibrate(data, trial, params, start=best[2].values)
        s = structure(fit, nq, nt)
        if s["structured"] and not struct["structured"]:
            break
        swaps.append((chosen[i], new, fit.bic - current.bic))
        chosen, current, struct = trial, fit, s
    return chosen, current, struct, swaps


def eliminate(data, params, chosen, current, struct, nq, nt):
    """Backward elimination: drop a selected effect when the model without it has the lower BIC and a
    residual as clean."""
    removed = []
    while len(chosen) >= 2:
        trials = list(zip(run_fits(data, [(calibrate, (chosen[:i] + chosen[i + 1:], params), dict(start=current.values))
                                          for i in range(len(chosen))]), range(len(chosen))))
        fit, i = min(trials, key=lambda t: t[0].bic)
        if fit.bic >= current.bic:
            break
        s = structure(fit, nq, nt)
        if s["structured"] and not struct["structured"]:
            break
        removed.append((chosen[i], fit.bic - current.bic))
        chosen, current, struct = chosen[:i] + chosen[i + 1:], fit, s
    return chosen, current, struct, removed


# -- a second effect on its own evidence ---------------------------------------------------
