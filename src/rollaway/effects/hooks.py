"""Calling an effect's hook as untrusted code (plugins are user input).

An exception (a ``sys.exit`` included), a result that is not numbers, a shape that does not
broadcast to the samples, or a NaN/inf where the inputs were finite becomes a one-line
:class:`~rollaway.errors.UserError` naming the effect and the plugin file it came from.
"""
from __future__ import annotations

import math

import numpy as np

from rollaway.effects.base import Effect, ModelState
from rollaway.errors import UserError


def call_hook(effect: Effect, hook: str, state: ModelState, x, v: dict, scalar_ok: bool = False):
    """Call one effect hook as untrusted code: an exception, a wrong shape or a non-finite value is a UserError.
    A hook the effect does not override passes *x* through untouched (and unchecked)."""
    if hook not in _overridden(type(effect)):
        return x
    try:
        out = getattr(effect, hook)(state, x, v)
    except (UserError, KeyboardInterrupt):
        raise
    except BaseException as exc:  # noqa: BLE001 - a plugin's bug (or its sys.exit) must not end the tool silently
        raise UserError(f"{effect_label(effect)}: hook '{hook}' raised {type(exc).__name__}: {exc}; fix the effect's "
                        f"code") from None
    try:
        arr = np.asarray(out, float)
    except (TypeError, ValueError):
        raise UserError(f"{effect_label(effect)}: hook '{hook}' returned {type(out).__name__}, not numbers; return an "
                        f"array shaped like its input") from None
    if not (scalar_ok and arr.ndim == 0) and arr.shape != state.time_s.shape:
        try:
            ok = np.broadcast_shapes(arr.shape, state.time_s.shape) == state.time_s.shape
        except ValueError:
            ok = False
        if not ok:
            raise UserError(f"{effect_label(effect)}: hook '{hook}' returned shape {arr.shape} for {state.time_s.shape} "
                            f"samples; return an array shaped like its input")
    if math.isfinite(arr.sum()):       # the common case: every value finite (a NaN or an inf makes the sum so)
        return out
    finite_out = np.isfinite(arr)
    if finite_out.all():                      # finite values whose sum overflows
        return out
    finite_in = np.isfinite(state.time_s) & np.isfinite(np.asarray(x, float))   # garbage in is not the hook's
    if not np.all(finite_out | ~finite_in):
        raise UserError(f"{effect_label(effect)}: hook '{hook}' returned NaN or inf; return finite values (check the "
                        f"effect's formula and its parameter bounds)")
    return out


_OVERRIDDEN: dict[type, frozenset] = {}


def _overridden(cls) -> frozenset:
    hooks = _OVERRIDDEN.get(cls)
    if hooks is None:
        hooks = _OVERRIDDEN[cls] = frozenset(cls.overridden_hooks())
    return hooks


def effect_label(effect: Effect) -> str:
    src = getattr(type(effect), "__rollaway_source__", None)
    return f"effect '{effect.name}'" + (f" ({src})" if src else "")
