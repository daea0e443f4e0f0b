"""What a "none" could have missed: the least size of each effect these bench data would have found.

A verdict "none" says that no effect was found, not that there is none.  How large an effect could hide
depends on the test design (forces, directions, start temperatures, samples) and on how much of the
effect the free brake parameters of the calibrated drum can imitate.  :func:`detection_limits` answers it
for every effect with one size parameter (its ``amplitude``, or its only parameter):

1. the calibrated drum's Jacobian is extended by the size parameter's column at its neutral value
   (:func:`rollaway.identify.calibrate.jacobian_at`, each test's T_0 profiled out; the effect's other
   parameters at their typical values), each channel's rows divided by √ of its residual variance factor
   (the BIC's own scale: ΔBIC ≈ −ΔRSS/φ + k·ln N);
2. the part of that column the free brake parameters cannot imitate, s⊥ (least-squares residual against
   their columns), sets the evidence an effect of size a adds: ΔRSS/φ ≈ a²·|s⊥|²;
3. the selection names an effect when ΔBIC < −10 (:data:`rollaway.identify.selection.BIC_THRESHOLD`), i.e.
   a²·|s⊥|² > 10 + k·ln N (k its parameters).  With the noise the evidence is non-central χ²₁: it clears that
   bar 4 times in 5 when a·|s⊥| ≥ √(10 + k·ln N) + 0.84 (:data:`POWER_Z`);
4. that linear bound is optimistic — the effect's other parameters (a time constant) are fitted too, the
   selection also asks for better held-out prediction, and it frees brake parameters again — so the limit
   reported is :data:`SELECTION_FACTOR` times it (measured: see the constant).

A limit above the effect's ``typical`` size means these data could miss an effect of the size real drums show.
"""
from __future__ import annotations

import math

import numpy as np

POWER_Z = 0.8416             # one-sided normal quantile of power 0.8 ("found 4 times in 5")
SELECTION_FACTOR = 2.0       # [assumed, measured] the selection needs this much more than the linear bound: on 80
                             # campaigns of tests/identify/bench_generator.py (a lining creep and a cable relaxation
                             # of fixed size, 2–4 forces, one or both directions, 1–15-min samples) effects above the
                             # linear bound ×2 were named (verdict or alternative) in 52 of 58, below it in 12 of 22;
                             # on 120 campaigns more, not used to set it: 89 of 89 above, 15 of 31 below


def size_parameter(effect) -> str | None:
    """The parameter that sets *effect*'s size: its declared ``amplitude``, or its only (global) parameter."""
    amp = getattr(effect, "amplitude", "")
    if amp:
        return amp
    glob = [p.name for p in effect.parameters if not p.per_test]
    return glob[0] if len(glob) == 1 and not any(p.per_test for p in effect.parameters) else None


def effect_columns(data, fit, effects=None):
    """For each effect not in *fit*'s model that has a size parameter (default: every available one), its size
    column against *fit*'s free parameters, rows per √ of each channel's residual variance factor (≥ 1):
    yields ``(name, effect, size spec, column, columns of fit.names, k)`` (k: the effect's global parameters).
    The column is taken at the effect's neutral size, its other parameters at their typical values."""
    from rollaway.effects import available_effects
    from rollaway.identify.calibrate import evaluate, jacobian_at
    from rollaway.identify.model import DrumPlan

    if fit.jacobian is None:
        return
    plan = DrumPlan(fit.model.params, fit.model.free)
    names = list(fit.names)
    have = {e.name for e in fit.model.effects}
    phi = np.concatenate([np.full(fit.n_temp, max(fit.variance_factor.get("temperature", 1.0), 1.0)),
                          np.full(fit.n_torque, max(fit.variance_factor.get("torque", 1.0), 1.0))])
    for name, cls in (effects or available_effects()).items():
        if name in have:
            continue
        eff = cls()
        size = size_parameter(eff)
        if size is None:
            continue
        spec = next(p for p in eff.parameters if p.name == size)
        values = {**fit.values, **{f"{name}.{p.name}": (p.neutral if p.name == size else p.typical)
                                   for p in eff.parameters}}
        try:
            at = evaluate(data, list(fit.model.effects) + [eff], plan, values)
            jac = jacobian_at(at, names + [f"{name}.{size}"])
        except Exception:        # noqa: BLE001 — a plugin that cannot be evaluated here has no column
            continue
        if jac.shape[0] != phi.size or not np.all(np.isfinite(jac)):
            continue
        jac = jac / np.sqrt(phi)[:, None]
        yield name, eff, spec, jac[:, -1], jac[:, :-1], sum(1 for p in eff.parameters if not p.per_test)


def detection_limits(data, base, threshold: float = 10.0, effects=None) -> list[dict]:
    """For each effect (default: every available one with a size parameter), the least size these *data* find 4
    times in 5 against the calibrated drum *base* (a :class:`~rollaway.identify.calibrate.FitResult`):
    ``{"effect", "parameter", "unit", "least_size", "typical", "ratio" (least/typical), "description"}``, the
    most sensitive (smallest ratio) first.  An effect whose column the drum imitates wholly gets ``inf``."""
    out = []
    for name, eff, spec, col, rest, k in effect_columns(data, base, effects):
        least, _ = _least_size(col, rest, k, base.n_temp + base.n_torque, threshold)
        out.append({"effect": name, "parameter": spec.name, "unit": spec.unit, "least_size": least,
                    "typical": spec.typical, "ratio": _ratio(least, spec), "description": spec.description})
    return sorted(out, key=lambda r: r["ratio"])


def _least_size(col, rest, k: int, n_rows: int, threshold: float) -> tuple[float, np.ndarray]:
    """(least size found 4 times in 5, β): β the fitted parameters' least-squares response to the size column."""
    beta = np.linalg.lstsq(rest, col, rcond=None)[0] if rest.shape[1] else np.zeros(0)
    norm = float(np.linalg.norm(col - rest @ beta if rest.shape[1] else col))
    need = math.sqrt(threshold + k * math.log(n_rows)) + POWER_Z
    return (SELECTION_FACTOR * need / norm if norm > 0 else math.inf), beta


def _ratio(least: float, spec) -> float:
    typical = abs(spec.typical) if spec.typical else math.nan
    return least / typical if typical == typical and typical > 0 else math.inf


def hidden_shifts(data, fit, threshold: float = 10.0, effects=None) -> list[dict]:
    """What *fit*'s values assume: for each effect outside its model that these *data* could miss at the size real
    drums show (least size found 4 times in 5 above the typical size, :func:`detection_limits`' rule), the values
    of the fitted global parameters had the data held that effect at its typical size.

    Linear: data that hold an effect of size a are fitted without it at θ̂ = θ* + β·a, β the least-squares
    response of the free parameters to the effect's size column (:func:`effect_columns`); so θ* = θ̂ − β·a.
    Returns ``[{"effect", "parameter", "typical", "unit", "ratio", "values": {name: θ*}}]``, largest ratio first;
    the fit's intervals are those of the model without these effects (they are not widened by them, except for the
    installation gap, whose spread the drum calibration counts as the held brake parameter ``gap_m``)."""
    out = []
    for name, eff, spec, col, rest, k in effect_columns(data, fit, effects):
        least, beta = _least_size(col, rest, k, fit.n_temp + fit.n_torque, threshold)
        ratio = _ratio(least, spec)
        if not ratio > 1.0 or not beta.size or not spec.typical:     # no typical size: nothing to state
            continue
        out.append({"effect": name, "parameter": spec.name, "typical": spec.typical, "unit": spec.unit,
                    "ratio": ratio, "values": {n: float(fit.values[n]) - float(b) * spec.typical
                                               for n, b in zip(fit.names, beta)}})
    return sorted(out, key=lambda r: -r["ratio"])


def hidden_words(fit, shifts: list[dict], names=("mu_drum", "heat_transfer_W_m2K")) -> str:
    """One line: the effects the calibrated values assume absent, and where μ_d and h (*names*) would be with each
    at its typical size (only shifts beyond the parameter's own 95 % interval; JSON ``hidden_effects`` has all)."""
    parts = []
    for r in shifts:
        moved = [f"{n} {v:.4g}" for n, v in r["values"].items() if n in names and n in fit.estimates
                 and not fit.estimates[n].ci95[0] <= v <= fit.estimates[n].ci95[1]]
        if moved:
            parts.append(f"{r['effect']} at {r['typical']:.3g}{'' if r['unit'] in ('–', '') else ' ' + r['unit']}: "
                         + ", ".join(moved))
    if not parts:
        return ""
    return ("The calibrated values assume no effect these data could miss at the size real drums show; with one "
            "at its typical size they would be (rollaway.identify.detection.hidden_shifts): " + "; ".join(parts)
            + " — read the intervals as conditional on their absence, or test where they show.")


def blind(limits: list[dict]) -> list[str]:
    """The effects these data could miss at the size real drums show (limit above the typical size)."""
    return [r["effect"] for r in limits if r["ratio"] > 1.0]


def limits_words(limits: list[dict], top: int = 4) -> str:
    """One line: the least sizes these data find, most sensitive first, and those they would miss at typical size."""
    if not limits:
        return ""
    seen = [f"{r['effect']} {r['parameter']} ≥ {r['least_size']:.2g}{'' if r['unit'] in ('–', '') else ' ' + r['unit']}"
            f" (typical {r['typical']:.2g}, ×{r['ratio']:.2g})" for r in limits[:top] if math.isfinite(r["least_size"])]
    missed = blind(limits)
    return ("What these data would have found 4 times in 5 (rollaway.identify.detection): "
            + "; ".join(seen) + "."
            + (f"  At the size real drums show, they could miss {', '.join(missed)}: test where they differ "
               f"(more forces, both directions, hotter starts, longer holds or denser samples)." if missed else ""))


__all__ = ["POWER_Z", "SELECTION_FACTOR", "blind", "detection_limits", "effect_columns", "hidden_shifts", "hidden_words",
           "limits_words", "size_parameter"]
