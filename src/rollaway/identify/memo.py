"""Fits computed once per diagnosis.

A diagnosis asks for some fits more than once: the pair refitted with the brake parameters it needs is the pair
the partner test compares; the first effect alone is fitted by the elimination step and again when the pair is
ordered; the first effect re-formed is fitted for the partial form and again for the shape rivals.  Inside
:func:`fit_memo` each :func:`~rollaway.identify.calibrate.calibrate` call is looked up by everything that
determines its result — the data set (the object, with its noise model), the effects (a shape-free effect by its
base and knots), the parameter set and its freed brake parameters, the start values (every number, per-test arrays
byte for byte) and the options — and a repeated call gets a copy of the first one's result: the same numbers,
since each fit is deterministic; a call that differs only by a smaller budget gets the larger one's fit where
that fit's every pass ended below it (MINPACK stops on its budget alone: the same steps, the same numbers).  A fit
started ahead in a background process
(:func:`rollaway.identify.workers.ahead`) is expected under its key and waited for when asked.  Outside
:func:`fit_memo` nothing is kept.
"""
from __future__ import annotations

import copy
import functools
from contextlib import contextmanager

import numpy as np

_MEMO: dict | None = None        # key → (fit, objects the key refers to by identity, kept alive)
_PENDING: dict = {}              # key → a call that waits for that fit from a background process (expect)
_ENDS: list = []                 # calls made when the outermost block ends (background processes stopped)


@contextmanager
def fit_memo():
    """Keep every fit made inside the block for repeated calls (nested blocks share the outer one's)."""
    global _MEMO
    outer = _MEMO
    if outer is None:
        _MEMO = {}
    try:
        yield
    finally:
        if outer is None:
            ends = list(_ENDS)
            forked()
            _MEMO = None
            for end in ends:
                end()


def memoised(func):
    """*func* run inside :func:`fit_memo`."""
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        with fit_memo():
            return func(*args, **kwargs)
    return wrapper


def _effect_key(e, keep: list):
    from rollaway.effects import available_effects
    from rollaway.effects.shape_free import is_shape_free
    if isinstance(e, str):
        return ("name", e)
    if is_shape_free(e):
        return ("shape-free", e.base, tuple(float(k) for k in e.knots), e.hook, e.covariate, float(e.scale))
    cls = e if isinstance(e, type) else type(e)
    if available_effects().get(getattr(cls, "name", None)) is not cls:
        keep.append(e)
        return ("object", id(e))           # not the registered class: this very object
    return ("class", id(cls))


def _value_key(v):
    if v is None:
        return None
    if isinstance(v, np.ndarray):
        return (v.dtype.str, v.shape, v.tobytes())
    if isinstance(v, (int, float, np.number, bool, np.bool_)):
        return float(v)
    raise TypeError(f"no memo key for {type(v).__name__}")


def key(data, effects, params, kwargs: dict):
    """The memo's key of ``calibrate(data, effects, params, **kwargs)``, or None (no memo, or a call it does not
    keep: one with its own model)."""
    if _MEMO is None or kwargs.get("model") is not None:
        return None
    keep = [data, data.torque_sigma_Nm, data.temp_sigma_C]
    try:
        eff = tuple(_effect_key(e, keep) for e in effects)
        start = tuple(sorted((k, _value_key(v)) for k, v in (kwargs.get("start") or {}).items()))
        opts = tuple(sorted((k, _value_key(v)) for k, v in kwargs.items() if k not in ("start", "free", "model")))
    except Exception:        # noqa: BLE001 - an effect or value the key cannot describe: no memo for this call
        return None
    plan = (getattr(params, "params", params), tuple(getattr(params, "free", ()) or ()), type(params).__name__)
    keep.append(plan[0])
    free = kwargs.get("free")
    return (id(data), id(data.torque_sigma_Nm), id(data.temp_sigma_C), eff,
            (id(plan[0]) if not isinstance(plan[0], (str, type(None))) else plan[0]), plan[1], plan[2],
            None if free is None else tuple(sorted(free)),
            start, opts), keep


def same_model(data, effects, params):
    """The kept fit of *effects* under *params* on *data* (every brake parameter the plan frees free) with the lowest
    BIC, whatever its start and budget, or None."""
    k = key(data, effects, params, {})
    if k is None:
        return None
    best = None
    for kk, (fit, _) in _MEMO.items():
        if kk[:8] == k[0][:8] and fit.jacobian is not None and (best is None or fit.bic < best.bic):
            best = fit
    return None if best is None else copy_fit(best)


def lookup(k):
    """A copy of the fit kept under *k* (from :func:`key`), or None.  Where none is kept, that of the same call
    with a larger budget that never bound (:func:`_unbound_twin`)."""
    if k is None or _MEMO is None:
        return None
    hit = _MEMO.get(k[0])
    if hit is None and k[0] in _PENDING:         # being fitted in the background: wait for it (it is stored)
        _PENDING.pop(k[0])()
        hit = _MEMO.get(k[0])
    if hit is None:
        twin = _unbound_twin(k[0])
        if twin is not None:
            _MEMO[k[0]] = hit = (twin, k[1])
    return None if hit is None else copy_fit(hit[0])


def _budget(k0) -> tuple | None:
    """(the memo key *k0* without its budget, its budget in iterations per pass), or None for a key of another kind
    or a fit that may give up (:func:`rollaway.identify.solver.futile` reads the budget)."""
    from rollaway.identify.fitting import MAX_ITERATIONS
    if not (isinstance(k0, tuple) and len(k0) == 10 and isinstance(k0[9], tuple)):
        return None
    opts = dict(k0[9])
    if opts.get("give_up_bic") is not None:
        return None
    rest = tuple((n, v) for n, v in k0[9] if n != "max_iterations")
    return k0[:9] + (rest,), opts.get("max_iterations") or MAX_ITERATIONS


def _unbound_twin(k0):
    """The fit of the call *k0* made with a larger budget (kept, or expected from the background: waited for) whose
    every pass ended below *k0*'s budget: MINPACK took the same steps and stopped where *k0*'s would have, so it is
    *k0*'s fit number for number (a partial form's fit and the same effect re-formed with the re-formed fits'
    budget, both started ahead: one process instead of two).  None where there is none."""
    own = _budget(k0)
    if own is None:
        return None
    for kk in list(_PENDING) + list(_MEMO):
        other = _budget(kk)
        if other is None or other[0] != own[0] or other[1] <= own[1]:
            continue
        if kk in _PENDING:
            _PENDING.pop(kk)()
        hit = _MEMO.get(kk)
        if hit is None:
            continue
        fit = hit[0]
        stage = (fit.fit_info.get("stages") or [{}])[0]
        peak = stage.get("peak_calls")
        if peak is not None and "gave_up" not in fit.fit_info and peak < own[1] * (len(fit.names) + 1):
            return fit
    return None


def known(k) -> bool:
    """Is the fit of *k* (from :func:`key`) kept, or expected from the background (nothing is waited for)?"""
    return k is not None and _MEMO is not None and (k[0] in _MEMO or k[0] in _PENDING)


def larger_budget(k, others) -> bool:
    """Is one of the keys *others* (from :func:`key`) the call *k* with a larger budget (whose fit may be *k*'s:
    :func:`lookup`)?"""
    own = None if k is None else _budget(k[0])
    return own is not None and any(o is not None and (b := _budget(o[0])) is not None and b[0] == own[0]
                                   and b[1] > own[1] for o in others)


def expect(k, wait, end=None) -> None:
    """The fit of *k* (from :func:`key`) comes from a background process: :func:`lookup` calls *wait* (which stores
    it, or not where the process failed) before it answers; *end* is called when the outermost block ends."""
    if k is not None and _MEMO is not None:
        _PENDING[k[0]] = wait
        if end is not None and end not in _ENDS:
            _ENDS.append(end)


def forked() -> None:
    """Forget the fits expected from the background: in a forked process (their pipes are the parent's to read), and
    when the outermost block ends."""
    _PENDING.clear()
    _ENDS.clear()


def store(k, fit) -> None:
    """Keep a copy of *fit* under *k* (from :func:`key`; nothing when *k* is None)."""
    if k is not None and _MEMO is not None:
        _MEMO[k[0]] = (copy_fit(fit), k[1])


ABSENT = object()            # recall's answer where nothing is kept


def recall(tag: str, k):
    """The answer kept by :func:`remember` under *tag* and *k* (from :func:`key`), or :data:`ABSENT`."""
    if k is None or _MEMO is None:
        return ABSENT
    hit = _MEMO.get((tag,) + k[0])
    return ABSENT if hit is None else hit[0]


def remember(tag: str, k, answer) -> None:
    """Keep *answer* — of a search whose result depends only on what *k* (from :func:`key`) describes — under
    *tag* for this diagnosis (nothing when *k* is None)."""
    if k is not None and _MEMO is not None:
        _MEMO[(tag,) + k[0]] = (answer, k[1])


def copy_fit(fit):
    """A copy whose later changes (its covariance, notes in ``fit_info``, warnings) stay its own."""
    out = copy.copy(fit)
    out.fit_info = dict(fit.fit_info)
    out.warnings = list(fit.warnings)
    return out


__all__ = ["ABSENT", "copy_fit", "expect", "fit_memo", "forked", "key", "known", "larger_budget", "lookup", "memoised",
           "recall", "remember", "store"]
