"""Interrupted sweeps continue where they stopped: no point lost, none done twice (real MuJoCo)."""
import json
import os
import signal
import subprocess
import sys
import time

import pandas as pd
import pytest

SPEC = """base_preset = "fmvss135"
simulate = "all"
[grid]
grade_pct = { start = 10, stop = 45, num = 18 }
occupants = [1, 5]
hand_force_N = [250, 400]
duration_s = [30]
"""
N_POINTS = 18 * 2 * 2 * 2


def _sigint_as_in_a_terminal():
    """A shell starts background jobs with SIGINT ignored, and Python keeps it ignored: undo that."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def start(spec, out):
    cmd = [sys.executable, "-c", "import sys; from rollaway.cli import main; sys.exit(main())",
           "sweep", str(spec), "--out", str(out), "--workers", "2", "--quiet", "--no-plots"]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                            preexec_fn=_sigint_as_in_a_terminal)


def journal_ids(out):
    path = out / "journal.jsonl"
    if not path.exists():
        return []
    ids = []
    for line in path.read_text().splitlines():
        try:
            ids.append(json.loads(line)["point_id"])
        except (json.JSONDecodeError, KeyError):
            pass
    return ids


def wait_for_lines(proc, out, n, timeout_s=60):
    t0 = time.time()
    while len(journal_ids(out)) < n:
        assert proc.poll() is None, f"sweep ended before {n} points: {proc.communicate()}"
        assert time.time() - t0 < timeout_s
        time.sleep(0.02)


def check_complete(out):
    ids = journal_ids(out)
    assert len(ids) == len(set(ids)) == N_POINTS, "a point lost or done twice"
    t = pd.read_parquet(out / "results.parquet")
    assert len(t) == N_POINTS and t["point_id"].is_unique
    assert t["simulated"].all() and (t["error"] == "").all()
    assert set(t["point_id"]) == set(ids)
    return t


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    d = tmp_path_factory.mktemp("ref")
    (d / "s.toml").write_text(SPEC)
    proc = start(d / "s.toml", d / "out")
    assert proc.wait(120) == 0, proc.communicate()
    return check_complete(d / "out"), d


@pytest.mark.parametrize("how", ["SIGKILL", "SIGINT"])
def test_interrupted_sweep_resumes_without_loss_or_duplicates(tmp_path, reference, how):
    (tmp_path / "s.toml").write_text(SPEC)
    out = tmp_path / "out"
    proc = start(tmp_path / "s.toml", out)
    wait_for_lines(proc, out, 25)
    os.killpg(proc.pid, getattr(signal, how))        # the whole group: as a terminal's Ctrl-C, or kill -9
    code = proc.wait(60)
    done_first = len(journal_ids(out))
    assert 25 <= done_first < N_POINTS
    if how == "SIGINT":
        assert code == 130 and "run the same command again" in proc.communicate()[1]
        partial = pd.read_parquet(out / "results.parquet")  # consolidated on Ctrl-C
        assert len(partial) == N_POINTS and partial["simulated"].sum() == done_first
    else:
        assert code == -signal.SIGKILL
    proc = start(tmp_path / "s.toml", out)
    stdout, stderr = proc.communicate(timeout=120)
    assert proc.returncode == 0, stderr
    assert f"({N_POINTS - done_first} now, {done_first} from an earlier run)" in stdout
    t = check_complete(out)
    drop = ["wall_time_s"]
    pd.testing.assert_frame_equal(t.drop(columns=drop), reference[0].drop(columns=drop))


def test_rerun_of_a_finished_sweep_simulates_nothing(reference):
    folder = reference[1]
    out = folder / "out"
    proc = start(folder / "s.toml", out)
    stdout, _ = proc.communicate(timeout=60)
    assert proc.returncode == 0 and f"(0 now, {N_POINTS} from an earlier run)" in stdout
    check_complete(out)
