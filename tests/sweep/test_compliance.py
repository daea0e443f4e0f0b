"""`rollaway check` as the CI gate: MuJoCo simulation of the regulation scenarios."""
import json

import pytest

SCEN = ('name = "{name}"\ngrade_pct = {grade}\ndirection = "{direction}"\noccupants = 5\n'
        'hand_force_N = {force}\nduration_s = 60\n{extra}')


def scenario(tmp_path, name, grade=20, direction="uphill", force=400, extra=""):
    p = tmp_path / f"{name}.toml"
    p.write_text(SCEN.format(name=name, grade=grade, direction=direction, force=force, extra=extra))
    return p


def test_default_gate_simulates_both_regulations_and_passes(run_cli):
    code, out, err = run_cli("check")
    assert code == 0, out + err
    rows = [line for line in out.splitlines() if line.strip().startswith(("fmvss135-", "unr13h-"))]
    assert len(rows) == 4 and all("held" in r and "PASS" in r for r in rows)
    assert {"downhill", "uphill"} <= {r.split()[0].split("-")[1] for r in rows}
    assert "all 4 scenarios hold in the MuJoCo simulation" in out


def test_a_brake_too_weak_for_the_grade_fails_the_gate(run_cli, tmp_path):
    weak = tmp_path / "weak.toml"
    weak.write_text('extends = "paper"\nmu_drum = 0.15\n')      # worn lining: uphill margin 0.87
    code, out, _ = run_cli("check", "--params", weak, "--format", "json")
    rows = json.loads(out)
    assert code == 1
    up = [r for r in rows if r["direction"] == "uphill"]
    assert len(up) == 2 and all(r["verdict"] == "FAIL" and r["sim_outcome"] == "brake_slip" for r in up)
    assert all(r["verdict"] == "PASS" for r in rows if r["direction"] == "downhill")
    code, out, _ = run_cli("check", "--params", weak)
    assert code == 1 and "2 of 4 scenarios roll away" in out and sum(line.startswith("  FAIL ") for line in out.splitlines()) == 2


def test_scenario_files_weak_hand_force_and_tyre_skid(run_cli, tmp_path):
    ok = scenario(tmp_path, "ok")
    weak = scenario(tmp_path, "weak-hand", force=150)
    wet = scenario(tmp_path, "wet", direction="downhill", extra="tyre_road_mu = 0.3\n")
    code, out, _ = run_cli("check", ok)
    assert code == 0 and "PASS" in out
    code, out, _ = run_cli("check", ok, weak, wet, "--format", "csv")
    lines = out.strip().splitlines()
    assert code == 1 and len(lines) == 4
    by_name = {line.split(",")[1]: line for line in lines[1:]}
    assert ",held," in by_name["ok"] and ",PASS," in by_name["ok"]
    assert ",brake_slip," in by_name["weak-hand"] and ",FAIL," in by_name["weak-hand"]
    assert ",tyre_skid," in by_name["wet"] and "ignores tyres" in by_name["wet"]


@pytest.mark.parametrize("args, needle", [
    (["fmvs135"], "did you mean 'fmvss135'"),
    (["missing.toml"], "does not exist"),
    (["--params", "papr"], "did you mean 'paper'"),
])
def test_bad_targets_are_user_errors(run_cli, args, needle):
    code, _, err = run_cli("check", *args)
    assert code == 2 and needle in err and err.count("\n") == 1


def test_bad_scenario_file_names_the_key(run_cli, tmp_path):
    p = scenario(tmp_path, "bad", extra="hand_forse_N = 3\n")
    code, _, err = run_cli("check", p)
    assert code == 2 and "hand_forse_N" in err and "hand_force_N" in err


def test_an_analytic_pass_the_band_doubts_says_so_in_its_reason():
    """With --uncertainty, a preset case whose predictive band gives the other answer 5 % or more keeps the calibrated
    values' verdict and says in its reason that it is not sure: a model calibrated on downhill tests with μ_d = 0.3,
    facing uphill on paper30 (the friction coefficient drawn apart from μ_d); the sure rows keep their plain reason."""
    import dataclasses

    import numpy as np

    from rollaway.model.drum_model import Covariance, DrumModel
    from rollaway.sweep.compliance import analytic_rows
    model = DrumModel(dataclasses.replace(DrumModel("paper").params, mu_drum=0.3),
                      covariance=Covariance(("mu_drum",), np.array([[0.01 ** 2]])),
                      predictive={"model_error_rel_sd": 0.0, "model_error_floor_rel_sd": 0.005, "model_error_dof": 5,
                                  "tested_hand_force_N": [200.0, 400.0], "tested_initial_temp_C": [150.0, 250.0],
                                  "tested_duration_s": 3600.0, "tested_directions": ["downhill"]})
    c = analytic_rows(["paper30", "fmvss135"], model, 400)
    rows = {(p, d): (v, r, q) for p, d, v, r, q in zip(c["preset"], c["direction"], c["verdict"], c["reason"],
                                                       c["rollaway_probability"])}
    verdict, reason, prob = rows["paper30", "uphill"]
    assert verdict == "PASS" and prob >= 0.05 and reason == (
        f"holds at the calibrated values; NOT SURE: roll-away probability {prob:.2f} in the predictive band")
    assert rows["paper30", "downhill"][:2] == ("FAIL", "rear tyres skid (adhesion)")      # sure: the tyres slide
    assert rows["fmvss135", "downhill"][:2] == ("PASS", "holds")
