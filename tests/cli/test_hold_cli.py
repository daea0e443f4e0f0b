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
