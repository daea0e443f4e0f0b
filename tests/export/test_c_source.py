"""One truth, two implementations: the FMU's C chain against DrumModel.evaluate (the Python chain).

The baseline and every catalogue effect at non-neutral values, both directions, several hand forces,
start and ambient temperatures, over an hour: within 1e-6 relative (the C code repeats the Python
arithmetic step by step, so in practice the numbers agree to the last bit or so).
"""
import numpy as np
import pytest

from rollaway.effects import CATALOGUE
from rollaway.export import export_fmu
from rollaway.export.c_source import effect_hooks_in_c, has_c_effect
from rollaway.model.drum_model import DrumModel
from tests.export.fmu_runs import TIMES_S, assert_same, simulate

# a visible, realistic value of every parameter (the catalogue's 'typical'), curvature too
VALUES = {f"{n}.{k}": v for n, cls in CATALOGUE.items() for k, v in cls.typical_values().items()}
VALUES["nonlinear_lining_stiffness.stiffness_curvature"] = 0.3
CASES = [(False, 150.0, 80.0, None), (True, 150.0, 320.0, 5.0), (False, 400.0, 200.0, None),
         (True, 400.0, 80.0, None), (False, 900.0, 320.0, 40.0), (True, 900.0, 200.0, 5.0)]


def model_with(effects):
    return DrumModel("paper", effects=effects, values={k: v for k, v in VALUES.items() if k.split(".")[0] in effects})


def check(model, fmu, cases=CASES):
    for uphill, force, t0, amb in cases:
        r = simulate(fmu, hand_force_N=force, uphill=uphill, initial_drum_temp_C=t0, ambient_temp_C=amb)
        assert np.array_equal(r["time"], TIMES_S)
        s = model.evaluate(TIMES_S, force, "uphill" if uphill else "downhill", initial_temp_C=t0,
                           ambient_C=model.params.ambient_temp_C if amb is None else amb)
        assert_same(r, s)


def test_every_catalogue_effect_has_c_code_for_its_hooks():
    for name, cls in CATALOGUE.items():
        assert has_c_effect(name), name
        assert set(cls.overridden_hooks()) <= set(effect_hooks_in_c(name)), name


def test_the_paper_chain(export_dir):
    model = DrumModel("paper")
    check(model, export_fmu(model, export_dir / "paper.fmu"))


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_each_catalogue_effect(export_dir, name):
    model = model_with([name])
    assert [e.name for e, _ in model.active()] == [name]      # non-neutral: the effect is in the chain
    check(model, export_fmu(model, export_dir / f"{name}.fmu"))


@pytest.mark.parametrize("order", ["catalogue", "reversed"])
def test_all_effects_at_once_in_the_models_order(export_dir, order):
    names = list(CATALOGUE) if order == "catalogue" else list(CATALOGUE)[::-1]
    model = model_with(names)
    check(model, export_fmu(model, export_dir / f"all-{order}.fmu"), CASES[:3])


def test_the_comparison_sees_a_wrong_chain(export_dir):
    """The hooks' order matters (cable loss before or after the nonlinear stiffness): an FMU of one order
    does not pass as the other — the comparison above can fail."""
    a = model_with(["cable_relaxation", "nonlinear_lining_stiffness"])
    b = model_with(["nonlinear_lining_stiffness", "cable_relaxation"])
    fmu = export_fmu(a, export_dir / "order-a.fmu")
    r = simulate(fmu)
    assert_same(r, a.evaluate(TIMES_S, 400.0, "downhill"))
    with pytest.raises(AssertionError):
        assert_same(r, b.evaluate(TIMES_S, 400.0, "downhill"))


def test_other_brake_parameters_are_baked_in(export_dir):
    """A model file's own values (μ_d, h, eq. 24's fit, arms, gap) reach the C code."""
    model = model_with(["shoe_thermal_lag"]).replace_params(
        mu_drum=0.33, heat_transfer_W_m2K=25.0, u6_slope_m_per_N=4.2e-7, u6_offset_m=-1.1e-5, shoe_arm_friction_m=0.05,
        gap_m=5e-4, lining_modulus_Pa=3e8, drum_radius_m=0.11, ambient_temp_C=15.0, initial_drum_temp_C=150.0)
    fmu = export_fmu(model, export_dir / "custom.fmu")
    check(model, fmu, CASES[:2])
    r = simulate(fmu)            # the FMU's start values are the model's T_0 and ambient
    assert_same(r, model.evaluate(TIMES_S, 400.0, "downhill"))


def test_radiation_table_is_close_to_the_ode(export_dir):
    """Both implementations tabulate the radiation-convection ODE (1500-point log grid): against an accurate
    ODE solution the drum temperature is off by less than 1e-4 of T − T_amb (measured ≈ 1e-5 at 800 °C)."""
    from scipy.integrate import solve_ivp
    model = model_with(["radiation_cooling"])
    p = model.params
    cap = p.drum_density_kg_m3 * p.drum_specific_heat_J_kgK * p.drum_volume_m3
    eps, ta = VALUES["radiation_cooling.emissivity"], p.ambient_temp_C
    fmu = export_fmu(model, export_dir / "radiation-ode.fmu")
    for t0 in (120.0, 450.0, 800.0):
        def rhs(_, T):
            return [-(p.heat_transfer_W_m2K * p.cooled_area_m2 * (T[0] - ta) + eps * 5.670374419e-8 * p.cooled_area_m2
                      * ((T[0] + 273.15) ** 4 - (ta + 273.15) ** 4)) / cap]
        ode = solve_ivp(rhs, (0, 3600), [t0], t_eval=TIMES_S, method="DOP853", rtol=1e-12, atol=1e-12).y[0]
        got = simulate(fmu, initial_drum_temp_C=t0)["drum_temp_C"]
        assert np.max(np.abs(got - ode) / (ode - ta)) < 1e-4


def test_the_result_does_not_depend_on_the_communication_step(export_dir):
    fmu = export_fmu(model_with(["shoe_thermal_lag", "radiation_cooling"]), export_dir / "steps.fmu")
    fine = simulate(fmu, output_interval_s=1.0)
    coarse = simulate(fmu, output_interval_s=600.0)
    at = np.searchsorted(fine["time"], coarse["time"])
    np.testing.assert_allclose(fine["torque_Nm"][at], coarse["torque_Nm"], rtol=1e-12)


@pytest.mark.parametrize("seed", range(8))
def test_random_models_anywhere_in_the_bounds(export_dir, seed):
    """Random subsets of the catalogue in random order, every value drawn within its bounds (clips and
    floors of the effects included), with random brake parameters: the C chain still equals the Python one."""
    rng = np.random.default_rng(seed)
    names = list(rng.permutation(sorted(CATALOGUE))[:rng.integers(1, len(CATALOGUE) + 1)])
    values = {f"{n}.{p.name}": float(rng.uniform(p.lower, p.upper)) for n in names for p in CATALOGUE[n].parameters}
    model = DrumModel("paper", effects=names, values=values).replace_params(
        mu_drum=float(rng.uniform(0.25, 0.6)), heat_transfer_W_m2K=float(rng.uniform(15, 80)),
        u6_slope_m_per_N=float(rng.uniform(3e-7, 5e-7)), ambient_temp_C=float(rng.uniform(-10, 40)))
    fmu = export_fmu(model, export_dir / f"random-{seed}.fmu")
    cases = [(bool(rng.integers(2)), float(rng.uniform(50, 1200)), float(rng.uniform(60, 450)), None)
             for _ in range(3)]
    check(model, fmu, cases)
