"""The user's drum: which brake parameters the bench data identify, calibrated before any effect is sought.

A bench rig tests *its* drum, not the paper's.  :func:`calibrate_drum` frees one name per
identifiable product of the chain (:mod:`rollaway.model.drum_parameters`: μ_d for the torque scale,
the eq. (24) slope and offset, the arm ratio l_fr/l_f, h, the ambient when not logged) and
decides which of them these data determine:

1. *not tested*: the test design cannot show it (one direction → the arm ratio, which only
   shows in the downhill/uphill ratio; a logged ambient is read, not fitted);
2. the rest are fitted jointly (each test's T_0 profiled out); the Jacobian, with each column
   in units of the parameter's assumed spread (``prior_sd``) and each channel's rows scaled by
   its residual variance factor, is decomposed into singular values.  While the smallest is
   below :data:`MIN_SINGULAR_VALUE` (the data pin that combination down less than a third of
   the assumed spread), the parameter that loads most on it (ties broken by
   :data:`FIX_FIRST`) is fixed at its assumed value and reported as *confounded with* the
   others that load on the same direction; then the fit is repeated;
3. what is left is pruned by BIC (backward elimination): a parameter whose freeing does not lower
   BIC — the data agree with its assumed value — is held there ("not needed"); μ_d always stays.

``free=`` and ``fix=`` override the choice.  Fixed and untested parameters keep their doubt:
:func:`predictive_covariance` adds their assumed spread as a Gaussian prior to the fit's
information, so a draw for an untested direction varies the arm ratio while the tested
direction's torque stays where the data put it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.model.drum_parameters import BASELINE_FREE, FREE_PARAMETERS, apply, value_of
from rollaway.errors import UserError, suggest
from rollaway.identify.calibrate import FitResult, calibrate, jacobian_at
from rollaway.identify.workers import fit_all
from rollaway.bench.measurements import Measurements
from rollaway.identify.model import DrumPlan
from rollaway.identify.drum_status import ParameterStatus
from rollaway.identify.enough import require
from rollaway.model.drum_model import Covariance
from rollaway.model.parameters import BrakeParameters, load_parameters

MIN_SINGULAR_VALUE = 3.0       # data must determine a direction to ≤ 1/3 of the assumed spread [assumed]
CONFOUND_LOADING = 0.3         # share of the weak direction (|loading|·column norm) that counts as "confounded with"
FIX_FIRST = ("ambient_temp_C", "shoe_arm_ratio", "u6_offset_m", "u6_slope_m_per_N", "heat_transfer_W_m2K",
             "mu_drum")        # among near-equal loadings, fix the earlier one (keep the torque scale longest)
UNIDENTIFIED = "not identifiable from these data"     # the bare drum's reason for a weak direction it fixed


@dataclass
class DrumCalibration:
    """What the bench data say about the user's drum: the plan for every later fit, the fit, the report."""

    params: BrakeParameters          # the set the data were fitted against (logged ambient written in)
    entries: dict[str, ParameterStatus]
    fit: FitResult
    singular_values: list[float]
    selection: str                   # how the free set was chosen

    @property
    def free(self) -> tuple[str, ...]:
        return tuple(n for n, e in self.entries.items() if e.status == "fitted")

    @property
    def plan(self) -> DrumPlan:
        return DrumPlan(self.params, self.free)

    def held(self) -> tuple[str, ...]:
        """Brake parameters the automatic choice held as *not needed* by the bare drum (the data test them and
        agreed with the assumed value); none when the user chose the free set."""
        if self.selection.startswith("chosen by you"):
            return ()
        return tuple(n for n, e in self.entries.items() if e.status == "fixed" and "not needed" in e.reason)

    def departures(self) -> tuple[str, ...]:
        """:meth:`held`, and the brake parameters held because torque and temperature logs cannot tell them from
        another: the gap, which adds to the lining thickness in eq. (16b), and those the bare drum fixed as not
        identifiable (the eq. (24) offset beside μ_d on one direction: their assumed values are a guess the data
        could not check).  The departures of a drum from the set that a second effect must not stand in for (:func:`rollaway.identify.partner.own_evidence` frees them in
        both fits it compares).  None when the user chose the free set."""
        if self.selection.startswith("chosen by you"):
            return ()
        return self.held() + tuple(n for n, e in self.entries.items()
                                   if e.status == "fixed" and (not FREE_PARAMETERS[n].automatic
                                                               or e.reason.startswith(UNIDENTIFIED)))

    def fixed_priors(self) -> dict[str, float]:
        """Assumed spreads of the brake parameters left at their assumed values (for the bands)."""
        return {n: e.prior_sd for n, e in self.entries.items() if e.prior_sd and e.status != "fitted"}

    def refree(self, fit: FitResult, reason: str) -> None:
        """Mark the brake parameters *fit* frees that this calibration held as fitted, with *fit*'s estimates."""
        for n in fit.model.free:
            e = self.entries.get(n)
            if e is not None and e.status != "fitted":
                est = fit.estimates[n]
                e.status, e.value, e.stderr, e.ci95, e.prior_sd = "fitted", est.value, est.stderr, tuple(est.ci95), None
                e.reason = reason

    def update(self, fit: FitResult) -> None:
        """Refresh the fitted entries from a later fit of the same plan (e.g. with effects)."""
        for n, e in self.entries.items():
            if n in fit.estimates:
                est = fit.estimates[n]
                e.value, e.stderr, e.ci95 = est.value, est.stderr, tuple(est.ci95)
        self.fit = fit

    def as_dict(self) -> dict:
        return {"selection": self.selection, "singular_values": self.singular_values,
                "parameters": {n: e.as_dict() for n, e in self.entries.items()}}

    def report(self) -> str:
        lines = [f"Your drum ({self.selection}):"]
        lines += [e.line() for e in self.entries.values()]
        return "\n".join(lines)

    def record(self) -> dict:
        """The model file's ``[calibration]`` table: one short text per brake parameter."""
        out = {}
        for n, e in self.entries.items():
            if e.status == "fitted":
                out[n] = f"fitted: {e.value:.6g} ± {e.stderr:.3g} {e.unit}".rstrip()
            else:
                out[n] = f"{e.status}: {e.value:.6g} {e.unit} — {e.reason}".rstrip()
        return out


def _check_names(names, flag: str) -> list[str]:
    out = []
    for n in names or ():
        if n not in FREE_PARAMETERS:
            raise UserError(f"{flag} {n}: not a brake parameter a calibration can free{suggest(n, BASELINE_FREE)}; "
                            f"choose from {', '.join(BASELINE_FREE)}")
        out.append(n)
    return out


def calibrate_drum(data: Measurements, params=None, *, free=None, fix=(), start: dict | None = None,
                   min_singular_value: float = MIN_SINGULAR_VALUE) -> DrumCalibration:
    """Calibrate the brake parameters these data identify (module docstring); *free*/*fix* override."""
    free, fix = _check_names(free, "--free"), _check_names(fix, "--fix")
    both = sorted(set(free) & set(fix))
    if both:
        raise UserError(f"--free {both[0]} and --fix {both[0]} contradict each other; give it once")
    p = params if isinstance(params, BrakeParameters) else load_parameters(params)
    logged = data.ambient_C is not None
    if logged:
        p = p.replace(ambient_temp_C=float(np.mean(data.ambient_C)))
    assumed = {n: value_of(p, n) for n in BASELINE_FREE}
    entries: dict[str, ParameterStatus] = {}

    def fixed(name, status, reason, confounded=(), prior=True):
        spec = FREE_PARAMETERS[name]
        entries[name] = ParameterStatus(name, status, assumed[name], assumed[name], spec.unit,
                                        prior_sd=spec.spread(assumed[name]) if prior else None,
                                        confounded_with=list(confounded), reason=reason)

    directions = np.unique(data.sign)
    candidates = []
    for n in BASELINE_FREE:
        if n in fix:
            fixed(n, "fixed by you", "held at its value by --fix")
        elif n == "ambient_temp_C" and logged:
            fixed(n, "logged", "read from the bench's ambient column (its mean is the model's ambient)", prior=False)
        elif not FREE_PARAMETERS[n].automatic and not free:
            fixed(n, "fixed", f"held at the set's value: torque and temperature logs cannot tell it from "
                              f"{', '.join(FREE_PARAMETERS[n].confounded_with)} (free it with --free)",
                  FREE_PARAMETERS[n].confounded_with)
        elif free:
            if n in free:
                candidates.append(n)
            else:
                fixed(n, "fixed by you", "not in --free")
        elif n == "shoe_arm_ratio" and directions.size < 2:
            side = "downhill" if directions[0] > 0 else "uphill"
            fixed(n, "not tested", f"only {side} tests: the arm ratio shows only in the downhill/uphill torque ratio")
        else:
            candidates.append(n)
    selection = ("chosen by you (--free)" if free else
                 f"free parameters chosen by singular values ≥ {min_singular_value:g} of the Jacobian in units of "
                 f"each parameter's assumed spread")
    require(data, len(candidates) + data.n_tests, "calibrate the drum")
    vals = dict(start or {})
    sv: list[float] = []
    while True:
        fit = calibrate(data, (), DrumPlan(p, tuple(candidates)), start=vals or None)
        vals = {k: v for k, v in fit.values.items()}
        if free or not candidates or fit.jacobian is None:
            break
        sv, drop, confounded = _weakest(fit, candidates)
        if drop is None or sv[-1] >= min_singular_value:
            break
        others = f", confounded with {', '.join(confounded)}" if confounded else ""
        fixed(drop, "fixed", f"{UNIDENTIFIED} (singular value {sv[-1]:.3g} < "
                             f"{min_singular_value:g}){others}", confounded)
        candidates.remove(drop)
        vals.pop(drop, None)
    if not free and fit.jacobian is not None:
        fit, vals = _prune(data, p, candidates, fit, vals, fixed)
    for n in candidates:
        est = fit.estimates[n]
        entries[n] = ParameterStatus(n, "fitted", est.value, assumed[n], est.unit, est.stderr, tuple(est.ci95))
    ordered = {n: entries[n] for n in BASELINE_FREE}
    return DrumCalibration(p, ordered, fit, [float(x) for x in sv], selection)


def _prune(data, p, candidates: list[str], fit: FitResult, vals: dict, fixed):
    """Backward elimination by BIC: a brake parameter whose freeing does not lower BIC is held at its assumed
    value (the data agree with it); the torque scale is always fitted.  *candidates* is pruned in place."""
    while len(candidates) > 1:
        names = [n for n in candidates if n != "mu_drum"]
        trials = list(zip(fit_all(data, [((), DrumPlan(p, tuple(c for c in candidates if c != n)),
                                          dict(start={k: v for k, v in vals.items() if k != n})) for n in names]),
                          names))                       # each held back in turn, side by side on the cores
        if not trials:
            break
        best, name = min(trials, key=lambda t: t[0].bic)
        gain = best.bic - fit.bic
        if gain > 0.0:
            break
        fixed(name, "fixed", f"not needed: the data agree with the assumed value (freeing it would change BIC by "
                             f"{-gain:+.1f})")
        candidates.remove(name)
        fit, vals = best, {k: v for k, v in best.values.items()}
    return fit, vals


def recheck(drum: DrumCalibration, data: Measurements, fit: FitResult, effects: list) -> FitResult:
    """Re-test the brake parameters' identifiability inside the final model (with its *effects*): an
    effect can take over what a brake parameter did (per-test offsets absorb the eq. (24) law, for
    one).  Parameters that lost their information are fixed at their assumed values (their doubt kept
    for the bands) and the model refitted; returns the (possibly refitted) fit."""
    if drum.selection.startswith("chosen by you") or not effects or fit.jacobian is None:
        return fit
    free = [n for n in drum.free if n in fit.names]
    while free:
        sv, drop, confounded = _weakest(fit, free)
        if drop is None or sv[-1] >= MIN_SINGULAR_VALUE:
            break
        with_effects = [c for c in confounded if "." in c] or effects
        e = drum.entries[drop]
        e.status, e.value, e.stderr, e.ci95 = "fixed", e.assumed_value, None, None
        e.prior_sd = FREE_PARAMETERS[drop].spread(e.assumed_value)
        e.confounded_with = confounded
        e.reason = (f"not identifiable once {', '.join(sorted({c.split('.')[0] for c in with_effects}))} is in the "
                    f"model (singular value {sv[-1]:.3g} < {MIN_SINGULAR_VALUE:g})"
                    + (f", confounded with {', '.join(confounded)}" if confounded else ""))
        free.remove(drop)
        vals = {k: v for k, v in fit.values.items() if k != drop}
        fit = calibrate(data, effects, drum.plan, start=vals)
    return fit


def free_needed(drum: DrumCalibration, data: Measurements, effects: list, fit: FitResult,
                names=None) -> FitResult | None:
    """Free again the brake parameters the bare drum held as not needed (:meth:`DrumCalibration.held`; or those
    of *names*) that the model with *effects* needs: forward selection by BIC — each held one freed beside *fit*
    (side by side on the cores), the best kept while it lowers BIC, then the next beside it.  Those kept become
    "fitted" (so :attr:`DrumCalibration.plan` frees them) and the fit is returned; else None and nothing changes.

    Freeing them all at once and holding them back one at a time (backward elimination) costs a fit of every
    parameter together, which crawls where some are barely identified, and frees pairs that only together
    lower BIC, by as little as 1."""
    held = [n for n in (drum.held() if names is None else names) if n not in drum.free]
    if not held or fit.jacobian is None:
        return None
    best, freed = fit, []
    while held:
        trials = list(zip(fit_all(data, [(effects, DrumPlan(drum.params, drum.free + tuple(freed) + (n,)),
                                          dict(start=dict(best.values))) for n in held]), held))
        trial, name = min(trials, key=lambda t: t[0].bic)
        if trial.bic >= best.bic or trial.jacobian is None:
            break
        held.remove(name)
        freed.append(name)
        best = trial
    if not freed:
        return None
    drum.refree(best, f"needed once {', '.join(effects)} is in the model (BIC {best.bic - fit.bic:+.1f})")
    return best


def _scaled_jacobian(fit: FitResult, jac: np.ndarray, names: list[str]) -> np.ndarray:
    """Jacobian (rows already per noise σ) with columns per assumed spread.  The rows are not rescaled
    by the fit's variance factor: a model still missing an effect fits worse, but the noise — what
    the identifiability is measured against — is the model-free estimate."""
    spread = np.array([_spread(fit, m) for m in names])
    return jac * spread[None, :]


def _spread(fit: FitResult, name: str) -> float:
    if name in FREE_PARAMETERS:
        return FREE_PARAMETERS[name].spread(fit.values.get(name, value_of(fit.model.params, name)))
    lo, hi = fit.model.bounds(name)
    return 0.25 * (hi - lo)


def _weakest(fit: FitResult, names: list[str]):
    """Singular values (descending) of the brake parameters *names* (the fit's other parameters
    profiled out) and the one to fix on the weakest direction, with what it is confounded with."""
    others = [i for i, n in enumerate(fit.names) if n not in names]
    cols = [fit.names.index(n) for n in names]
    jall = _scaled_jacobian(fit, fit.jacobian, list(fit.names))
    jall = np.where(np.isfinite(jall), jall, 0.0)
    j = jall[:, cols]
    if others:      # project out the effects' parameters: what the brake parameters alone still explain
        q, _ = np.linalg.qr(jall[:, others])
        j = j - q @ (q.T @ j)
    _, s, vt = np.linalg.svd(j, full_matrices=False)
    v = np.abs(vt[-1])
    big = [names[i] for i in np.flatnonzero(v >= 0.7 * v.max())]
    drop = min(big, key=FIX_FIRST.index)
    # what each parameter puts into the near-null combination j·v: |v_i|·‖j_i‖ (loadings alone favour the
    # column with the smaller scale: two exactly collinear columns of scales 1 and 6 load 0.99 and 0.16)
    part = v * np.linalg.norm(j, axis=0)
    confounded = [names[i] for i in np.flatnonzero(part >= CONFOUND_LOADING * part.max()) if names[i] != drop]
    if others:      # the effect parameters that share the direction
        a = jall[:, others]
        w = np.linalg.lstsq(a, jall[:, cols] @ vt[-1], rcond=None)[0]
        share = np.abs(w) / max(np.abs(w).max(), 1e-300)
        confounded += [fit.names[others[i]] for i in np.flatnonzero(share >= 0.5)]
    return list(s), drop, confounded


def predictive_covariance(fit: FitResult, priors: dict[str, float], inflation: dict | None = None) -> Covariance | None:
    """Covariance of the fit's parameters and of the brake parameters it held fixed (*priors*: their
    assumed spreads), from the data's information plus a Gaussian prior on the fixed ones (a held parameter
    whose catalogue effect the fit has, e.g. ``gap_m`` beside ``installation_gap``, is the effect's); an effect's
    held parameters (``EffectParameter.held``, e.g. how far a shape-free temperature law goes on beyond its hottest
    knot) with their ``prior_sd``.  *inflation*:
    channel → factor on that channel's variance factor (autocorrelated residuals,
    :func:`rollaway.identify.intervals.ess_inflation`)."""
    fitted_effects = {e.name for e in getattr(fit.model, "effects", ())}
    priors = {n: sd for n, sd in priors.items()
              if not (n in FREE_PARAMETERS and FREE_PARAMETERS[n].effect in fitted_effects)}
    priors.update({f"{e.name}.{p.name}": p.prior_sd for e in getattr(fit.model, "effects", ())
                   for p in e.parameters if p.held and p.prior_sd})       # an effect's held parameters: assumed
    names = list(fit.names) + [n for n in priors if n not in fit.names]
    if not names:
        return None
    jac = jacobian_at(fit, names)
    n = len(fit.data)
    k = inflation or {}
    phi = np.concatenate([np.full(n, max(fit.variance_factor.get("temperature", 1.0) * k.get("temperature", 1.0), 1e-300)),
                          np.full(n, max(fit.variance_factor.get("torque", 1.0) * k.get("torque", 1.0), 1e-300))])
    jw = jac / np.sqrt(phi)[:, None]
    info = jw.T @ jw
    prior = np.array([1.0 / priors[m] ** 2 if m in priors else 0.0 for m in names])
    info = info + np.diag(prior)
    scale = np.sqrt(np.maximum(np.diag(info), 1e-300))
    scaled = np.linalg.pinv(info / np.outer(scale, scale), rcond=1e-12)     # in scaled units: all of order one
    scaled = 0.5 * (scaled + scaled.T)
    w, v = np.linalg.eigh(scaled)
    cov = ((v * np.clip(w, 0.0, None)) @ v.T) / np.outer(scale, scale)       # PSD, then back to the units
    cov = 0.5 * (cov + cov.T)             # exactly symmetric (a prior-held column leaves rounding-sized asymmetry)
    keep = [i for i, m in enumerate(names) if np.isfinite(cov[i, i]) and cov[i, i] > 0]
    if not keep:
        return None
    return Covariance(tuple(names[i] for i in keep), cov[np.ix_(keep, keep)])


__all__ = ["DrumCalibration", "ParameterStatus", "calibrate_drum", "free_needed", "predictive_covariance",
           "MIN_SINGULAR_VALUE"]
