"""The Python API (``import rollaway``): each function against the module it calls, and the whole path."""
import subprocess
import sys

import numpy as np
import pytest

import rollaway
from rollaway.errors import UserError
from rollaway.hold import analytic_verdict

from tests.conftest import ROOT

BENCH = ROOT / "examples" / "identify" / "bench-hidden-effect.csv"
FMVSS = dict(grade_pct=20.0, hand_force_N=400.0, direction="downhill", occupants=5)


def test_import_rollaway_loads_no_api_and_no_numpy():
    code = "import sys, rollaway; print(sorted(m for m in ('rollaway.api', 'numpy') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_hold_is_the_analytic_verdict_at_the_given_temperature():
    v = rollaway.hold("paper", **FMVSS, duration_s=3600, initial_drum_temp_C=250)
    ref = analytic_verdict(rollaway.DrumModel("paper"), **FMVSS, duration_s=3600, initial_temp_C=250)
    assert v.brake_margin_min == ref.brake_margin_min and v.least_hand_force_N == ref.least_hand_force_N
    assert v.rollaway_probability is None


def test_hold_slip_time_is_seconds_or_none():
    weak = rollaway.hold("paper", grade_pct=20, hand_force_N=200, direction="uphill", occupants=1,
                         duration_s=3600)
    assert not weak.holds and 0 < weak.slip_time_s < 3600 and weak.outcome == "brake_slip"
    strong = rollaway.hold("paper", **FMVSS)
    assert strong.holds and strong.slip_time_s is None


def test_hold_package_is_still_importable_and_callable():
    from rollaway import hold
    assert hold.required_torque is not None
    assert hold("paper", **FMVSS).holds == rollaway.hold("paper", **FMVSS).holds


def test_drum_model_from_a_file_keeps_effects_and_covariance_and_adds_more(tmp_path):
    from rollaway.model.drum_model import Covariance
    from rollaway.model.model_file import save_model
    m = rollaway.DrumModel("paper", effects=["lining_creep"], values={"lining_creep.relaxed_fraction": 0.1},
                           covariance=Covariance(("mu_drum",), np.array([[1e-4]])))
    path = save_model(m, tmp_path / "m.toml")
    back = rollaway.DrumModel(path, effects=["friction_temperature"])
    assert [e.name for e in back.effects] == ["lining_creep", "friction_temperature"]
    assert back.values["lining_creep.relaxed_fraction"] == 0.1
    assert back.covariance.names == ("mu_drum",)
    assert rollaway.DrumModel(path, values={"lining_creep.relaxed_fraction": 0.2}).values[
        "lining_creep.relaxed_fraction"] == 0.2


def test_build_scenario_from_keys_a_file_or_both():
    from rollaway.api import build_scenario
    s = build_scenario(**FMVSS, duration_s=60)
    assert (s.name, s.grade_pct, s.occupants, s.model.params.name) == ("python", 20.0, 5, "paper")
    f = build_scenario(ROOT / "scenarios" / "hot-parking-rollaway.toml", grade_pct=5.0)
    assert f.grade_pct == 5.0 and f.name != "python"
    weak = rollaway.DrumModel("paper").replace_params(mu_drum=0.2)
    assert build_scenario(**FMVSS, duration_s=60, model=weak).model.params.mu_drum == 0.2
    with pytest.raises(UserError, match="missing key 'hand_force_N'"):
        build_scenario(grade_pct=20, direction="uphill", occupants=1, duration_s=60)


def test_simulate_from_keys():
    r = rollaway.simulate(**FMVSS, duration_s=30)
    assert r.outcome == "held" and r.rollaway_time_s is None


def test_check_analytic_passes_the_paper_set_and_fails_a_weak_brake():
    res = rollaway.check(["fmvss135"], analytic=True)
    assert res.passed and len(res.table()) == 2
    weak = rollaway.check(["fmvss135"], model=rollaway.DrumModel("paper").replace_params(mu_drum=0.1), analytic=True)
    assert not weak.passed and weak.failed == [0, 1]


def test_load_measurements_refuses_a_mapping_the_loader_does_not_take():
    with pytest.raises(UserError, match="takes no"):
        rollaway.load_measurements(BENCH, not_a_column="x")


def test_load_measurements_reduces_a_dense_log_as_the_command_line_does(tmp_path):
    """The same file gives the same rows in Python as through ``rollaway diagnose``: a 100 Hz log of 12-s tests is
    reduced to 1-s window means by default; ``window_s=0`` keeps every sample."""
    from rollaway.cli.identify_common import load_data
    from rollaway.identify.synth import synth
    path = tmp_path / "dense.csv"
    synth([], seed=4, dt_s=0.01, duration_s=12.0, hand_forces_N=(250.0, 320.0)).to_csv(path)
    data = rollaway.load_measurements(path)
    cli = load_data(path, None, None, None)
    assert data.reduction.window_s == 1.0 and len(data) == len(cli) < 4 * 1201 / 50
    np.testing.assert_allclose(data.torque_Nm, cli.torque_Nm)
    assert len(rollaway.load_measurements(path, window_s=0)) == 4 * 1201


def test_sweep_is_callable_and_writes_its_table(tmp_path):
    from rollaway.api import build_scenario
    from rollaway.sweep import grid_spec
    spec = grid_spec(build_scenario(**FMVSS, duration_s=300), {"grade_pct": [10, 40]}, simulate="none")
    res = rollaway.sweep(spec, tmp_path / "out", plots=False)
    assert list(res.table["verdict"]) == ["hold", "roll"]


def test_bench_data_to_calibrated_model_to_risk_on_held_out_tests(tmp_path):
    data = rollaway.load_measurements(BENCH)
    train = data.subset(np.isin(data.test_id, data.tests[:6]))
    held_out = data.subset(~np.isin(data.test_id, data.tests[:6]))
    d = rollaway.diagnose(train)
    assert d.verdict == "lining_creep"
    path = d.save_model(tmp_path / "cal.toml")
    model = rollaway.DrumModel(path)
    assert [e.name for e in model.effects] == ["lining_creep"] and model.covariance is not None
    # the calibrated model predicts the held-out tests' torque better than the paper model
    def rmse(m):
        s = m.evaluate(held_out.time_s, held_out.hand_force_N, held_out.sign, initial_temp_C=held_out.initial_temp_C)
        return float(np.sqrt(np.mean((s.torque_Nm - held_out.torque_Nm) ** 2)))
    assert rmse(model) < rmse(rollaway.DrumModel("paper"))
    v = rollaway.hold(model, grade_pct=30, hand_force_N=250, direction="downhill", occupants=5, duration_s=3600,
                      uncertainty=200)
    assert 0.0 <= v.rollaway_probability <= 1.0 and v.risk.draws == 200
    d.report(tmp_path / "r.html")
    assert (tmp_path / "r.html").stat().st_size > 1000


def test_fit_ladder_saves_its_last_rung(tmp_path):
    ladder = rollaway.fit(BENCH, ["lining_creep"])
    assert ladder.final.rmse_torque_Nm < ladder.baseline.rmse_torque_Nm
    model = rollaway.DrumModel(ladder.save_model(tmp_path / "f.toml"))
    assert model.provenance["data_file"] == BENCH.name
