import pytest

from rollaway.errors import UserError
from rollaway.parameters import SPECS, load_parameters, paper


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
