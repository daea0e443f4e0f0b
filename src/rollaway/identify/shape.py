"""The shape the data want: a flexible version of an effect's hook, drawn against the catalogue's form.

When a catalogue effect explains most of the misfit but leaves structure, its *physics* (which
quantity it changes) is probably right and its *form* wrong.  :func:`flexible_effect` builds an
effect that changes the same quantity by a factor ``1 + g(x)``, g a linear spline in the
effect's covariate x (time, lining or drum temperature, hand force) with knots over the
covariate's range (:func:`spline_knots`) and g = 0 at the lowest knot — no functional form assumed.  Fitting it
shows what the data want; :func:`shape_curves` evaluates both factors on a grid for a figure.
"""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter

KNOTS = 8                     # spline segments (equal widths over the covariate's range)
HOOK_COVARIATE = {"friction": "lining_temp_C", "lining_modulus": "lining_temp_C", "clamp_force": "time_s",
                  "displacement": "time_s", "gap": "time_s", "drum_temperature": "time_s",
                  "lining_temperature": "time_s", "torque": "time_s"}
COVARIATE_UNITS = {"time_s": "s", "lining_temp_C": "°C", "drum_temp_C": "°C", "hand_force_N": "N"}
_TEMPERATURE_HOOKS = ("drum_temperature", "lining_temperature")


def shape_hook(effect: Effect) -> tuple[str, str] | None:
    """(hook, covariate) of an effect's flexible form; None for per-test effects (no shape to draw)."""
    if any(p.per_test for p in effect.parameters):
        return None
    hooks = effect.overridden_hooks()
    if not hooks:
        return None
    hook = hooks[0]
    cov = effect.shape_covariate or HOOK_COVARIATE[hook]
    if hook == "drum_temperature" and cov != "time_s":
        cov = "time_s"          # nothing downstream of the drum temperature exists yet
    return hook, cov


def _covariate(state, name: str) -> np.ndarray:
    return np.broadcast_to(np.asarray(getattr(state, name), float), state.time_s.shape)


def spline_factor(x, knots, coef) -> np.ndarray:
    """1 + Σ_j c_j·clip((x − k_j)/(k_{j+1} − k_j), 0, 1): a linear spline, 1 at the first knot."""
    x = np.asarray(x, float)
    g = np.zeros_like(x)
    for j, c in enumerate(coef):
        width = max(knots[j + 1] - knots[j], 1e-12)
        g = g + c * np.clip((x - knots[j]) / width, 0.0, 1.0)
    return 1.0 + g


def spline_knots(x: np.ndarray, covariate: str) -> np.ndarray:
    """At most KNOTS + 1 knots over the covariate's range: equally spaced, except in time, where they are
    spaced geometrically from the first sample after the start (at least 1 % of the span): creep and
    relaxation change fastest at the start of a hold, and equal 450 s segments of an hour cannot follow a
    logarithmic loss.  A time knot that would leave a segment without samples is skipped."""
    lo, hi = float(np.min(x)), float(np.max(x))
    if not covariate == "time_s" or hi <= lo:
        return np.unique(np.linspace(lo, hi, KNOTS + 1))
    xs = np.unique(x)
    knots = [lo]
    first = max(float(xs[1] - lo) if xs.size > 1 else 0.0, 0.01 * (hi - lo))
    for k in lo + np.geomspace(first, hi - lo, KNOTS):
        if np.any((xs > knots[-1]) & (xs <= k)):        # every segment holds samples (else its slope is free)
            knots.append(float(k))
    knots[-1] = hi
    return np.unique(knots)


def flexible_effect(effect: Effect, covariate_values: np.ndarray) -> type[Effect] | None:
    """An Effect class changing *effect*'s quantity by a spline factor of its covariate."""
    found = shape_hook(effect)
    if found is None:
        return None
    hook, cov = found
    x = np.asarray(covariate_values, float)
    knots = spline_knots(x, cov)
    if len(knots) < 3:
        return None
    n = len(knots) - 1
    names = [f"c{j}" for j in range(n)]

    def apply(self, state, q, v):
        f = spline_factor(_covariate(state, cov), knots, [v[k] for k in names])
        if hook in _TEMPERATURE_HOOKS:
            return state.ambient_C + (q - state.ambient_C) * f
        return q * f

    params = tuple(EffectParameter(k, "–", neutral=0.0, lower=-0.9, upper=0.9, initial=0.0,
                                   description=f"change of the factor over knot segment {j}")
                   for j, k in enumerate(names))
    cls = type(f"Flexible_{effect.name}", (Effect,), {
        "name": f"{effect.name}_shape", "summary": f"shape-free version of {effect.name}",
        "physics": f"{hook} × (1 + linear spline in {cov}, {n} segments)", "signature": "",
        "reference": "linear spline (no functional form assumed)", "parameters": params, hook: apply,
        "elementwise": True,                  # fixed knots, each sample's own covariate
        "knots": knots, "hook": hook, "covariate": cov})
    return cls


def covariate_of(fit, name: str) -> np.ndarray:
    """The covariate at every sample of a fit (lining temperature from the fitted model)."""
    if name == "time_s":
        return fit.data.time_s
    if name == "hand_force_N":
        return fit.data.hand_force_N
    if name == "lining_temp_C":
        return np.asarray(fit.prediction.lining_temp_C, float)
    return np.asarray(fit.prediction.drum_temp_C, float)


def shape_curves(effect: Effect, catalogue_fit, flex_fit, flex_cls, points: int = 40) -> dict:
    """Both factors against the covariate: the catalogue form (its hook's output over its input at
    the fitted values, on the samples) and the flexible spline (on a grid)."""
    hook, cov = flex_cls.hook, flex_cls.covariate
    data = catalogue_fit.data
    model = catalogue_fit.model
    values = catalogue_fit.values
    st = model.state(data, values)
    pred = catalogue_fit.prediction
    st.drum_temp_C = np.asarray(pred.drum_temp_C, float)
    st.lining_temp_C = np.asarray(pred.lining_temp_C, float)
    st.extra["series_stiffness_N_per_m"] = np.ones_like(st.time_s)
    v = {p.name: float(values.get(f"{effect.name}.{p.name}", p.neutral)) for p in effect.parameters}
    probe = {"friction": np.full_like(st.time_s, values["mu_drum"]),
             "lining_modulus": np.full_like(st.time_s, model.params.lining_modulus_Pa),
             "gap": np.full_like(st.time_s, max(model.params.gap_m, 1e-3)),
             "displacement": np.full_like(st.time_s, 1e-4), "clamp_force": np.full_like(st.time_s, 1e3),
             "torque": np.full_like(st.time_s, 1e3)}
    x = covariate_of(catalogue_fit, cov)
    if hook in _TEMPERATURE_HOOKS:
        base = np.asarray(pred.drum_temp_C, float)
        out = getattr(effect, hook)(st, base, v) if hook == "lining_temperature" else base
        cat = (out - st.ambient_C) / np.where(np.abs(base - st.ambient_C) > 1e-9, base - st.ambient_C, 1.0)
    else:
        q = probe[hook]
        cat = np.asarray(getattr(effect, hook)(st, q, v), float) / q
    order = np.argsort(x)
    grid = np.linspace(float(x.min()), float(x.max()), points)
    coef = [flex_fit.values[f"{flex_cls.name}.c{j}"] for j in range(len(flex_cls.knots) - 1)]
    flex = spline_factor(grid, flex_cls.knots, coef)
    # put both on the same footing: factor 1 at the spline's reference (lowest covariate)
    cat_ref = float(np.interp(grid[0], x[order], np.broadcast_to(cat, x.shape)[order]))
    return {"hook": hook, "covariate": cov, "unit": COVARIATE_UNITS.get(cov, ""),
            "catalogue": {"x": x[order].tolist(), "factor": (np.broadcast_to(cat, x.shape)[order] / cat_ref).tolist()},
            "flexible": {"x": grid.tolist(), "factor": flex.tolist(), "knots": list(map(float, flex_cls.knots))}}
