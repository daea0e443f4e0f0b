"""Build the MuJoCo car for one scenario from ``models/car.xml`` through :class:`mujoco.MjSpec`.

Everything scenario-dependent is set on the spec, never by editing XML text:

* grade: the ``slope`` frame is rotated about y by θ = atan(|grade|/100) (docs/model.md, "Model chain" item 8);
  downhill is +x of that frame.  A negative grade flips the heading (as in :mod:`rollaway.hold`);
* heading: facing downhill = car +x along the frame's +x; facing uphill = yawed by π;
* the car itself from the parameter set: vehicle mass (wheels included), wheel radius,
  wheelbase, track, centre of gravity, gravity (Table 1 + docs/model.md, "Vehicle geometry" [assumed]);
* occupants: 70 kg (``occupant_mass_kg``) bodies welded to the chassis, 1–2 in the front row,
  3–5 in the rear row (docs/model.md; lateral seat positions are [assumed]);
* tyre–road friction μ_r on the tyre geoms (priority 1, so theirs wins) and on the road;
* the rear hinges' ``frictionloss`` starts at the drum torque at t = 0; it is then driven by
  :class:`rollaway.sim.brake_callback.BrakeController`.

Numerics [assumed, measured — see tests/sim]: 1 ms Euler step, elliptic cone, impratio 1000
while the tyres stick (:mod:`rollaway.sim.tyres` handles sliding), Newton solver, stiff joint
friction (``solreffriction 0.004 1``, ``solimpfriction 0.9999 0.9999 0.001``) and tyre contacts
(``solref 0.004 1``, ``solimp 0.99 0.9999 0.001``).  MuJoCo's soft friction lets a held wheel
creep at v ≈ (1−d)/d · dof_invweight0 · T / b; the rear hinges' ``dof_invweight0`` is
multiplied by :data:`REAR_INVWEIGHT_SCALE` (it only scales the constraint regulariser).
``mj_setConst`` resets it, so :func:`set_constants` is the one place constants are recomputed
and re-applies the scaling, and :func:`check_constants` asserts it before every run.  Creep:
0.31 mm per simulated hour at 20 %, 0.45 mm at 30 %.  MuJoCo sleep (enabled in the XML so
that the file alone holds a car still) is switched off here: the simulator has its own
event-driven skip, and sleeping trees do not wake when ``dof_frictionloss`` changes.

Reuse: :func:`car_model` compiles the physics-only car (no decorative geoms) once per
structure (occupants and vehicle geometry) and :func:`configure` sets everything else per
scenario on the compiled :class:`mujoco.MjModel` — the same numbers a fresh compile gives.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from rollaway.errors import UserError
from rollaway.hold import effective_slope as hold_effective_slope
from rollaway.hold import required_torque, total_mass_kg
from rollaway.physics.vehicle import FRONT_ROW_SEATS, grade_angle_rad
from rollaway.hold.scenario import Scenario

MODEL_PATH = Path(__file__).resolve().parents[3] / "models" / "car.xml"

WHEEL_MASS_KG = 15.0          # [assumed] one wheel with tyre and drum; counts in the vehicle mass
WHEEL_WIDTH_M = 0.2           # [assumed] for the wheel inertia only
REAR_INVWEIGHT_SCALE = 1e-3   # [assumed] measured: creep 0.3 mm/h instead of ~120 mm/h at 20 %
STICK_IMPRATIO = 1000.0       # [assumed] impratio while the tyres stick (as in car.xml): small tyre creep
CHASSIS_BOX_M = (4.2, 1.7, 1.0)  # [assumed] box whose inertia the chassis gets
# lateral seat positions, occupants 1..5 (y, +left) [assumed]; rows from docs/model.md
SEAT_Y_M = (0.4, -0.4, 0.5, -0.5, 0.0)
WHEELS = ("fl", "fr", "rl", "rr")
REAR = ("rl", "rr")


@dataclass(frozen=True)
class ModelInfo:
    """What the simulator needs to know about a compiled car."""

    grade_pct: float                 # |grade| the road is tilted by
    facing: str                      # heading relative to the fall line after the grade's sign
    theta_rad: float
    total_mass_kg: float             # car + occupants, as compiled (checked against hold.total_mass_kg)
    demand_axle_Nm: float            # T_req, eq. (23), at the rear axle
    wheel_radius_m: float
    downhill_unit: np.ndarray        # world-frame unit vector pointing down the slope
    car_body: int
    car_qpos_adr: int                # free joint: qpos[adr:adr+3] is the car origin position
    car_dof_adr: int                 # free joint: qvel[adr:adr+3] is the linear velocity
    rear_dofs: tuple[int, int]       # dof addresses of hinge_rl, hinge_rr
    front_dofs: tuple[int, int]
    rear_tyre_geoms: tuple[int, int]
    road_geom: int
    road_normal: np.ndarray = None    # world-frame unit normal of the road
    tyre_geoms: tuple = ()            # fl, fr, rl, rr
    rear_wheel_bodies: tuple = ()
    tyre_road_mu: float = 0.0
    rear_invweight0: tuple = ()       # the scaled rear dof_invweight0 (set by set_constants)


def _car_forward_sign(facing: str) -> float:
    return 1.0 if facing == "downhill" else -1.0


def effective_slope(scenario: Scenario) -> tuple[float, str]:
    """(|grade|, facing) of *scenario*, a negative grade folded into the heading (:func:`rollaway.hold.effective_slope`)."""
    return hold_effective_slope(scenario.grade_pct, scenario.direction)


def _box_inertia(mass, size):
    lx, ly, lz = size
    return [mass / 12 * (ly**2 + lz**2), mass / 12 * (lx**2 + lz**2), mass / 12 * (lx**2 + ly**2)]


def build_spec(scenario: Scenario, *, sleep: bool = False, model_path: Path = MODEL_PATH,
               physics_only: bool = False) -> mujoco.MjSpec:
    """The car's :class:`mujoco.MjSpec`, configured for *scenario* (not compiled).

    ``physics_only``: without the decorative geoms (posts, kerbs, car body shapes, occupants'
    capsules): the same dynamics, cheaper steps; for runs that are not rendered.
    """
    if not model_path.is_file():
        raise UserError(f"car model '{model_path}' is missing; reinstall rollaway from its source tree")
    p = scenario.params
    spec = mujoco.MjSpec.from_file(str(model_path))
    grade, facing = effective_slope(scenario)
    theta = float(grade_angle_rad(grade))
    spec.option.gravity = [0.0, 0.0, -p.gravity_m_s2]
    if not sleep:
        spec.option.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_SLEEP)
    spec.frame("slope").quat = [math.cos(theta / 2), 0.0, math.sin(theta / 2), 0.0]

    # vehicle geometry from the parameter set
    R, L, track = p.wheel_radius_m, p.wheelbase_m, p.track_m
    m_chassis = p.vehicle_mass_kg - 4 * WHEEL_MASS_KG
    if m_chassis <= 0:
        raise UserError(f"vehicle_mass_kg = {p.vehicle_mass_kg:g} must exceed the four wheels "
                        f"({4 * WHEEL_MASS_KG:g} kg) for the simulator")
    a, h = p.cg_behind_front_m, p.cg_height_m
    car = spec.body("car")
    sgn = _car_forward_sign(facing)
    car.pos = [sgn * a, 0.0, 0.0]                  # car CG above the frame origin
    car.quat = [1.0, 0.0, 0.0, 0.0] if sgn > 0 else [0.0, 0.0, 0.0, 1.0]
    car.ipos = [(-p.vehicle_mass_kg * a + 4 * WHEEL_MASS_KG * L / 2) / m_chassis, 0.0,
                (p.vehicle_mass_kg * h - 4 * WHEEL_MASS_KG * R) / m_chassis]
    car.mass = m_chassis
    car.inertia = _box_inertia(m_chassis, CHASSIS_BOX_M)
    i_axle = 0.5 * WHEEL_MASS_KG * R**2
    i_other = 0.25 * WHEEL_MASS_KG * R**2 + WHEEL_MASS_KG * WHEEL_WIDTH_M**2 / 12
    for w in WHEELS:
        body = spec.body(f"wheel_{w}")
        body.pos = [0.0 if w[0] == "f" else -L, track / 2 if w[1] == "l" else -track / 2, R]
        body.mass = WHEEL_MASS_KG
        body.inertia = [i_other, i_axle, i_other]
        tyre = spec.geom(f"tyre_{w}")
        tyre.size = [R, 0.0, 0.0]
        tyre.friction = [p.tyre_road_mu, tyre.friction[1], tyre.friction[2]]
    road = spec.geom("road")
    road.friction = [p.tyre_road_mu, road.friction[1], road.friction[2]]

    if not physics_only:
        _add_posts(spec, theta)
    for i in range(scenario.occupants):
        x = -(p.front_seat_behind_front_m if i < FRONT_ROW_SEATS else p.rear_seat_behind_front_m)
        seat = car.add_body(name=f"occupant_{i + 1}", pos=[x, SEAT_Y_M[i], p.seat_height_m],
                            mass=p.occupant_mass_kg, ipos=[0.0, 0.0, 0.0],
                            inertia=[4.0, 4.0, 1.5])  # [assumed] seated person
        if not physics_only:
            seat.add_geom(type=mujoco.mjtGeom.mjGEOM_CAPSULE, size=[0.17, 0.25, 0], pos=[0, 0, 0.3],
                          contype=0, conaffinity=0, group=1, density=0, material="person")
    if physics_only:
        for geom in list(spec.geoms):
            if geom.contype == 0 and geom.conaffinity == 0:
                spec.delete(geom)
    return spec


def _add_posts(spec: mujoco.MjSpec, theta: float) -> None:
    """Vertical (world-frame) posts along the far kerb, so the picture shows the road's tilt."""
    for i, xs in enumerate(np.arange(-200.0, 201.0, 8.0)):
        spec.worldbody.add_geom(name=f"post_{i}", type=mujoco.mjtGeom.mjGEOM_CYLINDER, size=[0.06, 1.5, 0],
                                pos=[xs * math.cos(theta), 4.6, -xs * math.sin(theta) + 1.5],
                                rgba=[0.9, 0.9, 0.9, 1], contype=0, conaffinity=0, group=1, density=0)


def set_constants(model: mujoco.MjModel, info: ModelInfo) -> None:
    """``mj_setConst`` (constants for the current qpos0 and masses), then the rear-hinge scaling.

    MuJoCo's constant recomputation resets ``dof_invweight0``; this is the one place that
    recomputes them, so the scaling that keeps creep small is never lost.  Idempotent.
    """
    mujoco.mj_setConst(model, mujoco.MjData(model))
    for dof in info.rear_dofs:
        model.dof_invweight0[dof] *= REAR_INVWEIGHT_SCALE
    object.__setattr__(info, "rear_invweight0", tuple(float(model.dof_invweight0[d]) for d in info.rear_dofs))


def check_constants(model: mujoco.MjModel, info: ModelInfo) -> None:
    """Assert the rear hinges still carry the scaled ``dof_invweight0`` (raise if a recompute lost it)."""
    got = tuple(float(model.dof_invweight0[d]) for d in info.rear_dofs)
    if not np.allclose(got, info.rear_invweight0, rtol=1e-9, atol=0.0):
        raise RuntimeError(f"rear dof_invweight0 {got} lost its scaling (expected {info.rear_invweight0}); "
                           "call rollaway.sim.model.set_constants after mj_setConst or a recompile")


def _quat_mul(a, b):
    out = np.zeros(4)
    mujoco.mju_mulQuat(out, np.asarray(a, float), np.asarray(b, float))
    return out


def configure(model: mujoco.MjModel, scenario: Scenario, *, gravity_tilt_rad: float = 0.0) -> ModelInfo:
    """Set the per-scenario values of a compiled car in place and return its :class:`ModelInfo`.

    What a scenario changes without changing the model's structure: the road's tilt and the
    car's placement and heading on it (exactly what compiling the ``slope`` frame gives),
    gravity, tyre–road friction; the run-time settings the simulator changes (brake
    frictionloss, tyre condim, impratio) are reset.  Then the constants are recomputed
    (:func:`set_constants`).  The structure (vehicle geometry and masses, occupants) must
    match the model's: see :func:`car_model`.

    ``gravity_tilt_rad`` represents part φ of the slope angle θ by tilting gravity instead of
    the road (road tilted by θ − φ, gravity by φ: the same physics); the simulator uses 0, the
    tests use it to check that verdicts do not depend on the representation.
    """
    p = scenario.params
    grade, facing = effective_slope(scenario)
    theta = float(grade_angle_rad(grade))
    phi = float(gravity_tilt_rad)
    road_tilt = theta - phi
    jid = lambda n: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, n)  # noqa: E731
    gid = lambda n: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, n)  # noqa: E731
    car = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "car")
    free = jid("car_free")
    q_slope = np.array([math.cos(road_tilt / 2), 0.0, math.sin(road_tilt / 2), 0.0])
    sgn = _car_forward_sign(facing)
    rot = np.zeros(9)
    mujoco.mju_quat2Mat(rot, q_slope)
    road = gid("road")
    model.geom_quat[road] = q_slope
    model.geom_pos[road] = 0.0
    model.body_pos[car] = rot.reshape(3, 3) @ np.array([sgn * p.cg_behind_front_m, 0.0, 0.0])
    model.body_quat[car] = _quat_mul(q_slope, [1.0, 0.0, 0.0, 0.0] if sgn > 0 else [0.0, 0.0, 0.0, 1.0])
    adr = int(model.jnt_qposadr[free])
    model.qpos0[adr:adr + 3] = model.body_pos[car]
    model.qpos0[adr + 3:adr + 7] = model.body_quat[car]
    model.opt.gravity[:] = [p.gravity_m_s2 * math.sin(phi), 0.0, -p.gravity_m_s2 * math.cos(phi)]
    model.opt.impratio = STICK_IMPRATIO
    tyres = tuple(gid(f"tyre_{w}") for w in WHEELS)
    for g in tyres + (road,):
        model.geom_friction[g, 0] = p.tyre_road_mu
    model.geom_condim[list(tyres)] = 3
    model.dof_frictionloss[:] = 0.0
    m_tot = float(total_mass_kg(p, scenario.occupants))
    info = ModelInfo(
        grade_pct=grade, facing=facing, theta_rad=theta, total_mass_kg=m_tot,
        demand_axle_Nm=float(required_torque(p, grade, scenario.occupants)),
        wheel_radius_m=p.wheel_radius_m,
        downhill_unit=np.array([math.cos(road_tilt), 0.0, -math.sin(road_tilt)]),
        road_normal=np.array([math.sin(road_tilt), 0.0, math.cos(road_tilt)]),
        car_body=car, car_qpos_adr=adr, car_dof_adr=int(model.jnt_dofadr[free]),
        rear_dofs=tuple(int(model.jnt_dofadr[jid(f"hinge_{w}")]) for w in REAR),
        front_dofs=tuple(int(model.jnt_dofadr[jid(f"hinge_{w}")]) for w in ("fl", "fr")),
        rear_tyre_geoms=tuple(gid(f"tyre_{w}") for w in REAR), tyre_geoms=tyres, road_geom=road,
        rear_wheel_bodies=tuple(int(model.geom_bodyid[gid(f"tyre_{w}")]) for w in REAR),
        tyre_road_mu=p.tyre_road_mu)
    set_constants(model, info)
    m_model = float(model.body_subtreemass[car])
    if abs(m_model - m_tot) > 1e-6 * m_tot:
        raise RuntimeError(f"compiled car mass {m_model} kg differs from the scenario's {m_tot} kg")
    return info


def build_model(scenario: Scenario, *, sleep: bool = False, physics_only: bool = False
                ) -> tuple[mujoco.MjModel, ModelInfo]:
    """Compile the car for *scenario*; return the model and a :class:`ModelInfo`.

    The rear hinges' frictionloss is 0 here: the brake controller sets it.
    """
    model = build_spec(scenario, sleep=sleep, physics_only=physics_only).compile()
    return model, configure(model, scenario)


def _structure_key(scenario: Scenario) -> tuple:
    """What decides a compiled car's structure and masses (all else is set by :func:`configure`)."""
    p = scenario.params
    return (scenario.occupants, p.vehicle_mass_kg, p.wheel_radius_m, p.wheelbase_m, p.track_m,
            p.cg_behind_front_m, p.cg_height_m, p.occupant_mass_kg, p.front_seat_behind_front_m,
            p.rear_seat_behind_front_m, p.seat_height_m)


_CACHE: dict[tuple, mujoco.MjModel] = {}
CACHE_SIZE = 16     # compiled physics-only cars kept per process (one per structure)


def car_model(scenario: Scenario, *, gravity_tilt_rad: float = 0.0) -> tuple[mujoco.MjModel, ModelInfo]:
    """The physics-only car for *scenario*, compiled once per structure and reconfigured per call.

    Sweeps change grade, heading, friction, gravity and the brake between points; those are
    values on the compiled :class:`mujoco.MjModel` (:func:`configure`), so a worker compiles
    one model per number of occupants instead of one per point.  The returned model is
    shared: use it for one run at a time.
    """
    key = _structure_key(scenario)
    model = _CACHE.get(key)
    if model is None:
        if len(_CACHE) >= CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))
        model = build_spec(scenario, physics_only=True).compile()
        _CACHE[key] = model
    return model, configure(model, scenario, gravity_tilt_rad=gravity_tilt_rad)
