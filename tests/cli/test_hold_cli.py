import json

import pytest


def test_hold_rolls_away_when_drum_cools(run_cli):
    code, out, _ = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 200, "--direction", "uphill")
    assert code == 1 and "ROLLS AWAY" in out and "brake slips at t = 292 s" in out


def test_hold_json_margin_series(run_cli):
    code, out, _ = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 400, "--direction", "uphill",
                           "--occupants", 5, "--format", "json")
    doc = json.loads(out)
    assert code == 0 and doc["verdict"] == "held" and doc["slip_time_s"] is None
    assert len(doc["series"]["time_s"]) == 7 and min(doc["series"]["hold_margin"]) > 1
    assert abs(doc["brake_margin_min"] - min(doc["series"]["hold_margin"])) < 1e-9


def test_hold_json_carries_the_decision_when_the_tyres_slide(run_cli):
    code, out, _ = run_cli("hold", "--grade-pct", 30, "--hand-force-N", 445, "--direction", "downhill",
                           "--occupants", 1, "--format", "json")
    doc = json.loads(out)
    assert code == 1 and doc["verdict"] == "tyre_skid" and doc["least_hand_force_N"] is None
    assert doc["tyre_margin"] < 1 < doc["brake_margin_min"]


def test_hold_self_locking_is_not_a_hold(run_cli):
    code, _, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--mu", 1.2)
    assert code == 2 and "self-locks" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("args, needle", [
    (["--grade-pct", "120", "--hand-force-N", "300"], "grade 120 % is outside"),
    (["--grade-pct", "-100", "--hand-force-N", "300"], "grade -100 % is outside"),
    (["--grade-pct", "twenty", "--hand-force-N", "300"], "--grade-pct"),
    (["--grade-pct", "20", "--hand-force-N", "-3"], "hand force -3 N is negative"),
    (["--grade-pct", "20", "--hand-force-N", "300", "--occupants", "9"], "occupants = 9"),
    (["--grade-pct", "20", "--hand-force-N", "300", "--direction", "up"], "did you mean 'uphill'"),
    (["--grade-pct", "20", "--hand-force-N", "300", "--tyre-mu", "-0.1"], "tyre_road_mu"),
])
def test_hold_bad_input(run_cli, args, needle):
    code, _, err = run_cli("hold", *args)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("value", ["-5", "nan", "1e9"])
def test_bad_duration_blames_duration_flag(run_cli, value):
    code, _, err = run_cli("hold", "--grade-pct", "20", "--hand-force-N", "300", "--duration-s", value)
    assert code == 2 and err.startswith("rollaway hold: error: --duration-s") and "--t-end-s" not in err


def test_a_hold_the_band_doubts_is_said_to_be_unsure(run_cli, tmp_path):
    """A model calibrated on downhill tests only, asked facing uphill with --uncertainty: where its predictive band
    gives a roll-away a probability of 5 % or more, the verdict of the calibrated values says it is not sure (the exit
    code stays the calibrated values'); where the band agrees, the verdict is plain."""
    import numpy as np
    from rollaway.model.drum_model import Covariance, DrumModel
    from rollaway.model.model_file import save_model
    model = DrumModel("paper", covariance=Covariance(("mu_drum",), np.array([[0.01 ** 2]])),
                      predictive={"model_error_rel_sd": 0.0, "model_error_floor_rel_sd": 0.005, "model_error_dof": 5,
                                  "tested_hand_force_N": [200.0, 400.0], "tested_initial_temp_C": [150.0, 250.0],
                                  "tested_duration_s": 3600.0, "tested_directions": ["downhill"]})
    path = tmp_path / "down.toml"
    save_model(model, path)
    lines = {}
    for grade in (8, 24):
        code, out, _ = run_cli("hold", "--grade-pct", grade, "--hand-force-N", 300, "--direction", "uphill",
                               "--occupants", 1, "--duration-s", 3600, "--params", path, "--uncertainty", 400)
        lines[grade] = (code, out.strip().splitlines()[-1])
    code, last = lines[24]
    assert code == 0 and last.startswith("verdict: HOLDS at the calibrated values, NOT SURE: roll-away probability"), last
    code, last = lines[8]
    assert code == 0 and last.startswith("verdict: HOLDS — beyond the bench data: facing uphill was not tested"), last
