"""Independent fits on the machine's cores.

A diagnosis screens many effect sets that do not depend on each other (each swap of a two-effect verdict, each
candidate of a forward step).  :func:`fit_all` runs such a list of :func:`~rollaway.identify.calibrate.calibrate`
calls in a pool of forked processes, one per core: a forked worker inherits the data and every loaded effect (a
plugin's too) and the calls themselves without pickling them, and sends back the fit without its data (the
caller's object is put back).
The results are the same, fit for fit, as one after another: each fit is deterministic and independent.

One after another instead: one core (``ROLLAWAY_WORKERS=1`` or the process's CPU affinity), no ``fork`` start
method (Windows), inside a daemonic process (a multiprocessing pool's worker cannot have children), outside the
main thread (a thread of a threaded scheduler: forking there may copy a lock another thread holds), fewer than two
fits, or a pool that fails (it cannot start, a worker is killed, a fit cannot be sent back: then the fits are
run here, which raises any error of their own).
"""
from __future__ import annotations

import multiprocessing as mp
import os
import threading
from concurrent.futures import ProcessPoolExecutor

from rollaway.errors import UserError

_CALLS: tuple = (None, [])   # (data, calls) in flight: inherited by the forked workers, never pickled


def cores() -> int:
    """Processes :func:`fit_all` may use: ``ROLLAWAY_WORKERS`` if set, else the CPUs this process may run on."""
    env = os.environ.get("ROLLAWAY_WORKERS", "").strip()
    if env:
        try:
            n = int(env)
        except ValueError:
            raise UserError(f"environment variable ROLLAWAY_WORKERS = {env!r} must be a whole number of processes, "
                            f"e.g. ROLLAWAY_WORKERS=1 to fit one set at a time") from None
        if n < 1:
            raise UserError(f"environment variable ROLLAWAY_WORKERS = {n} must be at least 1")
        return n
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def _call(i: int):
    data, calls = _CALLS
    fn, args, kwargs = calls[i]
    fit = fn(data, *args, **kwargs)
    fit.data = None              # the caller has it
    return fit


def run_fits(data, calls: list[tuple]) -> list:
    """``[fn(data, *args, **kwargs) for fn, args, kwargs in calls]``, each *fn* returning one fit, on several cores
    where that is possible (see the module docstring).  The workers inherit *data* and *calls* (only each call's
    index is sent) and send the fit back.  Calibrations kept by :mod:`rollaway.identify.memo` are not sent, one
    asked twice is sent once, and what the workers send back is kept (a worker's own memo dies with it)."""
    from rollaway.identify import memo
    from rollaway.identify.calibrate import calibrate
    keys = [memo.key(data, args[0], args[1], _full(kwargs)) if fn is calibrate and len(args) == 2 else None
            for fn, args, kwargs in calls]
    out = [memo.lookup(k) for k in keys]
    todo: dict = {}
    for i, (k, fit) in enumerate(zip(keys, out)):
        if fit is None:
            todo.setdefault(i if k is None else k[0], []).append(i)
    done = _run(data, [calls[idx[0]] for idx in todo.values()])
    for idx, fit in zip(todo.values(), done):
        memo.store(keys[idx[0]], fit)
        out[idx[0]] = fit
        for i in idx[1:]:
            out[i] = memo.lookup(keys[i]) or fit
    return out


def _run(data, calls: list[tuple]) -> list:
    global _CALLS
    n = min(cores(), len(calls))
    if (n < 2 or "fork" not in mp.get_all_start_methods() or mp.current_process().daemon
            or threading.current_thread() is not threading.main_thread()):
        return [fn(data, *args, **kwargs) for fn, args, kwargs in calls]
    _CALLS = (data, calls)
    try:
        with ProcessPoolExecutor(n, mp_context=mp.get_context("fork")) as pool:
            out = list(pool.map(_call, range(len(calls))))
    except Exception:        # noqa: BLE001 - no pool (limits, a killed worker, a fit that cannot be sent back):
        # one after another, which raises again any error of the fits themselves
        return [fn(data, *args, **kwargs) for fn, args, kwargs in calls]
    finally:
        _CALLS = (None, [])
    for fit in out:
        fit.data = data
    return out


def fit_all(data, jobs: list[tuple]) -> list:
    """``[calibrate(data, effects, params, **kwargs) for effects, params, kwargs in jobs]`` by :func:`run_fits`."""
    from rollaway.identify.calibrate import calibrate
    return run_fits(data, [(calibrate, (effects, params), kwargs) for effects, params, kwargs in jobs])


def _full(kwargs: dict) -> dict:
    """*kwargs* of a :func:`~rollaway.identify.calibrate.calibrate` call with its defaults filled in (as
    calibrate keys its own calls)."""
    return dict(dict(free=None, start=None, model=None, per_test=True, statistics=True, max_iterations=None),
                **kwargs)


__all__ = ["cores", "fit_all", "run_fits"]
