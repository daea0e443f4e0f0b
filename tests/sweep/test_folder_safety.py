"""A sweep folder belongs to one sweep: lock, spec fingerprint, no orphan workers, damaged journal lines."""
import json
import os
import signal
import subprocess
import sys
import time

import pandas as pd
import psutil
import pytest

from rollaway.errors import UserError
from rollaway.hold.scenario import preset_scenarios
from rollaway.sweep import grid_spec, run_sweep
from rollaway.sweep.folder import FolderLock
from rollaway.sweep.store import JOURNAL, Journal

BASE = preset_scenarios("fmvss135")[0]
SPEC = """base_preset = "fmvss135"
simulate = "all"
[grid]
grade_pct = { start = 10, stop = 45, num = 12 }
hand_force_N = [250, 400]
duration_s = [30]
"""


class FakeResult:
    outcome, rollaway_time_s, max_displacement_m, min_margin, creep_m, wall_time_s, sim_time_s = \
        "held", None, 0.0, 1.5, 0.0, 0.0, 1.0


def fake_simulate(scenario, mode="fast"):
    return FakeResult()


def start(spec, out, *extra):
    cmd = [sys.executable, "-c", "import sys; from rollaway.cli import main; sys.exit(main())",
           "sweep", str(spec), "--out", str(out), "--workers", "2", "--quiet", "--no-plots", *extra]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)


def wait_for(cond, proc, timeout_s=90):
    t0 = time.time()
    while not cond():
        assert proc.poll() is None, f"sweep ended early: {proc.communicate()}"
        assert time.time() - t0 < timeout_s, "timed out"
        time.sleep(0.05)


def journal_lines(out):
    p = out / JOURNAL
    return p.read_bytes().count(b"\n") if p.exists() else 0


def test_kill_9_leaves_no_worker_and_a_results_table(tmp_path):
    (tmp_path / "s.toml").write_text(SPEC)
    out = tmp_path / "out"
    proc = start(tmp_path / "s.toml", out)
    wait_for(lambda: journal_lines(out) >= 2, proc)
    children = psutil.Process(proc.pid).children(recursive=True)
    assert children, "expected worker processes"
    os.kill(proc.pid, signal.SIGKILL)                       # the parent only, as an OOM killer would
    proc.wait(10)
    t0 = time.time()
    gone, alive = psutil.wait_procs(children, timeout=10)
    assert not alive, f"orphans still alive after 10 s: {[p.pid for p in alive]}"
    assert time.time() - t0 < 10
    table = pd.read_parquet(out / "results.parquet")        # written before the first simulation
    assert len(table) == 48                                  # 12 grades × 2 forces × 2 directions
    # the folder is not locked by the dead sweep: a rerun takes it over and finishes
    proc = start(tmp_path / "s.toml", out)
    stdout, stderr = proc.communicate(timeout=180)
    assert proc.returncode == 0, stderr
    assert pd.read_parquet(out / "results.parquet")["simulated"].all()


def test_second_sweep_into_a_busy_folder_is_refused(tmp_path, run_cli):
    (tmp_path / "s.toml").write_text(SPEC)
    out = tmp_path / "out"
    proc = start(tmp_path / "s.toml", out)
    try:
        wait_for(lambda: journal_lines(out) >= 1, proc)
        code, _, err = run_cli("sweep", tmp_path / "s.toml", "--out", out, "--quiet", "--no-plots")
        assert code == 2
        assert "another sweep is writing into this folder" in err and f"pid {proc.pid}" in err
        assert err.count("\n") == 1 and "Traceback" not in err
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(10)


def test_lock_is_exclusive_and_released(tmp_path):
    with FolderLock(tmp_path):
        with pytest.raises(UserError, match="another sweep"):
            FolderLock(tmp_path).acquire()
    with FolderLock(tmp_path):     # released: can be taken again
        pass


def test_a_different_spec_in_the_folder_is_refused_with_the_way_out(tmp_path, run_cli):
    a = tmp_path / "a.toml"
    b = tmp_path / "b.toml"
    a.write_text('base_preset = "fmvss135"\nsimulate = "none"\n[grid]\ngrade_pct = [10, 20]\n')
    b.write_text('base_preset = "fmvss135"\nsimulate = "none"\n[grid]\ngrade_pct = [10, 30]\n')
    out = tmp_path / "out"
    assert run_cli("sweep", a, "--out", out, "--quiet", "--no-plots")[0] == 0
    assert run_cli("sweep", a, "--out", out, "--quiet", "--no-plots")[0] == 0       # same spec: resumes
    code, _, err = run_cli("sweep", b, "--out", out, "--quiet", "--no-plots")
    assert code == 2 and "holds the results of a different sweep" in err and "--fresh" in err
    assert str(a) in err
    code, _, err = run_cli("sweep", b, "--out", out, "--quiet", "--no-plots", "--fresh")
    assert code == 0, err
    assert set(pd.read_parquet(out / "results.parquet")["grade_pct"]) == {10.0, 30.0}


@pytest.mark.parametrize("damage", [b'{"point_id": "abc", "err\x00\x00\x00\n', b"\xff\xfe garbage \xc3\n",
                                    b"[1, 2, 3]\n", b'{"point_id": 17}\n', b"\x00" * 40 + b"\n"])
def test_damaged_journal_lines_are_dropped_and_rerun(tmp_path, damage):
    spec = grid_spec(BASE, {"grade_pct": [10, 20, 30], "duration_s": [30]}, simulate="all")
    out = tmp_path / "out"
    first = run_sweep(spec, out, workers=1, progress=False, plots=False, simulate_fn=fake_simulate)
    assert first.n_run == 3
    lines = (out / JOURNAL).read_bytes().splitlines(keepends=True)
    (out / JOURNAL).write_bytes(lines[0] + damage + lines[2] + damage[: len(damage) // 2])   # line 2 lost, torn tail
    again = run_sweep(spec, out, workers=1, progress=False, plots=False, simulate_fn=fake_simulate)
    assert again.n_resumed == 2 and again.n_run == 1
    recs = Journal(out).load()
    assert len(recs) == 3 and set(recs) == set(spec.points["point_id"])
    for raw in (out / JOURNAL).read_bytes().splitlines():
        assert isinstance(json.loads(raw.decode("utf-8")), dict)
