import pytest

from rollaway.errors import UserError
from rollaway.model.parameters import SPECS, load_parameters, paper


def test_paper_set_marks_assumed_values():
    assumed = {s.name for s in SPECS if s.assumed}
    assert {"mu_drum", "heat_transfer_W_m2K", "cooled_area_m2", "shoe_arm_normal_m", "shoe_arm_friction_m"} <= assumed
    assert "drum_radius_m" not in assumed
    assert paper().cooling_time_constant_s == pytest.approx(1001.0, abs=1)


def test_toml_extends_and_overrides(tmp_path):
    f = tmp_path / "mine.toml"
    f.write_text('extends = "paper"\nmu_drum = 0.35\n')
    p = load_parameters(f)
    assert p.mu_drum == 0.35 and p.drum_radius_m == 0.09 and p.name == "mine"


@pytest.mark.parametrize("text, match", [
    ('extends = "paper"\nmu_drumm = 0.3\n', r"unknown parameter 'mu_drumm' \(did you mean 'mu_drum'\?\)"),
    ('mu_drum = 0.3\n', r"missing parameter 'ambient_temp_C'"),
    ('extends = "paper"\nmu_drum = "high"\n', r"'mu_drum' must be a number"),
    ('extends = "paper"\nmu_drum = -1\n', r"'mu_drum' = -1 is outside"),
    ('extends = "papr"\n', r"names no parameter set \(did you mean 'paper'\?\)"),
    ('extends = "paper"\nmu_drum = \n', r"not valid TOML"),
])
def test_bad_parameter_files(tmp_path, text, match):
    f = tmp_path / "bad.toml"
    f.write_text(text)
    with pytest.raises(UserError, match=match) as e:
        load_parameters(f)
    assert "bad.toml" in str(e.value)


def test_unknown_named_set():
    with pytest.raises(UserError, match="did you mean 'paper'"):
        load_parameters("papper")


def test_every_parameter_has_a_finite_documented_range():
    import math
    from pathlib import Path
    page = (Path(__file__).resolve().parents[2] / "docs" / "parameters.md").read_text(encoding="utf-8")
    for s in SPECS:
        assert math.isfinite(s.lower) and math.isfinite(s.upper) and s.lower <= s.value <= s.upper, s.name
        assert f"| `{s.name}` | {s.lower:g} … {s.upper:g} | {s.unit} |" in page, f"docs/parameters.md range of {s.name}"


@pytest.mark.parametrize("text, key", [
    ('extends = ["paper"]\n', "'extends'"),
    ('extends = { set = "paper" }\n', "'extends'"),
    ('extends = "paper"\nheat_transfer_W_m2K = 1e-9\n', "'heat_transfer_W_m2K'"),
    ('extends = "paper"\ncg_behind_front_m = 2.7\n', "'cg_behind_front_m'"),
    ('extends = "paper"\ngravity_m_s2 = 1e6\n', "'gravity_m_s2'"),
])
def test_bad_parameter_files_name_the_key(tmp_path, text, key):
    f = tmp_path / "p.toml"
    f.write_text(text)
    with pytest.raises(UserError) as e:
        load_parameters(f)
    assert str(f) in str(e.value) and key in str(e.value)


def test_utf8_bom_is_accepted(tmp_path):
    f = tmp_path / "bom.toml"
    f.write_bytes(b"\xef\xbb\xbfextends = \"paper\"\nmu_drum = 0.35\n")
    assert load_parameters(f).mu_drum == 0.35


def test_derived_geometry_is_checked_on_replace():
    with pytest.raises(UserError, match="cg_behind_front_m"):
        paper().replace(wheelbase_m=1.0)


def test_error_inside_a_referenced_file_names_the_referencing_file_and_key(tmp_path):
    from rollaway.hold.scenario import load_scenario
    (tmp_path / "p.toml").write_text('extends = "paper"\nmu_drum = 9\n')
    s = tmp_path / "s.toml"
    s.write_text('name = "x"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 1\nhand_force_N = 400\n'
                 'duration_s = 300\nparams = "p.toml"\n')
    with pytest.raises(UserError) as e:
        load_scenario(s)
    msg = str(e.value)
    assert msg.startswith(f"{s}, key 'params': ") and "p.toml" in msg and "'mu_drum'" in msg
