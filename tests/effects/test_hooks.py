"""rollaway.effects.hooks.call_hook: an effect's hook called as untrusted code."""
import numpy as np
import pytest

from rollaway.effects.base import Effect, ModelState
from rollaway.effects.hooks import call_hook
from rollaway.errors import UserError
from rollaway.model.parameters import paper


def _state(n: int = 5) -> ModelState:
    t = np.linspace(0.0, 60.0, n)
    return ModelState(paper(), t, np.full(n, 300.0), np.ones(n), np.full(n, 150.0), np.full(n, 20.0), 10.0, 0.42)


def _effect(result):
    class Returns(Effect):
        name = "returns"

        def torque(self, state, torque_Nm, v):
            return result(torque_Nm)
    return Returns()


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_a_non_finite_value_from_finite_inputs_is_a_user_error(bad):
    def result(x):
        out = np.array(x, float)
        out[2] = bad
        return out
    with pytest.raises(UserError, match="returned NaN or inf"):
        call_hook(_effect(result), "torque", _state(), np.full(5, 100.0), {})


@pytest.mark.filterwarnings("ignore:overflow encountered")
def test_finite_values_whose_sum_overflows_pass():
    out = call_hook(_effect(lambda x: np.full(5, 1e308)), "torque", _state(), np.full(5, 100.0), {})
    assert np.all(out == 1e308)


def test_a_non_finite_value_where_the_input_was_one_is_not_the_hooks():
    x = np.array([1.0, np.nan, 3.0, 4.0, 5.0])
    out = call_hook(_effect(lambda q: 2.0 * q), "torque", _state(), x, {})
    assert np.isnan(out[1]) and out[0] == 2.0


def test_a_number_where_one_is_allowed_and_a_wrong_shape_refused():
    class Modulus(Effect):
        name = "modulus"

        def lining_modulus(self, state, modulus_Pa, v):
            return 0.5 * modulus_Pa
    assert call_hook(Modulus(), "lining_modulus", _state(), 2.0e9, {}, scalar_ok=True) == 1.0e9
    with pytest.raises(UserError, match="shape"):
        call_hook(_effect(lambda x: np.ones(3)), "torque", _state(), np.ones(5), {})


def test_a_hook_the_effect_does_not_override_passes_its_input_untouched():
    x = np.array([np.nan, 1.0])
    assert call_hook(_effect(lambda q: q), "friction", _state(2), x, {}) is x
