"""Pseudo-residual noise estimates stay finite where the cooling coordinate e^{−t/τ} underflows to 0."""
import numpy as np
import pytest

from rollaway.bench.noise import noise_estimate, pseudo_residuals
from rollaway.identify.synth import synth


def test_windows_where_the_cooling_coordinate_underflows_use_time():
    t = np.array([0.0, 1e4, 2e4, 7.4e5, 7.5e5, 7.6e5, 7.7e5])     # exp(−t/1000) = 0 from 7.5e5 s on
    y = np.sin(t / 3e4)
    e, level, w, c = pseudo_residuals(t, y, np.zeros(t.size, int), 1000.0, 1)
    assert np.all(np.isfinite(e)) and np.all(np.isfinite(c)) and len(e) == t.size - 2


def test_a_long_log_gives_a_finite_noise_estimate():
    d = synth([], seed=5, dt_s=600.0, duration_s=3600.0, hand_forces_N=(250.0,))
    d.time_s = d.time_s * 1000.0                      # the same log, its time read as if in ms
    n = noise_estimate(d, d.torque_Nm, 1000.0, relative=True)
    assert n is not None and np.isfinite(n.sigma)


def test_a_dense_log_is_estimated_on_evenly_spread_windows_and_finds_its_noise(monkeypatch):
    import rollaway.bench.noise as noise
    from rollaway.bench.measurements import Measurements
    from rollaway.bench.noise import MAX_WINDOWS
    rng = np.random.default_rng(3)
    n = 4 * MAX_WINDOWS                                   # one test at 100 Hz, heavy-tailed noise of known σ
    t = np.arange(n) * 0.01
    torque = 800.0 - 0.02 * t + 8.0 * rng.standard_t(4, n) / np.sqrt(2.0)
    d = Measurements(np.full(n, "D300"), np.full(n, "downhill"), np.full(n, 300.0), t,
                     180.0 - 0.01 * t + 1.5 * rng.standard_normal(n), torque)
    e, level, w, c = pseudo_residuals(d.time_s, d.torque_Nm, d.test_index, 1000.0, 1, max_windows=MAX_WINDOWS)
    assert len(e) <= MAX_WINDOWS and np.all(np.diff(w[:, 0]) >= w.shape[1])      # spread, not overlapping
    assert w[-1, 0] > 0.9 * n                                                      # over the whole log
    nt = noise_estimate(d, d.drum_temp_C, 1000.0)
    assert abs(nt.sigma / 1.5 - 1.0) < 0.03 and nt.dof <= 1.5 * MAX_WINDOWS
    nq = noise_estimate(d, d.torque_Nm, 1000.0, relative=True)
    monkeypatch.setattr(noise, "MAX_WINDOWS", None)                   # every window: the same noise, within 3 %
    every = noise_estimate(d, d.torque_Nm, 1000.0, relative=True)
    assert abs(nq.at(800.0) / every.at(800.0) - 1.0) < 0.03 and abs(nq.mean_factor / every.mean_factor - 1) < 0.03


@pytest.mark.parametrize("command", [("compare",), ("diagnose",), ("fit", "--effect", "lining_creep")])
def test_a_torque_column_of_zeros_is_one_line_naming_the_column(tmp_path, run_cli, command):
    """A log whose torque is 0 in every row measured nothing (a column map pointing at an unused channel): exit 2 and
    one line naming the file and the column, no traceback."""
    csv = tmp_path / "zero.csv"
    code, _, err = run_cli("synth", "--seed", "1", "--out", csv)
    assert code == 0, err
    lines = csv.read_text().splitlines()
    col = lines[0].split(",").index("torque_Nm")
    rows = [r.split(",") for r in lines[1:]]
    for r in rows:
        r[col] = "0"
    csv.write_text("\n".join([lines[0]] + [",".join(r) for r in rows]) + "\n")
    code, out, err = run_cli(command[0], csv, *command[1:])
    assert code == 2, (out, err)
    assert "Traceback" not in err and f"{csv}, column 'torque_Nm': 0 in every row" in err

