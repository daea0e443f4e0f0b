"""The shape-free version of an effect: the quantity its hook changes, times a linear spline of its covariate.

A catalogue effect is a physics (which quantity of the chain it changes) and a functional form (how).  Its
shape-free version keeps the physics and drops the form: the hook's quantity q becomes q·(1 + g(x)), g a linear
spline in the effect's covariate x (time, lining temperature, …) with fixed knots and g = 0 at the first knot —
or q + s·g(x) where the physics is an absolute change (``Effect.shape_scale`` = s: a cable relaxation loses the
same displacement at every hand force, which a factor on u_6 would turn into a loss proportional to the force).
:mod:`rollaway.identify.shape` fits one to see the shape the data want; a saved model may carry one as a competing
form (``[effects.NAME_shape]`` with ``knots`` and ``c0`` … in a model file, :mod:`rollaway.model.model_file`).
Below the first knot the spline is flat.  Beyond the last knot a spline in time is flat (the last segment's end value
holds); a spline in temperature has a held parameter ``beyond`` (:data:`BEYOND_CENTRE`, drawn by the bands with
:data:`BEYOND_PRIOR_SD` within 0–1): the share of its last slope that goes on, from a law that stops changing at the
hottest tested temperature (a glass transition that has saturated) to one that goes on as the data last showed
(a fade that has just begun); fits keep it at 0 (flat: what the data saw), the calibrated model carries the centre — flat alone was optimistic where a modulus or friction was still falling at the
hottest tested start, and the slope alone pessimistic where it had levelled off.
"""
from __future__ import annotations

import numpy as np

from rollaway.effects.base import Effect, EffectParameter
from rollaway.errors import UserError

SUFFIX = "_shape"              # "lining_creep" → "lining_creep_shape"
COEFFICIENT_BOUND = 0.9        # |c_j| ≤ this: no knot segment changes the factor by more than 90 %
HOOK_COVARIATE = {"friction": "lining_temp_C", "lining_modulus": "lining_temp_C", "clamp_force": "time_s",
                  "displacement": "time_s", "gap": "time_s", "drum_temperature": "time_s",
                  "lining_temperature": "time_s", "torque": "time_s"}
COVARIATES = ("time_s", "lining_temp_C", "drum_temp_C", "hand_force_N")
TEMPERATURE_HOOKS = ("drum_temperature", "lining_temperature")
EXTENDED = ("lining_temp_C", "drum_temp_C")  # a temperature law may go on changing beyond the hottest tested point
BEYOND_CENTRE = 0.5            # [assumed] between a law that stops at the hottest knot (0) and one that goes on along
                               # its last slope (1): no sample says which
BEYOND_PRIOR_SD = 0.5          # [assumed] drawn N(0.5, 0.5²) within [0, 1]: close to uniform over both ends
LEAST_FACTOR = 0.05            # a continued spline never takes more than 95 % of its quantity


def shape_hook(effect) -> tuple[str, str] | None:
    """(hook, covariate) of an effect's shape-free version; None for per-test effects (no shape to draw)."""
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


def spline_factor(x, knots, coef, beyond=None) -> np.ndarray:
    """1 + Σ_j c_j·clip((x − k_j)/(k_{j+1} − k_j), 0, 1): a linear spline, 1 at the first knot.  *beyond* (0–1):
    beyond the last knot the last segment goes on with that share of its slope (0 or None: flat), the going-on
    never taking the factor below :data:`LEAST_FACTOR`."""
    x = np.asarray(x, float)
    g = np.zeros_like(x)
    for j, c in enumerate(coef):
        width = max(knots[j + 1] - knots[j], 1e-12)
        g = g + c * np.clip((x - knots[j]) / width, 0.0, 1.0)
    if beyond is None:
        return 1.0 + g
    width = max(knots[-1] - knots[-2], 1e-12)
    on = coef[-1] * beyond * np.maximum(x - knots[-1], 0.0) / width
    return np.maximum(1.0 + g + on, np.minimum(1.0 + g, LEAST_FACTOR))


def _covariate(state, name: str) -> np.ndarray:
    return np.broadcast_to(np.asarray(getattr(state, name), float), state.time_s.shape)


def spline_effect(effect, knots, scale: float | None = None) -> type[Effect]:
    """An Effect class changing *effect*'s quantity (its first hook) by a spline factor of its covariate with
    *knots* (strictly increasing, at least three); parameters ``c0`` … one per knot segment.  *scale*: the unit of
    an absolute change (q + scale·g); default the effect's ``shape_scale``, 0 a factor (q·(1 + g))."""
    found = shape_hook(effect)
    if found is None:
        raise ValueError(f"effect '{effect.name}' has no shape-free version (no hook, or per-test parameters)")
    hook, cov = found
    knots = np.asarray(knots, float)
    names = [f"c{j}" for j in range(len(knots) - 1)]
    scale = float((getattr(effect, "shape_scale", 0.0) if scale is None else scale) or 0.0)

    def apply(self, state, q, v):
        f = spline_factor(_covariate(state, cov), knots, [v[k] for k in names], v["beyond"] if extend else None)
        if hook in TEMPERATURE_HOOKS:
            return state.ambient_C + (q - state.ambient_C) * f
        if scale:
            return q + scale * (f - 1.0)       # an absolute change: s·g(x)
        return q * f

    params = tuple(EffectParameter(k, "–", neutral=0.0, lower=-COEFFICIENT_BOUND, upper=COEFFICIENT_BOUND,
                                   initial=0.0, description=f"change of the factor over knot segment {j}")
                   for j, k in enumerate(names))
    extend = cov in EXTENDED
    if extend:
        params += (EffectParameter("beyond", "–", neutral=0.0, lower=0.0, upper=1.0, initial=BEYOND_CENTRE,
                                   held=True, prior_sd=BEYOND_PRIOR_SD,
                                   description="share of the last segment's slope that goes on beyond the hottest "
                                               "knot (held: no sample lies there; the bands draw it)"),)
    base, knot_list = effect.name, tuple(float(k) for k in knots)
    return type(f"ShapeFree_{effect.name}", (Effect,), {
        "__reduce__": lambda self: (_instance, (base, knot_list, scale)),    # pickled as its base, knots, scale
        "name": f"{effect.name}{SUFFIX}", "summary": f"shape-free version of {effect.name}",
        "physics": (f"{hook} + {scale:g} × linear spline in {cov}, {len(names)} segments" if scale else
                    f"{hook} × (1 + linear spline in {cov}, {len(names)} segments)"), "signature": "",
        "reference": "linear spline (no functional form assumed)", "parameters": params, hook: apply,
        "elementwise": True,                  # fixed knots, each sample's own covariate
        "knots": knots, "hook": hook, "covariate": cov, "base": effect.name, "scale": scale,
        **({"__rollaway_source__": src} if (src := getattr(effect, "__rollaway_source__", None)) else {})})


def _instance(base: str, knots, scale: float | None = None) -> Effect:
    """An instance of *base*'s shape-free form with *knots* (how one is unpickled: its class is built at run time)."""
    from rollaway.effects import get_effect
    return spline_effect(get_effect(base), knots, scale)()


def is_shape_free(effect) -> bool:
    """True for an effect built by :func:`spline_effect`."""
    return getattr(effect, "knots", None) is not None and getattr(effect, "base", None) is not None


def from_model_file(name: str, knots, where: str, scale=0.0) -> type[Effect]:
    """The shape-free effect ``[effects.NAME]`` of a model file (*name* = a catalogue effect + ``_shape``, *knots*
    its ``knots`` list, *scale* its ``scale``: the unit of an absolute change, absent (0) for a factor — files
    written before absolute forms existed hold factors); a one-line error naming *where* and the key otherwise."""
    from rollaway.effects import available_effects
    from rollaway.errors import suggest
    base = name[:-len(SUFFIX)]
    known = available_effects()
    if base not in known:
        raise UserError(f"{where}: [effects.{name}] is the shape-free version of unknown effect '{base}'"
                        f"{suggest(base, known)}; name it EFFECT{SUFFIX} after a catalogue effect")
    if shape_hook(known[base]) is None:
        raise UserError(f"{where}: [effects.{name}]: '{base}' has no shape-free version (per-test parameters); "
                        f"delete the table")
    key = f"effects.{name}.knots"
    if knots is None:
        raise UserError(f"{where}: [effects.{name}] needs 'knots', the spline's knots in its covariate "
                        f"({shape_hook(known[base])[1]}), e.g. knots = [0.0, 300.0, 900.0, 3600.0]")
    ok = (isinstance(knots, list) and len(knots) >= 3
          and all(isinstance(k, (int, float)) and not isinstance(k, bool) and np.isfinite(k) for k in knots))
    if not ok or np.any(np.diff(np.asarray(knots, float)) <= 0):
        raise UserError(f"{where}: key '{key}' must be a list of at least three increasing numbers, got {knots!r}"
                        [:300])
    if not (isinstance(scale, (int, float)) and not isinstance(scale, bool) and np.isfinite(scale) and scale >= 0):
        raise UserError(f"{where}: key 'effects.{name}.scale' must be a number ≥ 0 (the unit of an absolute change "
                        f"of the spline; leave it out for a factor), got {scale!r}"[:300])
    return spline_effect(known[base], knots, float(scale))


__all__ = ["COEFFICIENT_BOUND", "HOOK_COVARIATE", "SUFFIX", "from_model_file", "is_shape_free", "shape_hook",
           "spline_effect", "spline_factor"]
