"""Reduction of dense bench logs: same verdict and μ_d interval as the raw log, no bias from the windows, the
raw-rate noise recovered, and the result independent of how the log was cut into batches."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from rollaway.identify.calibrate import calibrate
from rollaway.identify.diagnose import diagnose
from rollaway.identify.model import BenchModel
from rollaway.bench.noise import noise_estimate, sample_sigma
from rollaway.bench.reduction import Reducer, reduce_measurements
from rollaway.bench.batch import Batch, Text
from rollaway.identify.synth import synth

CANDIDATES = ["lining_creep", "cable_relaxation", "friction_temperature"]


def _log(effects=("lining_creep",), seed=4, dt_s=0.1, duration_s=600.0, **kw):
    """10 Hz, 4 tests × 10 min (24 000 rows)."""
    return synth(list(effects), seed=seed, dt_s=dt_s, duration_s=duration_s, hand_forces_N=(200.0, 320.0), **kw)


@pytest.mark.parametrize("effects", [("lining_creep",), ()])
def test_raw_and_reduced_10hz_log_give_the_same_verdict_and_mu_interval(effects):
    raw = _log(effects, duration_s=420.0)         # small enough to diagnose sample by sample in a test
    red = reduce_measurements(raw)
    assert red.reduction.reduced and len(red) < len(raw) / 10
    a, b = diagnose(raw, effects=CANDIDATES), diagnose(red, effects=CANDIDATES)
    assert a.verdict == b.verdict == (effects[0] if effects else "none")
    ia, ib = a.refined.estimates["mu_drum"], b.refined.estimates["mu_drum"]
    truth = raw.truth["values"]["mu_drum"]
    assert abs(ia.value - truth) < 4 * ia.stderr and abs(ib.value - truth) < 4 * ib.stderr
    assert abs(ia.value - ib.value) < 0.25 * ia.stderr          # the same estimate to a quarter of its error
    assert ib.stderr == pytest.approx(ia.stderr, rel=0.1)       # and the same information


def test_window_means_are_unbiased_against_their_standard_error():
    """Noise-free 10 Hz log: each window mean equals the model at the window's mean time to ≪ its standard error."""
    clean = _log(("lining_creep",), noise_torque_Nm=0.0, noise_temp_C=0.0, duration_s=3600.0)
    red = reduce_measurements(clean)
    model = BenchModel(None, ["lining_creep"])
    pred = model.predict(red, {**clean.truth["values"], "initial_temp_C": red.test_initial_temp_C})
    se_torque = 8.0 / np.sqrt(red.count)            # what the rows would carry at synth's default noise
    se_temp = 1.5 / np.sqrt(red.count)
    assert np.max(np.abs(red.torque_Nm - pred.torque_Nm) / se_torque) < 0.05
    assert np.max(np.abs(red.drum_temp_C - pred.drum_temp_C) / se_temp) < 0.05


def test_raw_rate_noise_and_per_row_standard_errors():
    raw = _log((), noise_torque_Nm=4.0, noise_torque_rel=0.01, noise_temp_C=0.8)
    red = reduce_measurements(raw)
    nq, nt = red.reduction.noise_torque, red.reduction.noise_temp
    assert nt.sigma == pytest.approx(0.8, rel=0.03) and nq.absolute == pytest.approx(4.0, rel=0.15)
    assert nq.relative == pytest.approx(0.01, rel=0.15)
    # rows carry σ(level)/√n; the noise checks of the fits see the raw-rate noise, not the window scatter
    assert np.allclose(red.torque_sigma_Nm, sample_sigma(nq, red, red.torque_Nm))
    assert red.count[0] == 1 and red.time_s[0] == 0.0 and red.count.sum() == len(raw)
    assert np.median(red.count) == red.reduction.window_s * 10 == 100.0    # 10 s windows of a 10 min test
    assert noise_estimate(red, red.torque_Nm, 1000.0, relative=True) is nq
    fit = calibrate(red, ["lining_creep"])
    assert 0.8 < fit.variance_factor["torque"] < 1.25 and 0.8 < fit.variance_factor["temperature"] < 1.25


def test_sparse_log_is_not_reduced():
    d = synth([], seed=1, dt_s=10.0)
    out = reduce_measurements(d)
    assert not out.reduction.reduced and len(out) == len(d) and out.count is None
    assert out.rows_info() == {"rows_read": len(d), "rows_kept": len(d), "rows": len(d), "window_s": None,
                               "notes": []}


@pytest.mark.parametrize("duration_s, reduced", [(2.0, False), (4.0, False), (6.0, True), (12.0, True)])
def test_a_dense_log_of_short_tests_keeps_its_samples_where_windows_would_leave_too_few(duration_s, reduced):
    """100 Hz: 1-s windows leave a 2-s test 3 rows (fewer than a drum calibration frees) and a 4-s test 5: their
    samples are kept; a 6-s test keeps 6–8 windows, a 12-s test 12–14 (the t = 0 sample and one per second)."""
    d = synth([], seed=3, dt_s=0.01, duration_s=duration_s, hand_forces_N=(250.0, 320.0))
    out = reduce_measurements(d)
    assert out.reduction.reduced == reduced
    n = int(duration_s)
    assert len(out) == len(d) if not reduced else 4 * n <= len(out) <= 4 * (n + 2)      # 4 tests


def _batches(data, cuts):
    ids = list(dict.fromkeys(data.test_id.tolist()))
    dirs = ["downhill", "uphill"]
    codes = np.array([ids.index(t) for t in data.test_id])
    dcodes = np.array([dirs.index(d) for d in data.direction])
    edges = [0, *sorted(set(cuts)), len(data)]
    for a, b in zip(edges[:-1], edges[1:]):
        if b > a:
            yield Batch("log.csv", a + 2, "line", Text(codes[a:b], ids), Text(dcodes[a:b], dirs),
                        data.hand_force_N[a:b], data.time_s[a:b], data.drum_temp_C[a:b], data.torque_Nm[a:b], None, {})


_SMALL = synth([], seed=2, dt_s=0.5, duration_s=300.0, hand_forces_N=(250.0,))


@settings(max_examples=15, deadline=None)
@given(st.lists(st.integers(1, len(_SMALL) - 1), max_size=6))
def test_batch_boundaries_do_not_change_the_reduction(cuts):
    whole = Reducer()
    for b in _batches(_SMALL, []):
        whole.add(b)
    cut = Reducer()
    for b in _batches(_SMALL, cuts):
        cut.add(b)
    a, b = whole.finish("log.csv", window_s=10.0), cut.finish("log.csv", window_s=10.0)
    for name in ("time_s", "drum_temp_C", "torque_Nm", "count", "torque_sigma_Nm", "temp_sigma_C"):
        assert np.allclose(getattr(a, name), getattr(b, name), rtol=1e-12, atol=1e-9), name


def test_subset_keeps_counts_and_the_reduction():
    red = reduce_measurements(_log(()))
    part = red.subset(red.test_index == 1)
    assert part.reduction is red.reduction and np.array_equal(part.count, red.count[red.test_index == 1])
    assert part.test_info()[0]["samples"] == 6001 and len(part) < 300


def _with(data, rows, value, column="drum_temp_C"):
    out = data.subset(np.ones(len(data), bool))
    x = getattr(out, column).copy()
    x[rows] = value
    setattr(out, column, x)
    return out


def test_an_isolated_sample_out_of_range_in_a_dense_log_is_a_spike_dropped_with_a_note(tmp_path):
    """A thermocouple dropout of one sample in a 10 Hz log: dropped, said, and the reduction the clean log's."""
    from rollaway.bench.measurements import load_measurements
    clean = _log((), duration_s=1200.0)                     # 48 000 rows
    spiked = _with(clean, [20_000], -270.0)
    path = tmp_path / "spiked.csv"
    spiked.to_csv(path)
    red = load_measurements(str(path), window_s=None)
    assert red.reduction.reduced and red.reduction.rows_kept == len(clean) - 1
    assert any("1 isolated sample outside the physical range dropped" in n and "line 20002" in n
               and "drum_temp_C" in n for n in red.notes), red.notes
    ref = reduce_measurements(clean)
    assert len(red) == len(ref) and np.max(np.abs(red.drum_temp_C - ref.drum_temp_C)) < 0.05


@pytest.mark.parametrize("rows", [[20_000, 20_001, 20_002], [0], list(range(100, 48_000, 400))])
def test_out_of_range_values_that_are_no_isolated_spike_stay_an_error(tmp_path, rows):
    """A run of samples, the first row, or many scattered ones: a unit or wiring fault, named with its line."""
    from rollaway.bench.measurements import load_measurements
    from rollaway.errors import UserError
    path = tmp_path / "bad.csv"
    _with(_log((), duration_s=1200.0), rows, -270.0).to_csv(path)
    with pytest.raises(UserError, match=rf"line {rows[0] + 2}, column 'drum_temp_C'.*outside \[-60, 1000\]"):
        load_measurements(str(path), window_s=None)


def test_one_value_out_of_range_in_a_short_log_is_still_an_error(tmp_path):
    from rollaway.bench.measurements import load_measurements
    from rollaway.errors import UserError
    path = tmp_path / "short.csv"
    _with(synth([], seed=2, dt_s=300.0, duration_s=3600.0), [5], 5000.0).to_csv(path)
    with pytest.raises(UserError, match=r"line 7, column 'drum_temp_C': 5000 °C is outside"):
        load_measurements(str(path))
