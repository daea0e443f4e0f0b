"""A model file's [covariance] as people edit it: a zero-variance row is a parameter held fixed (every command
works, its draws keep the value); anything that is not a covariance is one line naming the file and the entry."""
import json

import numpy as np
import pytest

from rollaway.errors import UserError
from rollaway.model.drum_model import load_model
from rollaway.uncertainty.draws import draw_values

NAMES = '["mu_drum", "heat_transfer_W_m2K", "u6_offset_m"]'
SCENARIO = 'name = "s"\ngrade_pct = 20\ndirection = "uphill"\noccupants = 5\nhand_force_N = 400\nduration_s = 60\n'


def _model(tmp_path, matrix: str, names: str = NAMES):
    path = tmp_path / "m.toml"
    path.write_text(f'extends = "paper"\nmu_drum = 0.38\n[covariance]\nnames = {names}\nmatrix = {matrix}\n',
                    encoding="utf-8")
    return path


def test_zero_variance_rows_are_parameters_held_fixed_in_every_command(tmp_path, run_cli):
    path = _model(tmp_path, "[[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1e-10]]")
    draws = draw_values(load_model(path), 200, seed=1)
    assert np.all(draws["mu_drum"] == 0.38) and np.all(draws["heat_transfer_W_m2K"] == draws["heat_transfer_W_m2K"][0])
    assert np.std(draws["u6_offset_m"]) > 0
    code, out, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path, "--uncertainty", 50,
                             "--format", "json")
    assert code in (0, 1) and json.loads(out)["uncertainty"]["draws"] == 50, err
    code, out, err = run_cli("params", path)
    assert code in (0, None) and "mu_drum" in out, err
    code, out, err = run_cli("check", "--analytic", "--params", path, "--uncertainty", 30, "--format", "json")
    assert code in (0, 1) and "Traceback" not in err, err
    scen = tmp_path / "s.toml"
    scen.write_text(SCENARIO, encoding="utf-8")
    code, out, err = run_cli("simulate", scen, "--params", path, "--uncertainty", 20, "--format", "json")
    assert code == 0 and "Traceback" not in err, err


@pytest.mark.parametrize("matrix, needle", [
    ("[[0.0, 1e-30, 0.0], [1e-30, 0.0, 0.0], [0.0, 0.0, 4.0]]", "covariance.matrix[0][1]' = 1e-30 but the variance"),
    ("[[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]", "covariance.matrix[0][0]' = -1 is a negative variance"),
    ("[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 4.0]]", "correlation of 'mu_drum' and 'heat_transfer_W_m2K' is 2"),
    ("[[1.0, 0.9, -0.9], [0.9, 1.0, 0.9], [-0.9, 0.9, 1.0]]", "not positive semi-definite (its correlations"),
    ("[[1.0, 0.0, 0.0], [0.0, nan, 0.0], [0.0, 0.0, 1.0]]", "covariance.matrix[1][1]' must be a finite number"),
    ("[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, inf]]", "covariance.matrix[2][2]' must be a finite number"),
    ("[[1e-320, 1e-200, 0.0], [1e-200, 1e-320, 0.0], [0.0, 0.0, 1.0]]", "covariance.matrix[0][1]"),
])
def test_what_is_not_a_covariance_is_one_line_naming_the_entry(tmp_path, run_cli, matrix, needle):
    path = _model(tmp_path, matrix)
    with pytest.raises(UserError) as exc:
        load_model(path)
    assert needle in str(exc.value) and str(path) in str(exc.value)
    code, _, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path, "--uncertainty", 20)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_conditional_is_the_gaussian_conditional_of_draws():
    """Covariance.conditional(given) is the covariance of the others with *given* held: checked against the
    regression residuals of a million draws (not against the Schur formula it uses)."""
    from rollaway.model.covariance import Covariance
    rng = np.random.default_rng(3)
    a = rng.normal(size=(4, 4))
    cov = Covariance(("a", "b", "c", "d"), a @ a.T + 0.1 * np.eye(4))
    cond = cov.conditional(("b", "d"))
    assert cond.names == ("a", "c")
    x = rng.multivariate_normal(np.zeros(4), cov.matrix, size=1_000_000)
    g, o = x[:, [1, 3]], x[:, [0, 2]]
    resid = o - g @ np.linalg.lstsq(g, o, rcond=None)[0]
    np.testing.assert_allclose(cond.matrix, np.cov(resid.T), rtol=0.02, atol=1e-3)
    assert cov.conditional(("zz",)) is cov
