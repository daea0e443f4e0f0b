"""Which physical effect is the model missing?  Calibrate, fit each candidate, rank, decide.

1. Calibrate the baseline (μ_d, h).  Estimate the noise of each channel without the physics
   (:func:`rollaway.identify.residuals.noise_estimate`).
2. Fit every candidate effect jointly with μ_d and h; rank by BIC (both channels).
3. Candidates with ΔBIC < −10 against the baseline are cross-validated leave-one-test-out:
   each test is predicted by a model calibrated on the others; the candidate must predict
   the held-out tests better than the baseline does.
4. The verdict is the best candidate that passes both — *and* leaves no structure in the
   residual.  If it leaves structure, the tool says none of the catalogue explains the data
   (verdict ``none``, ``remaining_structure: true``).  Without a passing candidate the verdict
   is ``none``; ``remaining_structure`` then says whether the baseline residual is structured.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from rollaway.jsonsafe import to_jsonable

from rollaway.identify.calibrate import FitResult, calibrate, evaluate
from rollaway.effects import available_effects, get_effect
from rollaway.identify.measurements import Measurements
from rollaway.identify.residuals import Noise, association, noise_estimate, structure_tests, trend_words

BIC_THRESHOLD = -10.0        # "very strong" evidence (Kass & Raftery 1995)
INDISTINGUISHABLE_BIC = 6.0  # candidates within this ΔBIC of the best cannot be told apart
CV_TOP = 4                   # cross-validate at most this many candidates


@dataclass
class Candidate:
    effect: str
    fit: FitResult
    delta_bic: float
    delta_aic: float
    cv_score: float | None = None       # Σ over held-out tests of SSE/σ², both channels
    cv_better_tests: int | None = None

    def as_dict(self) -> dict:
        return {"effect": self.effect, "rmse_torque_Nm": self.fit.rmse_torque_Nm, "rmse_temp_C": self.fit.rmse_temp_C,
                "delta_bic": self.delta_bic, "delta_aic": self.delta_aic, "bic": self.fit.bic,
                "cv_score": self.cv_score, "cv_better_tests": self.cv_better_tests,
                "parameters": self.fit.effect_parameters(self.effect), "warnings": self.fit.warnings}


@dataclass
class Diagnosis:
    data: Measurements
    paper: FitResult
    baseline: FitResult
    noise_torque: Noise
    noise_temp: Noise
    candidates: list[Candidate]
    verdict: str
    indistinguishable_from: list[str]
    refined: FitResult
    remaining_structure: bool
    structure: dict
    baseline_cv: float | None
    evidence: list[str] = field(default_factory=list)

    def as_dict(self) -> dict:
        def rm(f):
            return {"rmse_torque_Nm": f.rmse_torque_Nm, "rmse_temp_C": f.rmse_temp_C, "bic": f.bic, "aic": f.aic,
                    "parameters": {k: e.as_dict() for k, e in f.estimates.items()}}
        return {"data": {"source": self.data.source, "samples": len(self.data), "tests": self.data.n_tests},
                "noise": {"torque_Nm": self.noise_torque.sigma, "temp_C": self.noise_temp.sigma},
                "paper": {"rmse_torque_Nm": self.paper.rmse_torque_Nm, "rmse_temp_C": self.paper.rmse_temp_C},
                "baseline": {**rm(self.baseline), "cv_score": self.baseline_cv},
                "candidates": [c.as_dict() for c in self.candidates],
                "verdict": self.verdict, "indistinguishable_from": self.indistinguishable_from,
                "refined": {"effects": self.refined.effects, **rm(self.refined)},
                "remaining_structure": self.remaining_structure, "structure": self.structure,
                "evidence": self.evidence}

    def to_json(self, path=None) -> str:
        text = json.dumps(to_jsonable(self.as_dict()), indent=2)
        if path is not None:
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text + "\n")
        return text

    def summary(self) -> str:
        lines = [f"verdict: {self.verdict}"]
        lines += [f"  {w}" for w in self.evidence]
        lines.append("")
        lines.append(f"{'candidate':<28}{'ΔBIC':>9}{'torque RMSE':>13}{'temp RMSE':>11}{'CV score':>10}")
        lines.append(f"{'(baseline)':<28}{0.0:>9.1f}{self.baseline.rmse_torque_Nm:>13.3g}"
                     f"{self.baseline.rmse_temp_C:>11.3g}{_f(self.baseline_cv):>10}")
        for c in self.candidates:
            lines.append(f"{c.effect:<28}{c.delta_bic:>9.1f}{c.fit.rmse_torque_Nm:>13.3g}{c.fit.rmse_temp_C:>11.3g}"
                         f"{_f(c.cv_score):>10}")
        lines.append("")
        lines.append(self.refined.report())
        return "\n".join(lines)

    def __repr__(self):
        return self.summary()

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import diagnosis_html
        return diagnosis_html(self)

    def report(self, path) -> None:
        from rollaway.identify.report import diagnosis_report
        diagnosis_report(self, path)


def _f(x):
    return "–" if x is None else f"{x:.1f}"


def channel_noise(data: Measurements, fit: FitResult) -> tuple[Noise, Noise]:
    tau = fit.model.state(data, fit.values).cooling_time_constant_s
    nq = (noise_estimate(data, data.torque_Nm, tau, relative=True)
          or Noise(max(fit.rmse_torque_Nm, 1e-9), max(fit.n_torque - 2, 1), max(fit.rmse_torque_Nm, 1e-9)))
    nt = noise_estimate(data, data.drum_temp_C, tau) or Noise(max(fit.rmse_temp_C, 1e-9), max(fit.n_temp - 1, 1))
    return nq, nt


def structure(fit: FitResult, nq: Noise, nt: Noise) -> dict:
    rt, rq = fit.residuals()
    hot = fit.data.time_s > 0
    kq, kt = len(fit.model.torque_parameters()), len(fit.model.temperature_parameters())
    out = {"torque": structure_tests(fit.data, rq, nq, kq, sigma=fit.data.torque_sigma_Nm),
           "temperature": structure_tests(fit.data, rt, nt, kt, hot)}
    out["structured"] = out["torque"]["structured"] or out["temperature"]["structured"]
    return out


def cv_score(data: Measurements, effects, params, nq: Noise, nt: Noise, start: dict) -> np.ndarray:
    """Leave-one-test-out: per held-out test, SSE/σ² of both channels under a model fitted to the rest."""
    scores = np.zeros(data.n_tests)
    for i in range(data.n_tests):
        train, test = data.subset(data.test_index != i), data.subset(data.test_index == i)
        fit = calibrate(train, effects, params, start=start)
        pred = fit.model.predict(test, fit.values)
        hot = test.time_s > 0
        sig = nq.sigma if test.torque_sigma_Nm is None else test.torque_sigma_Nm
        scores[i] = (float((((test.torque_Nm - pred.torque_Nm) / sig) ** 2).sum())
                     + float(((test.drum_temp_C - pred.drum_temp_C)[hot] ** 2).sum()) / nt.sigma ** 2)
    return scores


def _describe_residual(fit: FitResult, noise: Noise, channel: str) -> str:
    rt, rq = fit.residuals()
    r, unit, mask = (rq, "N·m", None) if channel == "torque" else (rt, "°C", fit.data.time_s > 0)
    assoc = association(fit.data, r, fit.prediction.drum_temp_C, mask)
    name, share = assoc[0]
    words = trend_words(fit.data, r, fit.prediction.drum_temp_C, name, mask)
    return (f"the {channel} residual followed {name} most ({share:.0%} of its variance explained by {name} "
            f"alone; it {words})")


def diagnose(data: Measurements, params=None, effects=None) -> Diagnosis:
    """Rank *effects* (default: the whole catalogue plus registered plugins) against *data*."""
    names = list(available_effects()) if effects is None else [get_effect(e).name for e in effects]
    data = data.subset(np.ones(len(data), bool))          # a copy that carries the noise model
    first = calibrate(data, (), params)
    nq, nt = channel_noise(data, first)
    data.torque_sigma_Nm = np.maximum(nq.at(first.prediction.torque_Nm), 1e-9)
    paper = evaluate(data, (), params)
    base = calibrate(data, (), params, start=first.values)
    start = {"mu_drum": base.values["mu_drum"], "heat_transfer_W_m2K": base.values["heat_transfer_W_m2K"]}
    cands = []
    for name in names:
        fit = calibrate(data, [name], params, start=start)
        cands.append(Candidate(name, fit, fit.bic - base.bic, fit.aic - base.aic))
    cands.sort(key=lambda c: c.delta_bic)
    strong = [c for c in cands if c.delta_bic < BIC_THRESHOLD][:CV_TOP]
    base_cv = None
    if strong:
        base_scores = cv_score(data, (), params, nq, nt, start)
        base_cv = float(base_scores.sum())
        for c in strong:
            s = cv_score(data, [c.effect], params, nq, nt, {**start, **c.fit.values})
            c.cv_score = float(s.sum())
            c.cv_better_tests = int((s < base_scores).sum())
    passing = [c for c in strong if c.cv_score is not None and c.cv_score < base_cv]
    base_struct = structure(base, nq, nt)
    ev = [f"Noise level (per-test smooth curves, no physics): torque σ ≈ {nq.sigma:.3g} N·m (√({nq.absolute:.3g}² + "
          f"({nq.relative:.2%}·torque)²)), drum temperature σ ≈ {nt.sigma:.3g} °C.",
          f"Paper defaults: torque RMSE {paper.rmse_torque_Nm:.3g} N·m, temperature RMSE {paper.rmse_temp_C:.3g} °C. "
          f"Calibrated baseline (μ_d = {base.values['mu_drum']:.4g}, h = {base.values['heat_transfer_W_m2K']:.4g} "
          f"W/(m² K)): {base.rmse_torque_Nm:.3g} N·m and {base.rmse_temp_C:.3g} °C; "
          + _describe_residual(base, nq, "torque") + "; " + _describe_residual(base, nt, "temperature") + "."]
    verdict, indist, refined, remaining, struct = "none", [], base, base_struct["structured"], base_struct
    if passing:
        best = passing[0]
        best_struct = structure(best.fit, nq, nt)
        effect = get_effect(best.effect)
        ev.append(f"Adding {best.effect} lowers BIC by {-best.delta_bic:.1f} (threshold {-BIC_THRESHOLD:g}); torque RMSE "
                  f"{base.rmse_torque_Nm:.3g} → {best.fit.rmse_torque_Nm:.3g} N·m, temperature RMSE "
                  f"{base.rmse_temp_C:.3g} → {best.fit.rmse_temp_C:.3g} °C; leave-one-test-out error "
                  f"{base_cv:.1f} → {best.cv_score:.1f} (better in {best.cv_better_tests} of {data.n_tests} held-out "
                  f"tests).  Its expected signature: {effect.signature}.")
        others = [c for c in cands if c is not best and c.delta_bic - best.delta_bic < INDISTINGUISHABLE_BIC
                  and c.delta_bic < BIC_THRESHOLD]
        if best_struct["structured"]:
            verdict, remaining, struct, refined = "none", True, best_struct, best.fit
            ev.append(f"But the residual of baseline + {best.effect} is still structured "
                      f"({_structure_words(best_struct)}): none of the catalogue explains the data; "
                      f"{best.effect} explains only part of it.  An effect outside the catalogue (or several "
                      f"together) remains — write it as a plugin and refit.")
        else:
            verdict, indist, refined, remaining, struct = best.effect, [c.effect for c in others], best.fit, False, \
                best_struct
            if others:
                ev.append("Indistinguishable on these data (within ΔBIC " + f"{INDISTINGUISHABLE_BIC:g}): "
                          + ", ".join(f"{c.effect} (ΔBIC {c.delta_bic - best.delta_bic:+.1f} vs best)" for c in others)
                          + "; more tests (other T_0, hand forces, longer holds) would separate them.")
            elif len(cands) > 1:
                ru = next(c for c in cands if c is not best)
                ev.append(f"Runner-up {ru.effect} is {ru.delta_bic - best.delta_bic:.1f} BIC worse: clearly separated.")
            ev.append(f"The refined residual is consistent with noise ({_structure_words(best_struct)}).")
    else:
        if strong:
            ev.append(f"{strong[0].effect} lowers BIC by {-strong[0].delta_bic:.1f} but does not predict held-out "
                      f"tests better than the baseline (cross-validation {strong[0].cv_score:.1f} vs {base_cv:.1f}); "
                      f"not accepted.")
        else:
            ev.append(f"No candidate lowers BIC by more than {-BIC_THRESHOLD:g} (best: {cands[0].effect}, "
                      f"ΔBIC {cands[0].delta_bic:+.1f})." if cands else "No candidates were given.")
        if base_struct["structured"]:
            ev.append(f"The baseline residual is structured ({_structure_words(base_struct)}) but no catalogue "
                      f"effect explains it: an unknown effect remains.")
        else:
            ev.append("The baseline residual is consistent with noise: no missing effect is detected.")
    return Diagnosis(data, paper, base, nq, nt, cands, verdict, indist, refined, remaining, struct, base_cv, ev)


def _structure_words(s: dict) -> str:
    parts = []
    for ch in ("torque", "temperature"):
        t = s[ch]
        parts.append(f"{ch}: variance {t['excess_variance']['ratio']:.2f}× noise (p = {t['excess_variance']['p']:.2g}), "
                     f"lag-1 autocorrelation {t['autocorrelation']['lag1']:+.2f} (p = {t['autocorrelation']['p']:.2g}), "
                     f"test offsets p = {t['test_offsets']['p']:.2g}, time profile p = {t['time_profile']['p']:.2g}")
    return "; ".join(parts)
