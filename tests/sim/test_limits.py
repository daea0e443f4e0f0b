"""Honesty at the limits: combined tyre + brake limits, a clean skid, knife edges, end of run, divergence."""
import dataclasses
import math

import mujoco
import numpy as np
import pytest

from rollaway.hold import tyre_adhesion_margin
from rollaway.sim import simulate
from rollaway.sim.model import REAR_INVWEIGHT_SCALE, build_model, car_model, check_constants, set_constants
from rollaway.sim.run import _Run
from tests.sim.conftest import force_for_margin, make_scenario


def combined(grade, direction, occupants, tyre_margin, brake_margin, duration_s=20.0):
    """Scenario with the given analytic tyre adhesion margin and constant brake margin (ambient drum)."""
    s = make_scenario(grade_pct=grade, direction=direction, occupants=occupants, duration_s=duration_s,
                      initial_drum_temp_C=27, hand_force_N=force_for_margin(brake_margin, grade, direction, occupants))
    tam = float(tyre_adhesion_margin(s.params, grade, direction, occupants))
    return s.replace(tyre_road_mu=s.params.tyre_road_mu * tyre_margin / tam)


GRID = [(5, "downhill", 0, 1.02), (5, "uphill", 5, 3.0), (20, "downhill", 1, 1.5), (20, "uphill", 0, 1.02),
        (32.5, "downhill", 5, 1.08), (32.5, "uphill", 1, 1.1), (50, "downhill", 0, 3.0), (50, "uphill", 5, 1.02),
        (5, "uphill", 3, 1.02), (50, "downhill", 3, 1.02), (20, "downhill", 4, 2.0), (35, "uphill", 2, 1.3)]


@pytest.mark.parametrize("grade,direction,occupants,brake", GRID)
@pytest.mark.parametrize("tyre,expected", [(1.02, "held"), (1.05, "held"), (0.95, "tyre_skid"), (0.98, "tyre_skid")])
def test_combined_limit_grid(grade, direction, occupants, brake, tyre, expected):
    r = simulate(combined(grade, direction, occupants, tyre, brake))
    assert r.outcome == expected, (r.outcome, r.status, r.slip_ratio)
    if expected == "held":
        assert r.max_displacement_m < 1e-3 and r.status == "ok"
    else:        # at least one rear wheel locked and sliding (with an uneven load the other drum may slip)
        assert max(r.wheel_slip_ratios) > 0.99
        if occupants in (0, 2, 4, 5):                   # laterally symmetric load: both wheels locked
            assert r.slip_ratio > 0.99


@pytest.mark.parametrize("grade,direction,occupants", [(20, "downhill", 0), (32.5, "downhill", 5), (50, "uphill", 0),
                                                      (20, "downhill", 1), (50, "uphill", 1)])
def test_tyre_threshold_half_percent_with_a_weak_brake(grade, direction, occupants):
    """Brake margin 1.02: tyre margin 1.005 holds, 0.995 skids (labelled as a tyre skid)."""
    assert simulate(combined(grade, direction, occupants, 1.005, 1.02)).outcome == "held"
    assert simulate(combined(grade, direction, occupants, 0.995, 1.02)).outcome == "tyre_skid"


def test_skid_is_clean_locked_and_straight():
    """Laterally symmetric car (no occupant), tyre margin 0.97, strong brake: ~8 s of skid."""
    s = combined(30, "downhill", 0, 0.97, 3.0, duration_s=9.0)
    run = _Run(s, "fixed", full_window=True)
    normals = []
    forces = run.contacts.forces

    def logged(data):
        out = forces(data)
        if run.phases.any_sliding:
            normals.append(out[0][2:].copy())
        return out
    run.contacts.forces = logged
    r = run.run()
    assert r.outcome == "tyre_skid" and r.slip_ratio >= 0.99
    n = np.array(normals)
    static = n[: len(n) // 20].mean()
    assert np.mean(np.abs(n / static - 1.0) <= 0.2) >= 0.95
    tr = r.trace
    q0, q1 = tr.qpos[0, 3:7], tr.qpos[-1, 3:7]
    yaw = lambda q: math.atan2(2 * (q[0] * q[3] + q[1] * q[2]), 1 - 2 * (q[2] ** 2 + q[3] ** 2))  # noqa: E731
    assert abs(math.degrees(yaw(q1) - yaw(q0))) <= 2.0
    assert tr.time_s[-1] - r.rollaway_time_s >= 7.0
    # friction averages μN: the slide decelerates as Coulomb's law with the dynamic load transfer says
    sel = tr.time_s > (r.tyre_slide_s + 0.5)
    a_sim = 2 * np.polyfit(tr.time_s[sel], tr.displacement_m[sel], 2)[0]
    g, th, L = 9.81, run.info.theta_rad, 2.6
    mu, x, h = s.tyre_road_mu, 1.1, 0.55
    force = g * (math.sin(th) - mu * (x * math.cos(th) - h * math.sin(th)) / L)
    a_expected = force / (1 + mu * h / L + 2 * 0.5 * 15 / 1250)
    assert a_sim == pytest.approx(a_expected, rel=0.02)


def test_settled_start_has_no_kick():
    r = simulate(make_scenario(grade_pct=20, duration_s=2, hand_force_N=500), mode="fixed")
    assert r.outcome == "held"
    assert np.max(np.abs(r.trace.speed_m_s)) < 1e-6


@pytest.mark.parametrize("tyre", [0.99998, 1.00002])
def test_knife_edge_tyre_fast_equals_fixed(tyre):
    s = combined(20, "downhill", 0, tyre, 2.0, duration_s=40)
    fast, fixed = simulate(s, mode="fast"), simulate(s, mode="fixed")
    assert fast.outcome == fixed.outcome
    if fast.rollaway_time_s is not None:
        assert fast.rollaway_time_s == pytest.approx(fixed.rollaway_time_s, abs=1.0)


def test_run_ending_while_the_brake_slips_is_not_held():
    """The drum cools through the demand shortly before the end: the car has moved < 5 cm."""
    s = make_scenario(grade_pct=20, direction="uphill", hand_force_N=200, duration_s=400)
    t_slip = simulate(s).analytic_time_to_slip_s
    r = simulate(s.replace(duration_s=t_slip + 8.0))
    assert r.max_displacement_m < 0.05
    assert r.outcome == "brake_slip" and r.status == "rolling_at_end"
    assert t_slip - 1.0 <= r.rollaway_time_s <= t_slip + 8.0


def test_huge_gravity_diverges_and_is_never_held():
    s = make_scenario(duration_s=5)
    bad = dataclasses.replace(s, params=dataclasses.replace(s.params, gravity_m_s2=1e9))
    r = simulate(bad)
    assert r.outcome == "diverged" and r.status == "diverged" and r.rollaway_time_s is None
    assert any(w in r.diverged_reason for w in ("MuJoCo warning", "energy", "settling", "left the road"))
    assert r.to_dict()["diverged_reason"]


def test_diverged_simulate_exits_3_and_sweep_row_carries_the_error(monkeypatch, run_cli, tmp_path):
    from rollaway.sweep.executors import make_task, run_task, scenario_to_dict
    s = make_scenario(duration_s=5)
    bad = dataclasses.replace(s, params=dataclasses.replace(s.params, gravity_m_s2=1e9))
    rec = run_task(make_task("p", scenario_to_dict(bad), {}))
    assert "diverged" in rec["error"]
    f = tmp_path / "g.toml"
    f.write_text('name = "g"\ngrade_pct = 20\ndirection = "downhill"\noccupants = 1\nhand_force_N = 400\n'
                 'duration_s = 5\n[parameters]\ngravity_m_s2 = 1e9\n')
    code, out, err = run_cli("simulate", f)
    if code == 2:                   # parameter bounds may reject it first: then the error names the key
        assert "gravity_m_s2" in err
    else:
        assert code == 3 and "diverged" in err


def test_invweight_scaling_survives_set_const_and_reuse():
    s = make_scenario(grade_pct=25, direction="uphill", occupants=2)
    model, info = car_model(s)
    fresh, finfo = build_model(s, physics_only=True)
    for f in ("qpos0", "body_pos", "body_quat", "geom_quat", "dof_invweight0", "geom_friction"):
        np.testing.assert_array_equal(getattr(model, f), getattr(fresh, f))
    unscaled = fresh.dof_invweight0[list(info.rear_dofs)] / REAR_INVWEIGHT_SCALE
    mujoco.mj_setConst(model, mujoco.MjData(model))           # loses the scaling ...
    with pytest.raises(RuntimeError, match="invweight"):
        check_constants(model, info)
    set_constants(model, info)                                # ... and this restores it
    check_constants(model, info)
    np.testing.assert_allclose(model.dof_invweight0[list(info.rear_dofs)], unscaled * REAR_INVWEIGHT_SCALE)


def test_early_classification_matches_the_full_window():
    for s in (combined(20, "downhill", 1, 0.95, 2.0), make_scenario(hand_force_N=100, duration_s=20)):
        early, full = simulate(s), simulate(s, full_window=True)
        assert early.outcome == full.outcome and early.rollaway_time_s == full.rollaway_time_s
        assert early.integrated_time_s < full.integrated_time_s


@pytest.mark.parametrize("grade,direction,occupants", [(20, "downhill", 1), (45, "uphill", 5)])
@pytest.mark.parametrize("tyre,brake,expected", [(1.5, 1.02, "held"), (1.5, 0.98, "brake_slip"),
                                                 (1.02, 2.0, "held"), (0.98, 2.0, "tyre_skid")])
def test_verdict_does_not_depend_on_how_the_grade_is_represented(grade, direction, occupants, tyre, brake, expected):
    """The same slope as road tilt, as gravity tilt, and split half and half: one verdict."""
    s = combined(grade, direction, occupants, tyre, brake, duration_s=10.0)
    theta = math.atan(grade / 100)
    for phi in (0.0, theta / 2, theta):
        r = _Run(s, "fast", gravity_tilt_rad=phi).run()
        assert r.outcome == expected, (phi, r.outcome, r.slip_ratio)


@pytest.mark.parametrize("brake", [0.9995, 1.0005])
def test_knife_edge_brake_fast_equals_fixed(brake):
    s = combined(30, "uphill", 1, 1.5, brake, duration_s=20)
    fast, fixed = simulate(s, mode="fast"), simulate(s, mode="fixed")
    assert fast.outcome == fixed.outcome == ("held" if brake > 1 else "brake_slip")
    if fast.rollaway_time_s is not None:
        assert fast.rollaway_time_s == pytest.approx(fixed.rollaway_time_s, abs=0.05)


def test_long_hold_keeps_little():
    """Two simulated days: a handful of records, the drum series computed an hour at a time."""
    from rollaway.sim.brake_callback import CHUNK_UPDATES
    run = _Run(make_scenario(grade_pct=20, hand_force_N=400, duration_s=2 * 86400.0), "fast")
    r = run.run()
    assert r.outcome == "held" and r.sim_time_s == pytest.approx(2 * 86400.0, abs=0.05)
    assert len(r.trace.time_s) < 100
    assert run.ctrl.torque_Nm.shape[1] <= CHUNK_UPDATES < run.ctrl.n_updates


def test_non_finite_drum_torque_is_a_user_error():
    from rollaway.errors import UserError
    s = make_scenario(duration_s=5)
    bad = dataclasses.replace(s, params=dataclasses.replace(s.params, mu_drum=0.0), hand_force_N=1e308)
    with pytest.raises(UserError, match="not finite"):
        simulate(bad)
