"""Independent fits on several cores: the same fits as one after another, and the cases that stay in-process."""
import multiprocessing as mp
import pickle

import numpy as np
import pytest

from rollaway.errors import UserError
from rollaway.identify import workers
from rollaway.identify.calibrate import calibrate
from rollaway.identify.workers import cores, fit_all, run_fits
from tests.identify.bench_generator import generate


@pytest.fixture(scope="module")
def data():
    return generate(["creep_power_law"], sampling="5min", seed=11, forces=np.linspace(180.0, 360.0, 3))


def _shape_fit(d, start):
    from rollaway.effects import get_effect
    from rollaway.identify.shape import flexible_effect
    return calibrate(d, [flexible_effect(get_effect("lining_creep"), d.time_s)], start=start)


def same(a: dict, b: dict) -> bool:
    return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)


def test_fits_on_several_cores_are_the_fits_one_after_another(data, monkeypatch):
    jobs = [([e], None, dict(max_iterations=6)) for e in ("lining_creep", "cable_relaxation", "friction_temperature")]
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    spawned = []
    real = workers._fork
    monkeypatch.setattr(workers, "_fork", lambda: spawned.append(1) or real())
    pooled = fit_all(data, jobs)
    assert spawned == [1]                          # one helper beside this process shared them
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    alone = fit_all(data, jobs)
    for a, b in zip(pooled, alone):
        assert same(a.values, b.values) and a.bic == b.bic and a.effects == b.effects
        assert a.data is data and np.array_equal(a.jacobian, b.jacobian)
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")          # a shape-free form (a class built at run time) comes back
    start = alone[0].values
    back = run_fits(data, [(_shape_fit, (start,), {}), (_shape_fit, (start,), {})])
    assert back[0].effects == ["lining_creep_shape"] and same(back[0].values, _shape_fit(data, start).values)


def test_a_shape_free_effect_pickles_as_its_base_and_knots():
    from rollaway.effects import get_effect
    from rollaway.effects.shape_free import spline_effect
    e = spline_effect(get_effect("cable_relaxation"), [0.0, 600.0, 3600.0])()
    back = pickle.loads(pickle.dumps(e))
    assert back.name == "cable_relaxation_shape" and list(back.knots) == [0.0, 600.0, 3600.0]


def test_workers_setting_is_validated_and_one_worker_stays_in_process(data, monkeypatch):
    monkeypatch.setenv("ROLLAWAY_WORKERS", "two")
    with pytest.raises(UserError, match="ROLLAWAY_WORKERS"):
        cores()
    monkeypatch.setenv("ROLLAWAY_WORKERS", "0")
    with pytest.raises(UserError, match="at least 1"):
        cores()
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    monkeypatch.setattr(workers, "_fork", lambda: pytest.fail("no helper with one worker"))
    assert len(fit_all(data, [(["lining_creep"], None, {}), (["cable_relaxation"], None, {})])) == 2


def test_a_helper_that_cannot_start_or_dies_or_fails_leaves_its_fits_to_this_process(data, monkeypatch):
    import os
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    jobs = [(["lining_creep"], None, {}), (["cable_relaxation"], None, {}), (["friction_temperature"], None, {})]
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    alone = fit_all(data, jobs)
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")

    def broken(*_):
        raise OSError("no processes here")
    monkeypatch.setattr(workers, "_fork", broken)
    fits = fit_all(data, jobs)
    assert [f.effects for f in fits] == [["lining_creep"], ["cable_relaxation"], ["friction_temperature"]]
    monkeypatch.undo()
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    for death in (lambda i: os._exit(9), lambda i: 1 / 0):       # killed on its first fit; a fit that raises there
        monkeypatch.setattr(workers, "_call", death)
        fits = fit_all(data, jobs)
        for a, b in zip(fits, alone):
            assert a.effects == b.effects and a.bic == b.bic and a.data is data
    monkeypatch.setattr(mp, "current_process", lambda: type("P", (), {"daemon": True})())
    monkeypatch.setattr(workers, "_fork", lambda: pytest.fail("a daemon cannot have children"))
    assert len(fit_all(data, jobs[:2])) == 2


def test_each_process_fits_a_fixed_share_whatever_the_timing(data, monkeypatch):
    """Of n processes the k-th fits calls k, k + n, …: the fits a process makes inside its calls stay in its memo and
    later calls find them there, so who fits what must not follow which process is free first (a shared counter gave
    this process only the slow first call here, the helper all the rest; a short high-rate log's verdict then
    changed from run to run)."""
    import os
    import time
    from types import SimpleNamespace
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")

    def who(d, i):
        time.sleep(0.4 if i == 0 else 0.01)
        return SimpleNamespace(pid=os.getpid(), data=None)
    got = run_fits(data, [(who, (i,), {}) for i in range(8)])
    here = [i for i, g in enumerate(got) if g.pid == os.getpid()]
    assert here == [0, 2, 4, 6], here
    assert len({g.pid for g in got}) == 2


def test_an_error_of_a_fit_itself_is_raised_here(data, monkeypatch):
    """A fit that fails in a helper fails again here, with its own error (the message the user reads)."""
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")

    def bad(d, x):
        raise UserError(f"plugin value {x} is not a number")
    with pytest.raises(UserError, match=r"plugin value \d is not a number"):
        run_fits(data, [(bad, (1,), {}), (bad, (2,), {}), (bad, (3,), {})][::-1])


def test_outside_the_main_thread_the_fits_stay_in_process(data, monkeypatch):
    import threading
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    monkeypatch.setattr(workers, "_fork", lambda: pytest.fail("no fork outside the main thread"))
    out = []
    t = threading.Thread(target=lambda: out.append(fit_all(data, [(["lining_creep"], None, {}),
                                                                  (["cable_relaxation"], None, {})])))
    t.start()
    t.join()
    assert [f.effects for f in out[0]] == [["lining_creep"], ["cable_relaxation"]]


def _counted_fits(monkeypatch) -> list:
    """Patch the fit itself to count the fits this process makes (a forked process counts its own)."""
    import rollaway.identify.calibrate as cal
    made, real = [], cal._calibrate
    monkeypatch.setattr(cal, "_calibrate", lambda *a: made.append(a[1]) or real(*a))
    return made


def test_a_fit_started_ahead_is_the_fit_made_here_and_is_not_made_again(data, monkeypatch):
    import os
    from rollaway.identify import memo
    job = (["lining_creep"], None, dict(max_iterations=6))
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    here = calibrate(data, job[0], job[1], **job[2])
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    made = _counted_fits(monkeypatch)
    pids, real = [], workers._fork
    monkeypatch.setattr(workers, "_fork", lambda: (lambda pid: pids.append(pid) or pid)(real()))
    with memo.fit_memo():
        workers.ahead(data, [job])
        assert len(pids) == 1 and memo.known(memo.key(data, job[0], job[1], workers._full(job[2])))
        workers.ahead(data, [job])                           # expected already: no second process
        assert len(pids) == 1
        fit_all(data, [(["cable_relaxation"], None, dict(max_iterations=3)),     # a batch in between
                       (["friction_temperature"], None, dict(max_iterations=3))])
        back = calibrate(data, job[0], job[1], **job[2])
    assert ["lining_creep"] not in made                      # it came from the background
    assert same(back.values, here.values) and back.bic == here.bic and np.array_equal(back.jacobian, here.jacobian)
    assert back.data is data
    with pytest.raises(ChildProcessError):                   # the background process was waited for
        os.waitpid(pids[0], os.WNOHANG)


def test_a_background_fit_never_asked_for_is_stopped_and_a_dead_one_is_fitted_here(data, monkeypatch):
    import os
    from rollaway.identify import memo
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    pids, real = [], workers._fork
    monkeypatch.setattr(workers, "_fork", lambda: (lambda pid: pids.append(pid) or pid)(real()))
    with memo.fit_memo():
        workers.ahead(data, [(["friction_temperature"], None, {})])
    with pytest.raises(ChildProcessError):                   # stopped and waited for when the block ended
        os.waitpid(pids[0], os.WNOHANG)
    assert not memo._PENDING and not memo._ENDS
    made = _counted_fits(monkeypatch)
    monkeypatch.setattr(workers, "_call", lambda i: os._exit(9))   # the background process dies on its fit
    job = (["cable_relaxation"], None, dict(max_iterations=4))
    with memo.fit_memo():
        workers.ahead(data, [job])
        fit = calibrate(data, job[0], job[1], **job[2])
    assert made == [["cable_relaxation"]] and fit.effects == ["cable_relaxation"]
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")              # one worker, or no memo block: nothing is started
    monkeypatch.setattr(workers, "_fork", lambda: pytest.fail("no background process with one worker"))
    with memo.fit_memo():
        workers.ahead(data, [job])
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    workers.ahead(data, [job])


def test_two_fits_started_ahead_run_side_by_side_each_in_its_own_process(data, monkeypatch):
    """A step that asks for two background fits waits for the longer, not for both in turn: each job has a process
    of its own, both are the fits made here, and both processes are waited for."""
    import os
    from rollaway.identify import memo
    jobs = [(["lining_creep"], None, dict(max_iterations=6)), (["cable_relaxation"], None, dict(max_iterations=6))]
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    here = [calibrate(data, e, p, **kw) for e, p, kw in jobs]
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    made = _counted_fits(monkeypatch)
    pids, real = [], workers._fork
    monkeypatch.setattr(workers, "_fork", lambda: (lambda pid: pids.append(pid) or pid)(real()))
    with memo.fit_memo():
        workers.ahead(data, jobs)
        assert len(pids) == 2
        back = [calibrate(data, e, p, **kw) for e, p, kw in reversed(jobs)][::-1]   # asked for in either order
    assert not made
    for b, h in zip(back, here):
        assert same(b.values, h.values) and b.bic == h.bic and b.data is data
    for pid in pids:
        with pytest.raises(ChildProcessError):
            os.waitpid(pid, os.WNOHANG)


def test_of_two_jobs_that_differ_only_in_budget_one_process_fits_the_larger_and_serves_both(data, monkeypatch):
    """A job asked ahead beside the same job with a larger budget has no process of its own: where the larger's
    passes end below its budget, the larger's fit is its fit, the same numbers as fitted here with its own budget;
    a budget the larger's passes reached is fitted when asked."""
    from rollaway.identify import memo
    monkeypatch.setenv("ROLLAWAY_WORKERS", "1")
    big = calibrate(data, ["lining_creep"])
    peak, k = big.fit_info["stages"][0]["peak_calls"], len(big.names) + 1
    loose, tight = peak // k + 1, max(peak // k, 1)
    here = {m: calibrate(data, ["lining_creep"], max_iterations=m) for m in (loose, tight)}
    monkeypatch.setenv("ROLLAWAY_WORKERS", "2")
    pids, real = [], workers._fork
    monkeypatch.setattr(workers, "_fork", lambda: (lambda pid: pids.append(pid) or pid)(real()))
    for m in (loose, tight):
        made = _counted_fits(monkeypatch)
        with memo.fit_memo():
            workers.ahead(data, [(["lining_creep"], None, {}), (["lining_creep"], None, dict(max_iterations=m))])
            assert len(pids) == 1
            got = calibrate(data, ["lining_creep"], max_iterations=m)
        pids.clear()
        assert same(got.values, here[m].values) and got.bic == here[m].bic
        assert len(made) == (m == tight), (m, made)
