"""The one drum chain: bit-identical baseline, neutral effects, untrusted hooks."""
import numpy as np
import pytest

from rollaway.effects import CATALOGUE
from rollaway.effects.base import Effect, EffectParameter
from rollaway.errors import UserError
from rollaway.model.drum_model import DrumModel
from rollaway.model.parameters import paper
from rollaway.physics import cooling, drum

T = np.linspace(0.0, 3600.0, 97)


def paper_chain(p, t, force, sign):
    """The paper's equations written out here, independently of rollaway.model."""
    tau = p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3 / (p.heat_transfer_W_m2K
                                                                                   * p.cooled_area_m2)
    temp = (p.initial_drum_temp_C - p.ambient_temp_C) * np.exp(-t / tau) + p.ambient_temp_C   # eq. (10)
    u6 = p.u6_slope_m_per_N * force + p.u6_offset_m                                            # eq. (24)
    k_d, k_l = p.drum_area_m2 * p.drum_modulus_Pa, p.lining_area_m2 * p.lining_modulus_Pa
    dT = temp - p.initial_drum_temp_C
    l_ol = p.lining_thickness_m
    f0 = k_d * (p.drum_expansion_per_K * dT + (u6 * k_l + k_l * p.lining_expansion_per_K * dT * l_ol
                                              - k_d * p.drum_expansion_per_K * dT * l_ol)
                / (k_l * p.drum_thickness_m + k_d * l_ol))                                     # eq. (16a)
    factor = p.shoe_arm_normal_m / (p.shoe_arm_normal_m - sign * p.mu_drum * p.shoe_arm_friction_m)
    return p.mu_drum * f0 * factor * p.drum_radius_m                                            # eq. (17b)


@pytest.mark.parametrize("direction, sign", [("downhill", 1.0), ("uphill", -1.0)])
def test_baseline_matches_the_paper_equations(direction, sign):
    got = DrumModel("paper").evaluate(T, 320.0, direction).torque_Nm
    np.testing.assert_allclose(got, paper_chain(paper(), T, 320.0, sign), rtol=1e-9)


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_neutral_effect_is_bit_identical_to_the_baseline(name):
    base = DrumModel("paper").evaluate(T, np.array([[200.0], [400.0]]), "uphill")
    with_neutral = DrumModel("paper", [name]).evaluate(T, np.array([[200.0], [400.0]]), "uphill")
    assert np.array_equal(base.torque_Nm, with_neutral.torque_Nm)
    assert np.array_equal(base.drum_temp_C, with_neutral.drum_temp_C)


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_every_effect_changes_the_torque_and_broadcasts(name):
    cls = CATALOGUE[name]
    values = {f"{name}.{k}": v for k, v in cls.typical_values().items()}
    m = DrumModel("paper", [name], values)
    s = m.evaluate(T, np.array([[200.0], [400.0]]), "downhill")
    assert s.torque_Nm.shape == (2, T.size) and np.all(np.isfinite(s.torque_Nm))
    assert not np.allclose(s.torque_Nm, DrumModel("paper").evaluate(T, np.array([[200.0], [400.0]])).torque_Nm)
    # element-wise: evaluating one point at a time gives the same numbers
    one = m.evaluate(T[7], 400.0, "downhill").torque_Nm
    assert float(one) == pytest.approx(s.torque_Nm[1, 7], rel=1e-12)


def _plugin(hook_body):
    class Bad(Effect):
        name = "bad_plugin"
        parameters = (EffectParameter("a", "–", neutral=0.0, lower=0.0, upper=1.0, initial=0.1),)

        def clamp_force(self, state, force_N, v):
            return hook_body(state, force_N, v)
    return Bad


@pytest.mark.parametrize("body, needle", [
    (lambda st, f, v: 1 / 0, "raised ZeroDivisionError"),
    (lambda st, f, v: f * np.nan, "NaN or inf"),
    (lambda st, f, v: np.ones(3), "returned shape"),
    (lambda st, f, v: "text", "not numbers"),
])
def test_a_bad_hook_is_a_one_line_user_error(body, needle):
    m = DrumModel("paper", [_plugin(body)], {"bad_plugin.a": 0.5})
    with pytest.raises(UserError, match=needle) as exc:
        m.evaluate(T, 300.0)
    assert "bad_plugin" in str(exc.value) and "\n" not in str(exc.value)


def test_unknown_effect_value_is_refused():
    with pytest.raises(UserError, match="unknown effect parameter 'lining_creep.fraction'"):
        DrumModel("paper", ["lining_creep"], {"lining_creep.fraction": 0.1})


def test_model_reads_parameters_through_and_changes_them():
    m = DrumModel("paper", ["lining_creep"], {"lining_creep.relaxed_fraction": 0.2})
    m2 = m.replace_params(mu_drum=0.35)
    assert m.mu_drum == 0.4 and m2.mu_drum == 0.35 and m2.values == m.values and m2.has_effects
    assert not DrumModel("paper", ["lining_creep"]).has_effects
