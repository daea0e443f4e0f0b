"""Too few samples to judge a fit are refused with what to change (rollaway.identify.enough)."""
import numpy as np
import pytest

from rollaway.errors import UserError
from rollaway.identify.enough import SPARE, require
from tests.identify.bench_generator import generate


def _one_short_test(tmp_path, seconds=0.48):
    """One downhill test at 100 Hz lasting *seconds*, written as a canonical CSV (``--window-s 1`` reduces it to two
    rows; the automatic reduction keeps its samples)."""
    data = generate(["friction_linear"], sampling="100Hz", seed=5, n_forces=1, directions=("downhill",),
                    duration_s=seconds, forces=[300.0])
    path = tmp_path / "short.csv"
    data.to_csv(path)
    return path


def test_require_passes_with_the_spare_samples_and_refuses_one_fewer():
    data = generate([], sampling="15min", seed=1, n_forces=2, directions=("downhill",))      # 2 tests × 5 samples
    require(data, len(data) - SPARE, "calibrate the drum")
    with pytest.raises(UserError, match=r"10 samples in 2 tests are too few to calibrate the drum \(9 parameters"):
        require(data, len(data) - SPARE + 1, "calibrate the drum")


def test_diagnose_of_one_half_second_test_is_a_one_line_error_naming_the_file_and_the_fix(tmp_path, run_cli):
    path = _one_short_test(tmp_path)
    code, out, err = run_cli("diagnose", path, "--window-s", "1")
    assert code == 2 and "Traceback" not in err and out == ""
    line = [ln for ln in err.splitlines() if not ln.startswith("note:")]
    assert len(line) == 1 and "short.csv" in line[0] and "too few to calibrate the drum" in line[0]
    assert "--window-s" in line[0]                            # the log was reduced: shorter windows keep more rows


def test_every_sample_of_the_same_test_is_enough_to_diagnose(tmp_path, run_cli):
    for window in (("--window-s", "0"), ()):                 # every sample; the automatic reduction keeps them
        code, out, _ = run_cli("diagnose", _one_short_test(tmp_path), *window)
        assert code == 0 and out.startswith("verdict:")


def test_a_fit_ladder_never_judges_an_effect_on_samples_it_interpolates(tmp_path):
    """Two window means and a friction law: the fit would pass through both (torque RMSE 1e-7 N·m) and BIC would
    call it very strong evidence."""
    from rollaway.bench import load_measurements
    from rollaway.identify.ladder import fit
    data = load_measurements(_one_short_test(tmp_path), 1.0)          # 1-s windows
    assert len(data) < 4
    with pytest.raises(UserError, match="too few to calibrate the paper model"):
        fit(data, ["friction_temperature"])
    longer = generate(["friction_linear"], sampling="15min", seed=2, n_forces=1, directions=("downhill",))
    assert len(longer) == 5                                  # T_0, μ_d, h and the slope: 4 + SPARE > 5
    with pytest.raises(UserError, match="too few to judge friction_temperature"):
        fit(longer, ["friction_temperature"])
    assert np.isfinite(fit(longer, []).final.bic)


def test_a_fit_with_more_globals_than_residuals_is_a_user_error_not_a_minpack_traceback(tmp_path):
    from rollaway.bench.measurements import load_measurements
    from rollaway.identify.calibrate import calibrate
    from rollaway.identify.model import DrumPlan
    from rollaway.model.drum_parameters import BASELINE_FREE
    from rollaway.model.parameters import paper
    data = load_measurements(_one_short_test(tmp_path), 1.0)                       # 2 rows: 4 residuals
    with pytest.raises(UserError, match="too few to fit the drum"):
        calibrate(data, (), DrumPlan(paper(), tuple(BASELINE_FREE)))              # 6 globals
