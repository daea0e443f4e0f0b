import json

import pytest


def test_check_analytic_defaults_pass(run_cli):
    code, out, err = run_cli("check", "--analytic")
    assert code == 0, err
    assert out.count("PASS") == 4 and "FAIL" not in out


def test_check_analytic_paper30_reports_tyre_skid(run_cli):
    code, out, _ = run_cli("check", "--analytic", "paper30", "--format", "json")
    rows = json.loads(out)
    down = next(r for r in rows if r["direction"] == "downhill")
    assert code == 1 and down["verdict"] == "FAIL" and "tyre" in down["reason"]


def test_check_analytic_weak_brake_fails(run_cli, tmp_path):
    f = tmp_path / "weak.toml"
    f.write_text('extends = "paper"\nmu_drum = 0.08\n')
    code, out, _ = run_cli("check", "--analytic", "--params", f)
    assert code == 1 and "FAIL" in out


@pytest.mark.parametrize("args, needle", [
    (["--analytic", "fmvs135"], "did you mean 'fmvss135'"),
    (["--analytic", "--params", "papr"], "did you mean 'paper'"),
])
def test_check_bad_input(run_cli, args, needle):
    code, _, err = run_cli("check", *args)
    assert code == 2 and needle in err and "Traceback" not in err


def test_params_lists_assumed(run_cli):
    code, out, _ = run_cli("params", "--format", "csv")
    assert code == 0
    mu = next(line for line in out.splitlines() if line.startswith("mu_drum,"))
    assert ",yes," in mu


def test_help_lists_commands(run_cli):
    code, out, _ = run_cli("--help")
    for c in ("brake", "check", "paper", "params"):
        assert c in out


def test_check_on_an_invalid_scenario_is_an_input_error(run_cli, tmp_path):
    bad = tmp_path / "selflock.toml"
    bad.write_text('name = "x"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 1\nhand_force_N = 400\n'
                   'duration_s = 300\nmu_drum = 1.5\n')
    code, out, err = run_cli("check", bad)
    assert code == 2 and "FAIL" not in out and str(bad) in err and err.count("\n") == 1


def test_check_on_a_folder_says_it_is_a_folder(run_cli, tmp_path):
    code, _, err = run_cli("check", tmp_path)
    assert code == 2 and "is a folder" in err
