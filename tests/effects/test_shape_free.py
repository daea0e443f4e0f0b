"""Shape-free forms: a spline factor on an effect's hook quantity, and their place in model files."""
import numpy as np
import pytest

from rollaway.effects import get_effect
from rollaway.effects.shape_free import (BEYOND_CENTRE, LEAST_FACTOR, from_model_file, is_shape_free, shape_hook,
                                         spline_effect, spline_factor)
from rollaway.errors import UserError
from rollaway.model.drum_model import DrumModel, load_model
from rollaway.model.model_file import model_to_toml, save_model

T = np.linspace(0, 3600, 37)
KNOTS = [0.0, 300.0, 900.0, 3600.0]


def test_spline_factor_is_one_at_the_first_knot_piecewise_linear_and_flat_beyond():
    f = spline_factor([0.0, 150.0, 300.0, 600.0, 3600.0, 9000.0], KNOTS, [-0.02, -0.03, -0.01])
    np.testing.assert_allclose(f, [1.0, 0.99, 0.98, 0.965, 0.94, 0.94])


def test_a_temperature_spline_goes_on_beyond_its_hottest_knot_by_a_held_share_of_its_last_slope():
    """Below its first knot and beyond its last a spline in time is flat; one in temperature goes on beyond its
    hottest knot with the held share ``beyond`` of its last slope (0: the law stops, 1: it goes on as the data
    last showed), never below LEAST_FACTOR; the fit never frees that share (no sample lies there)."""
    from rollaway.identify.model import BenchModel
    knots, coef = [20.0, 100.0, 180.0], [-0.1, -0.2]
    for beyond, at_260 in ((0.0, 0.7), (0.5, 0.6), (1.0, 0.5)):
        np.testing.assert_allclose(spline_factor([0.0, 180.0, 220.0, 260.0], knots, coef, beyond),
                                   [1.0, 0.7, 0.5 * (0.7 + at_260), at_260])
    assert spline_factor([1e4], knots, coef, 1.0)[0] == LEAST_FACTOR
    deep = [-0.9, -0.9]                                  # an absolute change's spline may fall below LEAST_FACTOR
    np.testing.assert_array_equal(spline_factor([50.0, 180.0, 300.0], knots, deep, 0.0),
                                  spline_factor([50.0, 180.0, 300.0], knots, deep))   # share 0: exactly flat
    friction = spline_effect(get_effect("friction_temperature"), knots)
    held = [p for p in friction.parameters if p.held]
    assert [p.name for p in held] == ["beyond"] and held[0].neutral == 0.0 and held[0].initial == BEYOND_CENTRE
    assert held[0].prior_sd > 0                          # fits: flat, as the data saw; the calibrated model: the centre
    assert not any(p.held for p in spline_effect(get_effect("lining_creep"), KNOTS).parameters)
    assert "friction_temperature_shape.beyond" not in BenchModel("paper", [friction]).parameter_names()
    fall = {"friction_temperature_shape.c0": -0.1, "friction_temperature_shape.c1": -0.2}
    torque = [float(DrumModel("paper", [friction], {**fall, "friction_temperature_shape.beyond": b})
                    .evaluate(np.array([0.0]), 250.0, initial_temp_C=260.0).torque_Nm[0]) for b in (0.0, 0.5, 1.0)]
    assert torque[0] > torque[1] > torque[2]            # a friction still falling at 180 °C: less torque from 260 °C
    cool = [float(DrumModel("paper", [friction], {**fall, "friction_temperature_shape.beyond": b})
                  .evaluate(np.array([0.0]), 250.0, initial_temp_C=150.0).torque_Nm[0]) for b in (0.0, 1.0)]
    assert cool[0] == cool[1]                            # within the knots the share changes nothing


def test_a_shape_free_creep_with_the_catalogue_law_at_its_knots_matches_it_there():
    creep = get_effect("lining_creep")
    cls = spline_effect(creep, KNOTS)
    assert is_shape_free(cls) and cls.name == "lining_creep_shape" and shape_hook(creep) == ("clamp_force", "time_s")
    loss = lambda t: 0.1 * (1 - np.exp(-np.asarray(t) / 900.0))                      # noqa: E731
    coef = -np.diff(loss(KNOTS))
    spline = DrumModel("paper", [cls], {f"lining_creep_shape.c{j}": c for j, c in enumerate(coef)})
    law = DrumModel("paper", ["lining_creep"], {"lining_creep.relaxed_fraction": 0.1,
                                                "lining_creep.relaxation_time_s": 900.0})
    a, b = (m.evaluate(np.array(KNOTS), 250.0, initial_temp_C=200.0).torque_Nm for m in (spline, law))
    np.testing.assert_allclose(a, b, rtol=1e-9)
    between = np.array([600.0, 2000.0])         # a chord of a concave loss lies below it: the spline loses less
    a, b = (m.evaluate(between, 250.0, initial_temp_C=200.0).torque_Nm for m in (spline, law))
    assert np.all(a > b)


def test_a_shape_free_cable_relaxation_loses_the_same_displacement_at_every_hand_force():
    """The cable's physics is a displacement lost (eq. 24's u_6 − δ(t)): its flexible form adds s·g(t) to u_6, so
    with the catalogue law at its knots it matches that law at every hand force — a factor on u_6 would lose
    a share of u_6, more at heavy forces (the lining creep's physics, not the cable's)."""
    cable = get_effect("cable_relaxation")
    cls = spline_effect(cable, KNOTS)
    assert cls.scale == cable.shape_scale > 0 and "+" in cls.physics
    loss = lambda t: 8e-6 * (1 - np.exp(-np.asarray(t) / 600.0))                      # noqa: E731
    coef = -np.diff(loss(KNOTS)) / cable.shape_scale
    spline = DrumModel("paper", [cls], {f"cable_relaxation_shape.c{j}": c for j, c in enumerate(coef)})
    law = DrumModel("paper", ["cable_relaxation"], {"cable_relaxation.displacement_loss_m": 8e-6,
                                                    "cable_relaxation.relaxation_time_s": 600.0})
    for force in (150.0, 250.0, 400.0):
        a, b = (m.evaluate(np.array(KNOTS), force, initial_temp_C=200.0).torque_Nm for m in (spline, law))
        np.testing.assert_allclose(a, b, rtol=1e-9)


def test_a_shape_free_radial_contraction_adds_the_same_clamp_force_at_every_hand_force():
    """Its physics is a clamp force that grows as the drum cools, the same at every hand force: the flexible form
    adds s·g(T_d) to the clamp force (a factor would scale it with the hand force)."""
    radial = get_effect("drum_radial_contraction")
    cls = spline_effect(radial, [40.0, 120.0, 250.0])
    assert cls.scale == radial.shape_scale > 0
    spline = DrumModel("paper", [cls], {"drum_radial_contraction_shape.c0": -0.5,
                                        "drum_radial_contraction_shape.c1": -0.8})
    plain = DrumModel("paper")
    t = np.array([0.0, 900.0, 3600.0])
    added = [spline.evaluate(t, f, initial_temp_C=250.0).normal_force_N - plain.evaluate(
        t, f, initial_temp_C=250.0).normal_force_N for f in (200.0, 400.0)]
    np.testing.assert_allclose(added[0], added[1], rtol=1e-9)
    a = added[0]                          # 1.3 units of 2 kN less at 250 °C (energised), none once cooled to 40 °C
    assert a[0] < -2600.0 and a[0] < a[1] < a[2] and abs(a[2]) < 1.0


def test_a_model_file_keeps_an_absolute_shape_and_reads_one_without_scale_as_a_factor(tmp_path):
    """A cable's spline is saved with its unit (``scale``) and comes back the same; a table without ``scale`` (files
    written before absolute forms existed) is the factor it meant then."""
    cls = spline_effect(get_effect("cable_relaxation"), KNOTS)
    m = DrumModel("paper", [cls], {"cable_relaxation_shape.c0": -0.2, "cable_relaxation_shape.c1": -0.1,
                                   "cable_relaxation_shape.c2": -0.05})
    path = save_model(m, tmp_path / "m.toml")
    assert "scale = 1e-05" in open(path).read()
    back = load_model(path)
    np.testing.assert_allclose(back.evaluate(T, 250.0).torque_Nm, m.evaluate(T, 250.0).torque_Nm, rtol=1e-12)
    old = tmp_path / "old.toml"
    old.write_text("\n".join(line for line in open(path).read().splitlines() if not line.startswith("scale =")))
    factor = load_model(old)
    assert factor.effects[0].scale == 0.0
    u6_factor = DrumModel("paper", [spline_effect(get_effect("cable_relaxation"), KNOTS, 0.0)], dict(m.values))
    np.testing.assert_allclose(factor.evaluate(T, 250.0).torque_Nm, u6_factor.evaluate(T, 250.0).torque_Nm,
                               rtol=1e-12)
    assert not np.allclose(factor.evaluate(T, 250.0).torque_Nm, m.evaluate(T, 250.0).torque_Nm)


def test_a_model_file_keeps_a_shape_free_form_and_its_torque(tmp_path):
    cls = spline_effect(get_effect("friction_temperature"), [30.0, 100.0, 200.0, 300.0])
    m = DrumModel("paper", [cls], {"friction_temperature_shape.c0": 0.02, "friction_temperature_shape.c1": -0.05,
                                   "friction_temperature_shape.c2": -0.1})
    back = load_model(save_model(m, tmp_path / "m.toml"))
    assert [e.name for e in back.effects] == ["friction_temperature_shape"] and back.values == m.values
    assert np.array_equal(back.evaluate(T, 300.0, initial_temp_C=250.0).torque_Nm,
                          m.evaluate(T, 300.0, initial_temp_C=250.0).torque_Nm)
    assert model_to_toml(back) == model_to_toml(m)
    assert "knots = [30.0, 100.0, 200.0, 300.0]" in model_to_toml(m)


@pytest.mark.parametrize("table, needle", [
    ("[effects.lining_crep_shape]\nknots = [0, 1, 2]\n", "did you mean 'lining_creep'"),
    ("[effects.lining_creep_shape]\nc0 = 0.1\n", "needs 'knots'"),
    ("[effects.lining_creep_shape]\nknots = [0, 2, 1]\n", "key 'effects.lining_creep_shape.knots'"),
    ("[effects.lining_creep_shape]\nknots = [0, 1]\n", "at least three"),
    ("[effects.lining_creep_shape]\nknots = [0, 1, 2]\nc5 = 0.1\n", "unknown key 'effects.lining_creep_shape.c5'"),
    ("[effects.lining_creep_shape]\nknots = [0, 1, 2]\nc0 = 2.0\n", "outside [-0.9, 0.9]"),
    ("[effects.torque_zero_offset_shape]\nknots = [0, 1, 2]\n", "no shape-free version"),
    ("[effects.cable_relaxation_shape]\nknots = [0, 1, 2]\nscale = -1e-05\n", "key 'effects.cable_relaxation_shape.scale'"),
])
def test_bad_shape_free_tables_are_one_line_errors_naming_the_key(tmp_path, run_cli, table, needle):
    path = tmp_path / "bad.toml"
    path.write_text('extends = "paper"\n' + table, encoding="utf-8")
    with pytest.raises(UserError) as exc:
        load_model(path)
    assert needle in str(exc.value) and str(path) in str(exc.value)
    code, _, err = run_cli("hold", "--grade-pct", 20, "--hand-force-N", 300, "--params", path)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


def test_from_model_file_builds_the_catalogue_effects_spline():
    cls = from_model_file("cable_relaxation_shape", [0.0, 600.0, 3600.0], "m.toml")
    assert cls.base == "cable_relaxation" and list(cls.knots) == [0.0, 600.0, 3600.0]
    assert [p.name for p in cls.parameters] == ["c0", "c1"]
