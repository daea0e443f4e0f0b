"""The compiled car: masses, centre of gravity, geometry and per-scenario settings."""
import math

import mujoco
import numpy as np
import pytest

from rollaway.model.parameters import paper
from rollaway.physics.vehicle import centre_of_gravity_m
from rollaway.sim import build_model
from rollaway.sim.model import MODEL_PATH, REAR_INVWEIGHT_SCALE, build_spec
from tests.sim.conftest import make_scenario


def _slope_frame_com(model, data, info):
    """Centre of mass of the car in the slope frame, relative to the front-axle ground point."""
    mujoco.mj_forward(model, data)
    c, s = math.cos(info.theta_rad), math.sin(info.theta_rad)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])          # slope frame -> world
    com = rot.T @ data.subtree_com[info.car_body]
    hub = rot.T @ data.xpos[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "wheel_fl")]
    return com, hub


@pytest.mark.parametrize("occupants", [0, 1, 2, 3, 5])
def test_mass_and_centre_of_gravity(occupants):
    p = paper()
    model, info = build_model(make_scenario(occupants=occupants, grade_pct=30))
    data = mujoco.MjData(model)
    assert info.total_mass_kg == pytest.approx(1250 + 70 * occupants, abs=1e-9)
    x, z = centre_of_gravity_m(occupants, vehicle_mass_kg_=p.vehicle_mass_kg, occupant_mass_kg=70.0,
                               cg_behind_front_m=1.1, cg_height_m=0.55, front_seat_behind_front_m=1.3,
                               rear_seat_behind_front_m=2.2, seat_height_m=0.5)
    com, hub = _slope_frame_com(model, data, info)
    assert hub[0] - com[0] == pytest.approx(x, abs=1e-6)          # facing downhill: forward is +x
    assert com[2] - (hub[2] - 0.3) == pytest.approx(z, abs=1e-6)


def test_empty_car_matches_model_md():
    model, info = build_model(make_scenario(occupants=0))
    com, hub = _slope_frame_com(model, mujoco.MjData(model), info)
    assert (hub[0] - com[0], com[2] - hub[2] + 0.3) == pytest.approx((1.1, 0.55), abs=1e-6)
    ids = {n: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, f"wheel_{n}") for n in ("fl", "fr", "rl", "rr")}
    pos = {n: model.body_pos[i] for n, i in ids.items()}
    assert pos["fl"][0] - pos["rl"][0] == pytest.approx(2.6)
    assert pos["fl"][1] - pos["fr"][1] == pytest.approx(1.5)
    assert all(model.body_mass[i] == 15.0 for i in ids.values())
    assert model.body_subtreemass[info.car_body] == pytest.approx(1250.0)


def test_committed_xml_alone_is_the_empty_car():
    model = mujoco.MjModel.from_xml_path(str(MODEL_PATH))
    car = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "car")
    assert model.body_subtreemass[car] == pytest.approx(1250.0)
    for j in ("hinge_fl", "hinge_fr", "hinge_rl", "hinge_rr"):
        assert mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, j) >= 0


@pytest.mark.parametrize("grade,direction,facing", [(20, "downhill", "downhill"), (30, "uphill", "uphill"),
                                                    (-20, "downhill", "uphill")])
def test_grade_heading_friction_and_brake_dofs(grade, direction, facing):
    model, info = build_model(make_scenario(grade_pct=grade, direction=direction, tyre_road_mu=0.55))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert info.facing == facing
    assert math.tan(info.theta_rad) == pytest.approx(abs(grade) / 100)
    forward = data.xmat[info.car_body].reshape(3, 3)[:, 0]
    assert forward @ info.downhill_unit == pytest.approx(1.0 if facing == "downhill" else -1.0)
    assert info.downhill_unit[2] < 0
    for g in info.rear_tyre_geoms:
        assert model.geom_friction[g][0] == pytest.approx(0.55)
        assert model.geom_priority[g] == 1
    assert model.opt.enableflags & int(mujoco.mjtEnableBit.mjENBL_SLEEP) == 0
    fresh = build_spec(make_scenario(grade_pct=grade, direction=direction)).compile()
    for dof in info.rear_dofs:
        assert model.dof_invweight0[dof] == pytest.approx(REAR_INVWEIGHT_SCALE * fresh.dof_invweight0[dof])
    for dof in info.front_dofs:
        assert model.dof_frictionloss[dof] == 0.0
        assert model.dof_invweight0[dof] == pytest.approx(fresh.dof_invweight0[dof])
