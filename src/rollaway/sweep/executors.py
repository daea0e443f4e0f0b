"""Where the simulations of a sweep run: in-process, local processes, or a Dask cluster.

A *task* is a plain dict (picklable, small): the base scenario as plain values, the point's
changes and its id.  :func:`run_task` builds the scenario, simulates it and returns a plain
record; it never raises — a failing point (bad input, diverged simulation, any exception)
comes back with its ``error`` text and the sweep carries on.

Executors yield records as points finish, in completion order.  ``cancel()`` drops the
points not started (Ctrl-C); the caller journals what has finished.
"""
from __future__ import annotations

import math
import multiprocessing
import os
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from functools import partial

from rollaway.errors import UserError
from rollaway.model.parameters import BrakeParameters
from rollaway.hold.scenario import Scenario

SimulateFn = Callable[..., object]
SIM_FIELDS = ("outcome", "rollaway_time_s", "max_displacement_m", "min_margin", "creep_m", "wall_time_s",
              "sim_time_s")


def scenario_to_dict(s: Scenario) -> dict:
    return {"name": s.name, "grade_pct": s.grade_pct, "direction": s.direction, "occupants": s.occupants,
            "hand_force_N": s.hand_force_N, "duration_s": s.duration_s, "description": s.description,
            "regulation": s.regulation, "params": s.params.as_dict(), "params_name": s.params.name,
            "effects": [e.name for e in s.model.effects], "effect_values": dict(s.model.values),
            "effect_files": {e.name: getattr(type(e), "__rollaway_source__", None) for e in s.model.effects}}


def scenario_from_dict(d: dict) -> Scenario:
    """Rebuild a scenario in a worker (plugin effects are imported again from their files)."""
    from rollaway.effects import available_effects, load_effect_file
    from rollaway.model.drum_model import DrumModel

    d = dict(d)
    params = BrakeParameters(**d.pop("params"), name=d.pop("params_name"))
    effects, values, files = d.pop("effects", []), d.pop("effect_values", {}), d.pop("effect_files", {})
    for name in effects:
        if name not in available_effects() and files.get(name):
            load_effect_file(files[name])
    return Scenario(params=params, model=DrumModel(params, effects, values), **d)


def make_task(point_id: str, base: dict, changes: dict) -> dict:
    return {"point_id": point_id, "base": base, "changes": changes}


def _default_simulate(scenario, **kw):
    from rollaway.sim import simulate
    return simulate(scenario, **kw)


def run_task(task: dict, simulate_fn: SimulateFn | None = None) -> dict:
    """Simulate one point; return a plain record (``error`` is "" on success)."""
    start = time.perf_counter()
    rec = {"point_id": task["point_id"], "error": "", "worker": f"{socket.gethostname()}:{os.getpid()}"}
    try:
        scenario = scenario_from_dict(task["base"]).replace(**task["changes"])
        res = (simulate_fn or _default_simulate)(scenario, mode="fast")
        for f in SIM_FIELDS:
            v = getattr(res, f, None)
            rec[f"sim_{f}"] = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v
        if rec["sim_outcome"] == "diverged":
            raise FloatingPointError(f"simulation diverged: {getattr(res, 'diverged_reason', '')}")
        if rec["sim_outcome"] not in ("held", "brake_slip", "tyre_skid"):
            raise RuntimeError(f"simulator returned outcome {rec['sim_outcome']!r}")
        disp = rec.get("sim_max_displacement_m")
        if disp is not None and not math.isfinite(disp):
            raise FloatingPointError("simulation diverged (non-finite displacement)")
    except Exception as exc:  # noqa: BLE001 - a failing point is recorded, never fatal
        rec = {k: v for k, v in rec.items() if not k.startswith("sim_")}
        rec["error"] = f"{type(exc).__name__}: {exc}".strip()
    rec["wall_time_s"] = time.perf_counter() - start
    return rec


WATCHDOG_PERIOD_S = 0.5
_PR_SET_PDEATHSIG = 1


def _parent_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:      # a process of another user took the pid: ours is gone
        return False
    return True


def _watchdog(parent_pid: int) -> None:
    while True:
        time.sleep(WATCHDOG_PERIOD_S)
        if os.getppid() == 1 or not _parent_alive(parent_pid):
            os._exit(3)


def _worker_init(parent_pid: int) -> None:
    """Workers leave Ctrl-C to the parent, and exit within a second when the sweep process dies.

    The sweep process is not the workers' parent under forkserver, so a thread polls it
    (``kill(pid, 0)``); where the sweep is the parent, the kernel's parent-death signal
    (``prctl(PR_SET_PDEATHSIG)``, Linux) ends the worker at once.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if os.getppid() == parent_pid and sys.platform.startswith("linux"):
        try:
            import ctypes
            ctypes.CDLL(None, use_errno=True).prctl(_PR_SET_PDEATHSIG, signal.SIGKILL)
        except (OSError, AttributeError):
            pass
    threading.Thread(target=_watchdog, args=(parent_pid,), daemon=True, name="rollaway-watchdog").start()


class SerialExecutor:
    """Run tasks one after the other in this process (``--workers 1``, small runs)."""

    def __init__(self, simulate_fn: SimulateFn | None = None):
        self.fn = partial(run_task, simulate_fn=simulate_fn)
        self._cancelled = False

    def run(self, tasks: Iterable[dict]) -> Iterator[dict]:
        for t in tasks:
            if self._cancelled:
                return
            yield self.fn(t)

    def cancel(self) -> None:
        self._cancelled = True

    def finished(self) -> Iterator[dict]:
        return iter(())

    def close(self) -> None:
        pass


def _mp_context():
    """forkserver (no fork of a threaded parent), with rollaway and MuJoCo preloaded once.

    Like spawn, it re-imports the main script in the workers; a main read from stdin
    (``python -``) cannot be, so that case falls back to fork.
    """
    main_path = getattr(sys.modules.get("__main__"), "__file__", None)
    if main_path and not os.path.exists(main_path):
        return multiprocessing.get_context("fork")
    ctx = multiprocessing.get_context("forkserver")
    ctx.set_forkserver_preload(["rollaway.sweep.executors", "rollaway.sim"])
    return ctx


class ProcessExecutor:
    """Local worker processes (one per core by default); tasks go out in a bounded window."""

    def __init__(self, workers: int, simulate_fn: SimulateFn | None = None):
        self.pool = ProcessPoolExecutor(max_workers=workers, mp_context=_mp_context(), initializer=_worker_init,
                                        initargs=(os.getpid(),))
        self.fn = partial(run_task, simulate_fn=simulate_fn)
        self.window = 4 * workers
        self._pending: set[Future] = set()
        self._cancelled = False

    def run(self, tasks: Iterable[dict]) -> Iterator[dict]:
        it = iter(tasks)
        by_future: dict[Future, dict] = {}
        while True:
            while not self._cancelled and len(self._pending) < self.window:
                t = next(it, None)
                if t is None:
                    break
                fut = self.pool.submit(self.fn, t)
                by_future[fut] = t
                self._pending.add(fut)
            if not self._pending:
                return
            done, self._pending = wait(self._pending, return_when=FIRST_COMPLETED)
            for fut in done:
                task = by_future.pop(fut)
                if fut.cancelled():
                    continue
                try:
                    yield fut.result()
                except Exception as exc:  # noqa: BLE001 - e.g. a worker process died
                    yield {"point_id": task["point_id"], "error": f"{type(exc).__name__}: {exc}", "wall_time_s": 0.0}

    def cancel(self) -> None:
        self._cancelled = True
        for f in self._pending:
            f.cancel()

    def finished(self) -> Iterator[dict]:
        """Records of points that completed while cancelling (so they are not lost)."""
        for f in list(self._pending):
            if f.done() and not f.cancelled() and f.exception() is None:
                yield f.result()

    def close(self) -> None:
        self.pool.shutdown(wait=True, cancel_futures=True)


class DaskExecutor:
    """Tasks sent to a running ``dask.distributed`` scheduler (``--dask tcp://host:8786``)."""

    def __init__(self, address: str, simulate_fn: SimulateFn | None = None):
        from distributed import Client
        try:
            self.client = Client(address, timeout=f"{os.environ.get('ROLLAWAY_DASK_TIMEOUT_S', '15')}s")
        except (OSError, TimeoutError, ValueError) as exc:
            raise UserError(f"cannot reach the Dask scheduler at '{address}' ({exc}); start one with "
                            f"'dask scheduler' and workers with 'dask worker ADDRESS', or drop --dask") from None
        self.fn = partial(run_task, simulate_fn=simulate_fn)
        self.futures = []

    def run(self, tasks: Iterable[dict]) -> Iterator[dict]:
        from distributed import as_completed
        tasks = list(tasks)
        if not tasks:
            return
        self.futures = self.client.map(self.fn, tasks, pure=False)
        by_key = {f.key: t for f, t in zip(self.futures, tasks)}
        for fut in as_completed(self.futures):
            try:
                yield fut.result()
            except Exception as exc:  # noqa: BLE001 - KilledWorker and the like
                yield {"point_id": by_key[fut.key]["point_id"], "error": f"{type(exc).__name__}: {exc}",
                       "wall_time_s": 0.0}

    def cancel(self) -> None:
        if self.futures:
            self.client.cancel(self.futures)

    def finished(self) -> Iterator[dict]:
        for f in self.futures:
            if f.status == "finished":
                yield f.result()

    def close(self) -> None:
        self.client.close()


def make_executor(n_tasks: int, workers: int | None = None, dask_address: str | None = None,
                  simulate_fn: SimulateFn | None = None):
    """Pick the executor: Dask if an address is given, else processes (serial for 1 worker or 1 task)."""
    if dask_address:
        return DaskExecutor(dask_address, simulate_fn)
    n = workers if workers is not None else (os.cpu_count() or 1)
    n = max(1, min(n, n_tasks))
    return SerialExecutor(simulate_fn) if n == 1 else ProcessExecutor(n, simulate_fn)
