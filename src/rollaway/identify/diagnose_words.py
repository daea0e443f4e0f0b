"""The words of a diagnosis: noise, residuals, structure tests and why no candidate was accepted."""
from __future__ import annotations

from rollaway.bench.noise import Noise
from rollaway.identify.calibrate import FitResult
from rollaway.identify.residuals import association, trend_words
from rollaway.identify.selection import BIC_THRESHOLD


def score_text(x):
    return "–" if x is None else f"{x:.1f}"


def noise_words(name: str, n: Noise, unit: str, option: str) -> str:
    if n.source == "instrument":
        return f"{name} σ = {n.sigma:.3g} {unit} (instrument figure, {option})"
    rel = f" = √({n.absolute:.3g}² + ({n.relative:.2%}·{name})²)" if n.relative > 0 else ""
    text = f"{name} σ ≈ {n.sigma:.3g} {unit}{rel} (local degree-{n.degree} pseudo-residuals, {n.dof:.0f} dof)"
    if not n.reliable:
        text += (f" — NOT RELIABLE: {n.note}; the structure checks may miss remaining structure — give the "
                 f"instrument's figure with {option}")
    return text


def no_candidate_words(cands, strong, cur_cv) -> str:
    if strong:
        return (f"{strong[0].effect} lowers BIC by {-strong[0].delta_bic:.1f} but does not predict held-out tests "
                f"better than the baseline (cross-validation {strong[0].cv_score:.1f} vs {cur_cv:.1f}); not accepted.")
    if cands:
        return (f"No candidate lowers BIC by more than {-BIC_THRESHOLD:g} (best: {cands[0].effect}, "
                f"ΔBIC {cands[0].delta_bic:+.1f}).")
    return "No candidates were given."


def drum_words(fit: FitResult, free) -> str:
    """The calibrated drum's freed brake parameters *free* as ``name = value``, each at a bound of its range said so:
    the bare drum can push one there to stand in for an effect it lacks (μ_d against the eq. (24) slope, offset and
    arm ratio), so the value is not the drum's own; the "Your drum" table gives them with the verdict's effects."""
    out = []
    for n in free:
        e = fit.estimates.get(n)
        out.append(f"{n} = {fit.values[n]:.4g}" + (f" (its {e.at_bound} bound: the bare drum leans on it for what it "
                                                   f"lacks)" if e and e.at_bound else ""))
    return ", ".join(out) or "nothing freed"


def describe_residual(fit: FitResult, channel: str) -> str:
    rt, rq = fit.residuals()
    r = rq if channel == "torque" else rt
    assoc = association(fit.data, r, fit.prediction.drum_temp_C)
    name, share = assoc[0]
    words = trend_words(fit.data, r, fit.prediction.drum_temp_C, name)
    return (f"the {channel} residual followed {name} most ({share:.0%} of its variance explained by {name} "
            f"alone; it {words})")


def structure_words(s: dict) -> str:
    parts = []
    for ch in ("torque", "temperature"):
        t = s[ch]
        parts.append(f"{ch}: variance {t['excess_variance']['ratio']:.2f}× noise (p = {t['excess_variance']['p']:.2g}), "
                     f"lag-1 autocorrelation {t['autocorrelation']['lag1']:+.2f} (p = {t['autocorrelation']['p']:.2g}), "
                     f"test offsets p = {t['test_offsets']['p']:.2g}, time profile p = {t['time_profile']['p']:.2g}")
    return "; ".join(parts)
