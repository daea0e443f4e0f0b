"""Model files: round trip, validation like any parameter file, accepted by every command."""
import json

import numpy as np
import pytest

from rollaway.errors import UserError
from rollaway.model.drum_model import Covariance, DrumModel
from rollaway.model.drum_model import load_model
from rollaway.model.model_file import model_to_toml, save_model

T = np.linspace(0, 3600, 13)


def creep_model():
    m = DrumModel("paper", ["lining_creep"], {"lining_creep.relaxed_fraction": 0.15,
                                              "lining_creep.relaxation_time_s": 900.0}).replace_params(mu_drum=0.38)
    m.covariance = Covariance(("mu_drum", "lining_creep.relaxed_fraction"), np.array([[1e-4, 2e-6], [2e-6, 9e-6]]))
    m.provenance = {"data_file": "bench.csv", "rows": 104, "rmse_torque_Nm": 8.1}
    return m


def test_round_trip_keeps_values_covariance_provenance_and_torque(tmp_path):
    m = creep_model()
    path = save_model(m, tmp_path / "sub" / "m.toml", comment="test")
    back = load_model(path)
    assert back.values == m.values and back.params == m.params.__class__(**m.params.as_dict(), name="m")
    np.testing.assert_array_equal(back.covariance.matrix, m.covariance.matrix)
    assert back.covariance.names == m.covariance.names and back.provenance == m.provenance
    assert np.array_equal(back.evaluate(T, 300.0).torque_Nm, m.evaluate(T, 300.0).torque_Nm)
    assert model_to_toml(back) == model_to_toml(m)   # stable: writing it again gives the same file


@pytest.mark.parametrize("text, needle", [
    ('extends = "paper"\n[effects.lining_crep]\nrelaxed_fraction = 0.1\n', "did you mean 'lining_creep'"),
    ('extends = "paper"\n[effects.lining_creep]\nrelaxed = 0.1\n', "unknown key 'effects.lining_creep.relaxed'"),
    ('extends = "paper"\n[effects.lining_creep]\nrelaxed_fraction = 5\n', "outside [0, 0.6]"),
    ('extends = "paper"\n[effects.lining_creep]\nrelaxed_fraction = "a"\n', "must be a finite number"),
    ('extends = "paper"\n[effect.lining_creep]\nrelaxed_fraction = 0.1\n', "key 'effect' is a table"),
    ('extends = "paper"\n[covariance]\nnames = ["mu_drum"]\nmatrix = [[1, 2]]\n', "1×1 list of rows"),
    ('extends = "paper"\n[covariance]\nnames = ["mu_drum", "h"]\nmatrix = [[1, 0], [0, 1]]\n', "names 'h'"),
    ('extends = "paper"\n[covariance]\nnames = ["mu_drum", "heat_transfer_W_m2K"]\nmatrix = [[1, 2], [0, 1]]\n',
     "not symmetric"),
    ('extends = "paper"\n[covariance]\nnames = ["mu_drum", "heat_transfer_W_m2K"]\nmatrix = [[1, 2], [2, 1]]\n',
     "not positive semi-definite"),
    ('extends = "paper"\n[covariance]\nnames = ["mu_drum"]\nmatrix = [[1]]\nscale = 2\n', "covariance.scale"),
    ('extends = "paper"\nmu_drum = 0.4\n[provenance]\nrows = [1, 2]\n', "provenance.rows"),
    ('extends = "paper"\n[effects.x]\nplugin = "nowhere.py"\n', "effects.x.plugin"),
])
def test_bad_model_files_are_one_line_errors_naming_file_and_key(tmp_path, run_cli, text, needle):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(UserError, match=None) as exc:
        load_model(path)
    assert needle in str(exc.value) and str(path) in str(exc.value)
    code, _, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


@pytest.fixture
def model_file(tmp_path):
    return save_model(creep_model(), tmp_path / "creep.toml")


def test_every_command_accepts_a_model_file(run_cli, model_file, tmp_path):
    code, out, _ = run_cli("brake", "--hand-force-N", 300, "--params", model_file, "--format", "json")
    rows = json.loads(out)
    ref = creep_model().evaluate(np.array([r["time_s"] for r in rows]), 300.0).torque_Nm
    assert code == 0 and np.allclose([r["torque_Nm"] for r in rows], ref, rtol=1e-12)
    code, out, _ = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", model_file, "--format", "json")
    assert code in (0, 1) and json.loads(out)["effects"] == ["lining_creep"]
    code, out, _ = run_cli("check", "--analytic", "--params", model_file, "--format", "json")
    assert code in (0, 1) and len(json.loads(out)) == 4
    code, out, _ = run_cli("params", model_file, "--format", "json")
    assert code in (0, None) and any(r["name"] == "lining_creep.relaxed_fraction" for r in json.loads(out))
    scen = tmp_path / "s.toml"
    scen.write_text(f'name = "s"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\n'
                    f'duration_s = 60\nparams = "{model_file.name}"\n', encoding="utf-8")
    code, out, _ = run_cli("simulate", scen, "--format", "json")
    assert code == 0 and json.loads(out)["outcome"] == "held"
    code, out, _ = run_cli("check", scen, "--format", "json")          # the scenario names the model file
    assert code == 0
    code, _, err = run_cli("check", scen, "--params", model_file)       # --params is the presets' model only
    assert code == 2 and "--params sets the drum model of the regulation presets" in err
    code, _, _ = run_cli("paper", "--params", model_file, "--out", tmp_path / "figs")
    assert code in (0, None) and len(list((tmp_path / "figs").glob("*.png"))) >= 6


def test_chart_draws_both_models_and_refuses_bad_input(run_cli, model_file, tmp_path):
    code, out, _ = run_cli("chart", "--params", "paper", "--params", model_file, "--out", tmp_path / "c.png")
    assert code in (0, None) and (tmp_path / "c.png").stat().st_size > 10_000
    code, _, err = run_cli("chart", "--occupants", 9, "--out", tmp_path / "d.png")
    assert code == 2 and "occupants" in err


def test_least_force_curves_of_a_model_with_clamp_loss_lie_above_the_paper_model(model_file):
    from rollaway.figures.design import least_force_curves
    curves = least_force_curves({"paper": DrumModel("paper"), "creep": load_model(model_file)}, occupants=5,
                                duration_s=3600.0, initial_temp_C=200.0)
    ok = np.isfinite(curves[("paper", "uphill")])
    assert np.all(curves[("creep", "uphill")][ok] > curves[("paper", "uphill")][ok])


def test_calibration_table_is_validated(tmp_path):
    import pytest
    from rollaway.errors import UserError
    from rollaway.model.drum_model import DrumModel
    good = tmp_path / "good.toml"
    good.write_text('extends = "paper"\n[calibration]\nmu_drum = "fitted: 0.38 ± 0.01"\n', encoding="utf-8")
    assert DrumModel(good).calibration == {"mu_drum": "fitted: 0.38 ± 0.01"}
    for body, words in (('mu_drm = "fitted"', "unknown key 'calibration.mu_drm'"),
                        ("mu_drum = 3", "must be text")):
        bad = tmp_path / "bad.toml"
        bad.write_text(f'extends = "paper"\n[calibration]\n{body}\n', encoding="utf-8")
        with pytest.raises(UserError, match=words):
            DrumModel(bad)


def test_a_model_with_a_plugin_effect_and_its_shape_free_form_names_the_plugin_and_loads_elsewhere(tmp_path):
    """A model fitted with an effect from a plugin file (diagnose --effect-file) is saved with ``plugin =`` that
    file, relative to the model file, so that it loads in another command; so is its shape-free form."""
    from rollaway.effects import get_effect, load_effect_file
    from rollaway.effects.shape_free import spline_effect
    from tests.corpus.plugin_cases import plug
    plugin = tmp_path / "fx" / "humid.py"
    plugin.parent.mkdir()
    plugin.write_text(plug(**{'name = "humidity"': 'name = "humidity_for_files"'}), encoding="utf-8")
    load_effect_file(plugin)
    shape = spline_effect(get_effect("humidity_for_files"), [20.0, 100.0, 300.0])
    for effects, values in ((["humidity_for_files"], {"humidity_for_files.a": 0.1}),
                            ([shape], {"humidity_for_files_shape.c0": 0.02, "humidity_for_files_shape.c1": -0.08})):
        m = DrumModel("paper", effects, values)
        path = save_model(m, tmp_path / "models" / "m.toml")
        assert 'plugin = "../fx/humid.py"' in path.read_text(encoding="utf-8")
        back = load_model(path)
        assert np.array_equal(back.evaluate(T, 300.0).torque_Nm, m.evaluate(T, 300.0).torque_Nm)
