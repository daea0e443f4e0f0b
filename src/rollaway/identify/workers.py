"""Independent fits on the machine's cores.

A diagnosis screens many effect sets that do not depend on each other (each swap of a two-effect verdict, each
candidate of a forward step).  :func:`fit_all` runs such a list of :func:`~rollaway.identify.calibrate.calibrate`
calls on all cores: this process and one forked helper per further core each fit a fixed share of them (of n
processes, the k-th fits calls k, k + n, k + 2n, …).  A share, not the next call from a shared counter: the fits a
process makes inside its calls stay in its memo (:mod:`rollaway.identify.memo`; a helper's dies with it) and later
calls can find them there, so which process fitted which call must not depend on timing — a shared counter let a
short high-rate log's verdict change from one run to the next (a partner named in 9 of 15 runs, not in the other
6).  A forked helper inherits the data and every loaded effect (a plugin's too) and the calls
themselves without pickling them, and sends back each fit without its data (the caller's object is put back)
through a pipe this process drains as it goes.  This process works on the batch too, with its own caches warm, and
a batch costs one fork per further core and nothing else (a process pool costs its start, its queues and one more
process each time: 20–30 ms a batch here, a diagnosis runs 10–20 batches).
The results are the same, fit for fit, as one after another: each fit is deterministic and independent.
A fit a later step will likely ask for can be started at once in a background process of its own (:func:`ahead`),
beside whatever this process does next; it reaches the memo when asked for (:mod:`rollaway.identify.memo`).

One after another instead: one core (``ROLLAWAY_WORKERS=1`` or the process's CPU affinity), no ``fork``
(Windows), inside a daemonic process (a multiprocessing pool's worker cannot have children), outside the main
thread (a thread of a threaded scheduler: forking there may copy a lock another thread holds), or fewer than two
fits.  A helper that cannot be started, is killed, or whose fit fails or cannot be sent back leaves its fits to
this process, which raises any error of their own.
"""
from __future__ import annotations

import multiprocessing as mp
import os
import pickle
import signal
import threading

from rollaway.errors import UserError

_CALLS: tuple = (None, [])   # (data, calls) in flight: inherited by the forked helpers, never pickled
_fork = os.fork if hasattr(os, "fork") else None


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
    if (n < 2 or _fork is None or mp.current_process().daemon
            or threading.current_thread() is not threading.main_thread()):
        return [fn(data, *args, **kwargs) for fn, args, kwargs in calls]
    _CALLS = (data, calls)
    try:
        out = _shared(data, calls, n)
    finally:
        _CALLS = (None, [])
    for i, fit in enumerate(out):
        if fit is None:          # a helper's fit that did not come back: fitted here (raises its own error)
            fn, args, kwargs = calls[i]
            out[i] = fn(data, *args, **kwargs)
        else:
            fit.data = data
    return out


def _shared(data, calls: list[tuple], n: int) -> list:
    """The fits of *calls* shared between this process and up to *n* − 1 forked helpers, the k-th of them fitting
    calls k, k + n, … (this process the 0-th); ``None`` where a helper's fit did not come back (or a helper could
    not be forked: :func:`_run` fits those here)."""
    count = len(calls)
    out: list = [None] * count
    helpers, readers, finished = [], [], False
    try:
        for _ in range(n - 1):
            r, w = os.pipe()
            try:
                pid = _fork()
            except OSError:      # no process to be had (limits): fewer helpers
                os.close(r)
                os.close(w)
                break
            if pid == 0:         # a helper: fits until none is left, each sent back as it is done; never returns
                _helper(r, w, _stride(len(helpers) + 1, n), count, helpers)
            os.close(w)
            helpers.append((pid, r))
        for pid, r in helpers:
            t = threading.Thread(target=_drain, args=(r, out), daemon=True)
            t.start()
            readers.append(t)
        take = _stride(0, n)
        while (i := take()) < count:
            fn, args, kwargs = calls[i]
            out[i] = fn(data, *args, **kwargs)
            out[i].data = None   # as a helper's (the caller's object is put back)
        for t in readers:
            t.join()
        finished = True
    finally:
        for k, (pid, r) in enumerate(helpers):
            if not finished:     # this process failed or was interrupted: stop the helpers
                _kill(pid)
                if k >= len(readers):                  # a pipe nobody reads
                    os.close(r)
            try:
                os.waitpid(pid, 0)
            except ChildProcessError:
                pass
    return out


def _stride(first: int, step: int):
    """The indices *first*, *first* + *step*, … one by one."""
    nxt = [first]

    def take() -> int:
        i = nxt[0]
        nxt[0] += step
        return i
    return take


def _helper(r: int, w: int, take, count: int, earlier) -> None:
    """A forked helper's life: the next fit while any is left, each written to *w* as length + pickle; ends the
    process (it never returns into the caller's frames)."""
    code = 0
    try:
        from rollaway.identify import memo
        memo.forked()                                # the background fits' pipes are the caller's to read
        os.close(r)
        for _, other in earlier:                     # the pipes of the helpers forked before it are not its own
            os.close(other)
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        with os.fdopen(w, "wb") as pipe:
            while (i := take()) < count:
                try:
                    blob = pickle.dumps((i, _call(i)), protocol=pickle.HIGHEST_PROTOCOL)
                except Exception:    # noqa: BLE001 - the caller fits it again and raises the error itself
                    blob = pickle.dumps((i, None))
                pipe.write(len(blob).to_bytes(8, "little") + blob)
                pipe.flush()
    except BaseException:            # noqa: BLE001 - nothing of a helper may reach the caller's code
        code = 1
    finally:
        os._exit(code)


def _drain(r: int, out: list) -> None:
    """Read a helper's fits from its pipe into *out* until it ends (a cut-off record is dropped)."""
    with os.fdopen(r, "rb") as pipe:
        while (record := _record(pipe)) is not None:
            i, fit = record
            out[i] = fit


def _record(pipe):
    """The next (index, fit) a helper wrote to *pipe*, or None at its end (a cut-off record is dropped)."""
    head = pipe.read(8)
    if len(head) < 8:
        return None
    size = int.from_bytes(head, "little")
    blob = pipe.read(size)
    return pickle.loads(blob) if len(blob) == size else None


def ahead(data, jobs: list[tuple]) -> None:
    """Start the fit jobs ``(effects, params, kwargs)`` of :func:`~rollaway.identify.calibrate.calibrate` that a
    later step is likely to ask for, now, each in a forked background process of its own beside whatever this process
    does next (a serial fit that would otherwise leave a core idle; a step that asks for two waits for the longer,
    not for both one after the other: 0.59 s of waiting on the slowest short high-rate log, where a partial form's
    fit and the re-formed first ran in one process).  Nothing is returned: a later ``calibrate`` of the same
    job gets the background's fit from the memo (:func:`rollaway.identify.memo.lookup` waits for one still running),
    the same numbers as fitted here (each fit is deterministic); one never asked for costs only the other core's
    time, and the process is stopped when the diagnosis ends.  Nothing where fits run one after another (the module
    docstring), outside a memo block, or for a job already kept or expected; nor for a job that another of *jobs*
    asks with a larger budget: where that one's passes end below this one's budget its fit is this one's too
    (:func:`rollaway.identify.memo.lookup`; else this one is fitted when asked)."""
    from rollaway.identify import memo
    from rollaway.identify.calibrate import calibrate
    if (cores() < 2 or _fork is None or mp.current_process().daemon
            or threading.current_thread() is not threading.main_thread()):
        return
    keys, calls = [], []
    every = [memo.key(data, effects, params, _full(kwargs)) for effects, params, kwargs in jobs]
    for k, (effects, params, kwargs) in zip(every, jobs):
        if (k is not None and not memo.known(k) and k[0] not in (kk[0] for kk in keys)
                and not memo.larger_budget(k, every)):     # its larger-budget twin's fit may be its own (memo)
            keys.append(k)
            calls.append((calibrate, (effects, params), kwargs))
    if not keys:
        return
    for k, call in zip(keys, calls):         # one process each: a step that asks for several waits for the longest
        _background(data, k, call)


def _background(data, k, call) -> None:
    """Fork one background process fitting *call* (memo key *k*); the memo gets its fit when asked for."""
    from rollaway.identify import memo
    r, w = os.pipe()
    try:
        pid = _fork()
    except OSError:              # no process to be had: the fit is made when asked
        os.close(r)
        os.close(w)
        return
    if pid == 0:                 # the background process: the fit, sent back when done; never returns
        global _CALLS
        _CALLS = (data, [call])
        order = iter(range(1))
        _helper(r, w, lambda: next(order, 1), 1, [])
    os.close(w)
    state = {"pipe": os.fdopen(r, "rb"), "fit": None}

    def stop():
        if state["pipe"] is not None:
            _kill(pid)
            state["pipe"].close()
            state["pipe"] = None
            _reap(pid)

    def wait():
        if state["pipe"] is not None:
            record = _record(state["pipe"])          # None: it ended (or failed): the fit is made when asked
            state["pipe"].close()
            state["pipe"] = None
            _reap(pid)
            if record is not None and record[1] is not None:
                fit = record[1]
                fit.data = data
                memo.store(k, fit)
    memo.expect(k, wait, stop)


def _reap(pid: int) -> None:
    try:
        os.waitpid(pid, 0)
    except ChildProcessError:
        pass


def _kill(pid: int) -> None:
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def fit_all(data, jobs: list[tuple]) -> list:
    """``[calibrate(data, effects, params, **kwargs) for effects, params, kwargs in jobs]`` by :func:`run_fits`."""
    from rollaway.identify.calibrate import calibrate
    return run_fits(data, [(calibrate, (effects, params), kwargs) for effects, params, kwargs in jobs])


def _full(kwargs: dict) -> dict:
    """*kwargs* of a :func:`~rollaway.identify.calibrate.calibrate` call with its defaults filled in (as
    calibrate keys its own calls)."""
    return dict(dict(free=None, start=None, model=None, per_test=True, statistics=True, max_iterations=None),
                **kwargs)


__all__ = ["ahead", "cores", "fit_all", "run_fits"]
