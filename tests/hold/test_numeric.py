"""Numeric hold check of models with effects against brute-force dense evaluation (1e-6 relative)."""
import numpy as np
import pytest

from rollaway import hold
from rollaway.effects import CATALOGUE
from rollaway.model.drum_model import DrumModel

CASE = dict(grade_pct=30.0, direction="downhill", occupants=5)
DURATION_S = 3600.0
DENSE = np.linspace(0.0, DURATION_S, 1_000_001)


def _model(name):
    cls = CATALOGUE[name]
    return DrumModel("paper", [name], {f"{name}.{k}": v for k, v in cls.typical_values().items()})


def _dense_margin(model, force):
    return hold.hold_margin(model, DENSE, force, **CASE)


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_least_margin_slip_time_and_least_force_match_dense_evaluation(name):
    model = _model(name)
    force = float(hold.minimum_hand_force_N(model, duration_s=DURATION_S, **CASE))
    assert np.isfinite(force) and force > 0
    # least hand force: the dense least margin straddles 1 within ±1e-6 of it
    assert _dense_margin(model, force * (1 + 1e-6)).min() >= 1.0
    assert _dense_margin(model, force * (1 - 1e-6)).min() < 1.0
    for f in (0.9 * force, 1.1 * force):
        dense = _dense_margin(model, f)
        got = float(hold.min_brake_margin(model, f, duration_s=DURATION_S, **CASE))
        assert got == pytest.approx(dense.min(), rel=1e-6)
        assert got <= dense.min() * (1 + 1e-12)       # refined: never above the dense minimum
        t_slip = float(hold.time_to_slip_s(model, f, horizon_s=DURATION_S, **CASE))
        below = np.flatnonzero(dense < 1.0)
        if below.size == 0:
            assert np.isnan(t_slip)
            continue
        k = below[0]
        if k == 0:
            assert t_slip == 0.0
            continue
        # dense crossing, linearly interpolated between the bracketing instants
        m0, m1 = dense[k - 1], dense[k]
        t_dense = DENSE[k - 1] + (m0 - 1.0) / (m0 - m1) * (DENSE[k] - DENSE[k - 1])
        assert t_slip == pytest.approx(t_dense, rel=1e-6)
        assert float(hold.hold_margin(model, t_slip, f, **CASE)) == pytest.approx(1.0, abs=1e-9)


def test_vectorised_over_points_equals_point_by_point():
    model = _model("lining_creep")
    forces = np.array([150.0, 220.0, 260.0, 400.0])
    many = hold.min_brake_margin(model, forces, duration_s=DURATION_S, **CASE)
    one = [float(hold.min_brake_margin(model, f, duration_s=DURATION_S, **CASE)) for f in forces]
    np.testing.assert_allclose(many, one, rtol=1e-12)
    slips = hold.time_to_slip_s(model, forces, horizon_s=DURATION_S, **CASE)
    each = [float(hold.time_to_slip_s(model, f, horizon_s=DURATION_S, **CASE)) for f in forces]
    np.testing.assert_allclose(slips, each, rtol=1e-9)
    assert slips[0] == 0.0 and np.isnan(slips[-1])


def test_a_model_without_active_effects_takes_the_closed_forms():
    f = np.linspace(100, 500, 9)
    closed = hold.min_brake_margin(DrumModel("paper").params, f, duration_s=DURATION_S, **CASE)
    via_model = hold.min_brake_margin(DrumModel("paper", ["lining_creep"]), f, duration_s=DURATION_S, **CASE)
    assert np.array_equal(closed, via_model)


def test_analytic_verdict_of_a_model_with_effects():
    model = _model("lining_creep")
    force = float(hold.minimum_hand_force_N(model, duration_s=DURATION_S, **CASE))
    bad = hold.analytic_verdict(model, hand_force_N=0.95 * force, duration_s=DURATION_S, **CASE)
    good = hold.analytic_verdict(model, hand_force_N=1.05 * force, duration_s=DURATION_S, **CASE)
    assert bad.outcome == "brake_slip" and 0 < bad.time_to_slip_s < DURATION_S and not bad.holds
    assert good.outcome == "held" and good.least_hand_force_N == pytest.approx(force)


def test_self_locking_is_its_own_outcome():
    v = hold.analytic_verdict(DrumModel("paper").replace_params(mu_drum=1.2), hand_force_N=300, duration_s=60,
                              **CASE)
    assert v.outcome == "self_locking" and not v.holds and v.least_hand_force_N is None


def test_a_drawn_gap_among_the_values_is_the_gap_argument():
    """Uncertainty draws hand the held brake parameters over as values: a gap there acts as eq. (16b)'s l_g."""
    from rollaway.hold.numeric import MarginFunction
    from rollaway.model.drum_model import DrumModel
    from rollaway.model.parameters import paper
    model = DrumModel(paper())
    gaps = np.array([0.0, 5e-4, 1e-3])
    by_values = MarginFunction(model, np.full(3, 300.0), 1.0, 2000.0, None, None, 150.0, values={"gap_m": gaps})
    by_arg = MarginFunction(model, np.full(3, 300.0), 1.0, 2000.0, None, gaps, 150.0)
    t = np.array([0.0, 600.0, 3600.0])[:, None]
    a, b = by_values(t, np.arange(3)[None, :]), by_arg(t, np.arange(3)[None, :])
    np.testing.assert_array_equal(a, b)
    assert np.all(np.diff(a, axis=1) < 0)           # a wider gap, a softer clamp: less margin
