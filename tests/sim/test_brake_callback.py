"""The brake controller: drum torque per wheel, for the sense the wheel is driven (eqs. 18–21)."""
import mujoco
import numpy as np
import pytest

from rollaway.model.brake import drum_brake
from rollaway.sim import build_model, simulate
from rollaway.sim.brake_callback import BrakeController
from tests.sim.conftest import make_scenario


@pytest.mark.parametrize("grade,direction,expected", [(20, "downhill", "downhill"), (20, "uphill", "uphill"),
                                                      (-20, "uphill", "downhill")])
def test_held_car_gets_the_capacity_of_its_driven_sense(grade, direction, expected):
    s = make_scenario(grade_pct=grade, direction=direction, hand_force_N=300, duration_s=2)
    r = simulate(s, mode="fixed")
    tr = r.trace
    sense = 1 if expected == "downhill" else -1
    assert (tr.sense[5:] == sense).all()
    # each record carries the capacity set at the brake update one period before it (records are decimated at rest)
    want = drum_brake(s.params, time_s=tr.time_s[1:] - 0.02, hand_force_N=300, direction=expected).torque_Nm
    np.testing.assert_allclose(tr.capacity_Nm[1:, 0], want, rtol=1e-9)
    np.testing.assert_allclose(tr.capacity_Nm[1:, 1], want, rtol=1e-9)


def test_sense_follows_the_resisted_torque_when_pushed_the_other_way():
    """A car facing downhill pushed uphill harder than gravity: the brake now resists a backward
    torque and must switch to the eq. (19) capacity."""
    s = make_scenario(grade_pct=20, direction="downhill", hand_force_N=300, duration_s=2)
    model, info = build_model(s)
    data = mujoco.MjData(model)
    ctrl = BrakeController(s, info, model, 3.0)
    ctrl.update(model, data)
    mujoco.mj_step(model, data, nstep=200)
    ctrl.update(model, data)
    assert list(ctrl.sense) == [1, 1]
    push = -2.0 * info.total_mass_kg * 9.81 * np.sin(info.theta_rad) * info.downhill_unit
    data.xfrc_applied[info.car_body, :3] = push
    for _ in range(20):
        mujoco.mj_step(model, data, nstep=20)
        cap = ctrl.update(model, data)
    assert list(ctrl.sense) == [-1, -1]
    k = ctrl.index(data.time)
    rev = drum_brake(s.params, time_s=ctrl.time_s[k], hand_force_N=300, direction="uphill").torque_Nm
    np.testing.assert_allclose(cap, [rev, rev])
    np.testing.assert_allclose(model.dof_frictionloss[list(info.rear_dofs)], [rev, rev])
