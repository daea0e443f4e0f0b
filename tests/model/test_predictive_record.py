"""A model file's [predictive] table as people edit it: every bad value, and every bad alternative file, is one
line naming the model file and the key (an alternative's own error is prefixed by the key that names it)."""
import pytest

from rollaway.errors import UserError
from rollaway.model.drum_model import load_model

HEAD = ('extends = "paper"\nmu_drum = 0.38\n[covariance]\nnames = ["mu_drum"]\nmatrix = [[1e-4]]\n'
        '[predictive]\nmodel_error_rel_sd = 0.01\nmodel_error_dof = 5\n')
ALT_OK = 'extends = "paper"\nmu_drum = 0.37\n'


@pytest.mark.parametrize("extra, needle", [
    ("model_error_dof = 5.5\n", "'predictive.model_error_dof' must be a whole number"),
    ("model_error_tests = \"x\"\n", "'predictive.model_error_tests' must be a whole number"),
    ("tested_initial_temp_C = [20.0, inf]\n", "'predictive.tested_initial_temp_C' must be [lowest, highest]"),
    ("tested_hand_force_N = [350.0, 190.0]\n", "'predictive.tested_hand_force_N' must be [lowest, highest]"),
    ("tested_directions = \"downhill\"\n", "'predictive.tested_directions'"),
    ("alternatives = \"alt.toml\"\n", "'predictive.alternatives' must be a list"),
    ("alternatives = [{ weight = 0.3, file = \"alt.toml\", note = 1 }]\n", "'predictive.alternatives[0]' must be"),
    ("alternatives = [{ weight = 0.3, file = \"gone.toml\" }]\n", "'predictive.alternatives[0].file'"),
    ("alternatives = [{ weight = 0.3, file = \"m.toml\" }]\n", "names this model file itself"),
    ("alternatives = [{ weight = 0.2, file = \"alt.toml\" }, { weight = 0.2, file = \"alt.toml\" }]\n",
     "'predictive.alternatives[1].file' names 'alt.toml' again"),
    ("alternatives = [{ weight = 0.3, file = \"broken.toml\" }]\n",
     "key 'predictive.alternatives[0].file': "),
    ("alternatives = [{ weight = 0.3, file = \"badcov.toml\" }]\n",
     "key 'predictive.alternatives[0].file': "),
    ("alternatives = [{ weight = 0.3, file = \"nested.toml\" }]\n", "has alternatives of its own"),
])
def test_bad_predictive_values_are_one_line_naming_file_and_key(tmp_path, run_cli, extra, needle):
    text = HEAD.replace("model_error_dof = 5\n", "") if extra.startswith("model_error_dof") else HEAD
    (tmp_path / "alt.toml").write_text(ALT_OK, encoding="utf-8")
    (tmp_path / "broken.toml").write_text("extends = [\n", encoding="utf-8")
    (tmp_path / "badcov.toml").write_text(ALT_OK + '[covariance]\nnames = ["mu_drum"]\nmatrix = [[-1.0]]\n')
    (tmp_path / "nested.toml").write_text(HEAD + 'alternatives = [{ weight = 0.3, file = "alt.toml" }]\n')
    path = tmp_path / "m.toml"
    path.write_text(text + extra, encoding="utf-8")
    with pytest.raises(UserError) as exc:
        load_model(path)
    assert needle in str(exc.value) and str(path) in str(exc.value)
    for args in (["params", path], ["hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path,
                                     "--uncertainty", 20]):
        code, _, err = run_cli(*args)
        assert code == 2 and needle in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_a_model_with_a_valid_alternative_is_accepted(tmp_path, run_cli):
    (tmp_path / "alt.toml").write_text(ALT_OK, encoding="utf-8")
    path = tmp_path / "m.toml"
    path.write_text(HEAD + 'alternatives = [{ weight = 0.3, file = "alt.toml" }]\n', encoding="utf-8")
    m = load_model(path)
    assert [round(w, 3) for w, _ in m.alternatives] == [0.3]
    code, out, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path, "--uncertainty", 40)
    assert code in (0, 1) and "roll-away probability" in out, err
