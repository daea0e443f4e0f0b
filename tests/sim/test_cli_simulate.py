import json
from pathlib import Path

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"


def test_simulate_prints_table_and_writes_json(run_cli, tmp_path):
    out = tmp_path / "r.json"
    code, stdout, stderr = run_cli("simulate", SCENARIOS / "fmvss135-uphill.toml", "--json", out)
    assert code == 0, stderr
    assert "outcome" in stdout and "held" in stdout
    d = json.loads(out.read_text())
    assert d["outcome"] == "held" and d["rollaway_time_s"] is None
    for key in ("max_displacement_m", "min_margin", "wall_time_s"):
        assert isinstance(d[key], float)


def test_simulate_rollaway_json(run_cli, tmp_path):
    out = tmp_path / "r.json"
    code, _, _ = run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--json", out, "--mode", "fixed")
    assert code == 0
    d = json.loads(out.read_text())
    assert d["outcome"] == "tyre_skid" and d["rollaway_time_s"] > 0 and d["mode"] == "fixed"


def _one_line_error(code, stdout, stderr, *words):
    assert code == 2
    assert "Traceback" not in stderr and len(stderr.strip().splitlines()) == 1
    for w in words:
        assert w in stderr


def test_bad_render_extension(run_cli, tmp_path):
    _one_line_error(*run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--render", tmp_path / "x.avi"), ".avi", ".mp4")


def test_outputs_into_missing_folders_are_created(run_cli, tmp_path):
    code, out, err = run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--render", tmp_path / "a" / "x.png",
                             "--json", tmp_path / "b" / "c" / "x.json")
    assert code == 0, err
    assert (tmp_path / "a" / "x.png").stat().st_size > 1000 and (tmp_path / "b" / "c" / "x.json").is_file()


def test_render_under_a_file(run_cli, tmp_path):
    (tmp_path / "f").write_text("")
    _one_line_error(*run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--render", tmp_path / "f" / "x.gif"),
                    "is a file, not a folder")


def test_json_under_a_file(run_cli, tmp_path):
    (tmp_path / "f").write_text("")
    _one_line_error(*run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--json", tmp_path / "f" / "x.json"),
                    "is a file, not a folder")


def test_missing_scenario_file(run_cli, tmp_path):
    _one_line_error(*run_cli("simulate", tmp_path / "nope.toml"), "nope.toml", "does not exist")


def test_unknown_key_in_scenario(run_cli, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text((SCENARIOS / "tyre-skid.toml").read_text() + "hand_forse_N = 3\n")
    _one_line_error(*run_cli("simulate", f), "hand_forse_N", "hand_force_N")


def test_bad_value_in_scenario(run_cli, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text((SCENARIOS / "tyre-skid.toml").read_text().replace("grade_pct = 20", "grade_pct = 250"))
    _one_line_error(*run_cli("simulate", f), "grade_pct")


def test_bad_mode(run_cli):
    _one_line_error(*run_cli("simulate", SCENARIOS / "tyre-skid.toml", "--mode", "turbo"), "turbo")


def test_self_locking_shoe_is_a_user_error(run_cli, tmp_path):
    f = tmp_path / "lock.toml"
    f.write_text((SCENARIOS / "tyre-skid.toml").read_text() + "mu_drum = 1.5\n")
    _one_line_error(*run_cli("simulate", f), "self-locks", "mu_drum")
