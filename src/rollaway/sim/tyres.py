"""The tyre–road contacts: forces and slip read from MuJoCo, and the sliding regime.

Two regimes for the rear tyres, switched by :class:`TyrePhases` (the axle enters together,
each wheel may leave on its own):

* **stick** (MuJoCo's own friction): condim 3, elliptic cone, ``impratio``
  :data:`rollaway.sim.model.STICK_IMPRATIO` (1000).  A high impratio keeps a held tyre's creep
  small (MuJoCo documentation, "Preventing slip"), but with it a *sliding* contact bounces: the
  convex contact model couples slip to separation and the stiff friction regulariser makes the
  normal force chatter (rear tyres unloaded on most steps, spikes of 100× the static load),
  which saturates the brake and turns "locked" wheels.
* **slide** (Coulomb's law applied explicitly): when both rear tyres are on their friction
  cones, or a contact point slips faster than :data:`SLIDE_ENTER_M_S` while its wheel does not
  roll along, the rear contacts become frictionless (condim 1: MuJoCo keeps the normal force)
  and the Coulomb force F = −μ_r·N·v̂ (N the contact's normal force from MuJoCo, v̂ the slip
  direction of the contact point) is applied at each contact point through ``xfrc_applied``.
  Below :data:`SLIDE_REG_M_S` of slip it is scaled by |v|/:data:`SLIDE_REG_M_S` (a viscous
  regularisation that keeps the explicit force stable: damping·dt/m_car < 1); it is recomputed
  every step below :data:`SLIDE_FAST_M_S` and every :data:`SLIDE_HOLD_STEPS` steps above.
  A wheel goes back to the stick regime when its drum can no longer hold it against μ_r·N·R
  (the wheel spins up and its tyre regrips: a brake slip, handled by MuJoCo's friction); the
  axle goes back when the slip has died out and a static test says MuJoCo's friction holds.

All thresholds [assumed]; measured effect in tests/sim/test_limits.py (clean skid, combined
limits, knife edges).
"""
from __future__ import annotations

import mujoco
import numpy as np

from rollaway.sim.model import ModelInfo

SLIDE_ENTER_M_S = 4e-3      # [assumed] contact slip that starts the slide regime (creep is ~1e-7 m/s)
SLIDE_REG_M_S = 2e-3        # [assumed] regularisation speed of the explicit friction; also the exit speed
SLIDE_FAST_M_S = 0.02       # [assumed] above this slip the Coulomb force is held over SLIDE_HOLD_STEPS steps
SLIDE_HOLD_STEPS = 5        # [assumed] 5 ms: short against the car's roll and pitch periods
CONE_CHECK_M_S = 1e-4       # [assumed] slip above which the stick regime re-tests the friction cones
CONE_EPS = 1e-6             # [assumed] |F_t| ≥ μN(1 − CONE_EPS): the contact is on its friction cone
STICK_EPS = 1e-4            # [assumed] static test: |F_t| < μN(1 − STICK_EPS) on a rear tyre means the axle sticks
_BODY = mujoco.mjtObj.mjOBJ_BODY


class TyreContacts:
    """Per-step readings of the four tyre contacts of one run."""

    def __init__(self, model: mujoco.MjModel, info: ModelInfo):
        self.model, self.info = model, info
        self._v6 = np.zeros(6)
        self._f6 = np.zeros(6)
        self._index = {g: i for i, g in enumerate(info.tyre_geoms)}

    def forces(self, data: mujoco.MjData) -> tuple[np.ndarray, np.ndarray]:
        """(normal force (4,), tangential force magnitude (4,)) of the tyres fl, fr, rl, rr [N]."""
        n, ft = np.zeros(4), np.zeros(4)
        road = self.info.road_geom
        for c in range(data.ncon):
            con = data.contact[c]
            g = con.geom2 if con.geom1 == road else con.geom1
            i = self._index.get(g)
            if i is None:
                continue
            mujoco.mj_contactForce(self.model, data, c, self._f6)
            n[i] += self._f6[0]
            ft[i] += float(np.hypot(self._f6[1], self._f6[2]))
        return n, ft

    def static_on_cone(self, data: mujoco.MjData) -> bool:
        """Whether both rear tyres would be on their friction cones if the car stood still now.

        A static test with MuJoCo's friction (condim 3): velocities zeroed, one ``mj_forward``;
        the state is restored (the next ``mj_step`` recomputes everything from qpos/qvel).
        """
        m, geoms = self.model, list(self.info.rear_tyre_geoms)
        condim, qvel = m.geom_condim[geoms].copy(), data.qvel.copy()
        m.geom_condim[geoms] = 3
        data.qvel[:] = 0.0
        mujoco.mj_forward(m, data)
        n, ft = self.forces(data)
        m.geom_condim[geoms] = condim
        data.qvel[:] = qvel
        mujoco.mj_forward(m, data)
        mu = self.info.tyre_road_mu
        return bool(np.all(ft[2:] >= mu * n[2:] * (1.0 - STICK_EPS)))

    def rear_margin(self, data: mujoco.MjData) -> float:
        """Σμ_r·N / |ΣF_t| of the rear tyres (inf when they carry no friction): the axle's reserve."""
        n, ft = self.forces(data)
        carried = ft[2:].sum()
        return float(self.info.tyre_road_mu * n[2:].sum() / carried) if carried > 0 else np.inf

    def rear_slip(self, data: mujoco.MjData) -> np.ndarray:
        """(2, 3) world-frame slip velocity of the rear tyres' contact points (road-tangential part)."""
        nrm, r = self.info.road_normal, self.info.wheel_radius_m
        out = np.zeros((2, 3))
        for j, b in enumerate(self.info.rear_wheel_bodies):
            mujoco.mj_objectVelocity(self.model, data, _BODY, b, self._v6, 0)
            w, lin = self._v6[:3], self._v6[3:]
            a = -r * nrm                                   # hub → contact point
            v = lin + (w[1] * a[2] - w[2] * a[1], w[2] * a[0] - w[0] * a[2], w[0] * a[1] - w[1] * a[0])
            out[j] = v - (v @ nrm) * nrm
        return out


class TyrePhases:
    """Switches each rear tyre between the stick and the slide regime (module docstring)."""

    def __init__(self, model: mujoco.MjModel, info: ModelInfo, contacts: TyreContacts):
        self.model, self.info, self.contacts = model, info, contacts
        self.sliding = np.zeros(2, dtype=bool)
        self.first_slide_s: float | None = None
        self._normal = np.zeros(2)
        self._check_cone = True
        self._arm = -info.wheel_radius_m * info.road_normal

    @property
    def any_sliding(self) -> bool:
        return bool(self.sliding.any())

    def update(self, data: mujoco.MjData, capacity_Nm: np.ndarray) -> None:
        """Choose the rear tyres' regime (module docstring).

        The two rear tyres share the slope force; one of them on its friction cone while the
        other has reserve is a car at rest (statically indeterminate split), so the axle is
        the unit: it enters the slide regime when *both* rear tyres are on their cones
        (|F_t| ≥ μ_r·N within :data:`CONE_EPS`, MuJoCo's contact forces) or a contact point
        slips faster than :data:`SLIDE_ENTER_M_S` while its wheel does not roll along
        (|ω|·R < slip/2).  A wheel leaves it when its drum can no longer hold it against
        μ_r·N·R (N averaged over the last update's steps; clean in this regime); the axle
        leaves it when the slip is below :data:`SLIDE_REG_M_S` and MuJoCo's friction would
        hold the car at rest (:meth:`TyreContacts.static_on_cone`).
        """
        slip = np.linalg.norm(self.contacts.rear_slip(data), axis=1)
        mu, r = self.info.tyre_road_mu, self.info.wheel_radius_m
        if not self.sliding.any():
            # the cone test costs a contact-force read; needed at the start and once anything slips
            if not (self._check_cone or slip.max() > CONE_CHECK_M_S):
                return
            self._check_cone = False
            omega = np.abs(data.qvel[list(self.info.rear_dofs)])
            n, ft = self.contacts.forces(data)
            on_cone = bool(np.all((ft[2:] > 0) & (ft[2:] >= mu * n[2:] * (1.0 - CONE_EPS))))
            slipping = bool(np.any((slip > SLIDE_ENTER_M_S) & (omega * r < 0.5 * slip)))
            if on_cone or slipping:
                for j in (0, 1):
                    self._set(j, True, data.time)
                self._normal[:] = n[2:]
            return
        for j in (0, 1):
            if self.sliding[j] and self._normal[j] > 0 and capacity_Nm[j] < mu * self._normal[j] * r:
                self._set(j, False, data.time)
        if self.sliding.any() and np.all(slip < SLIDE_REG_M_S) and not self.contacts.static_on_cone(data):
            for j in (0, 1):
                self._set(j, False, data.time)
        if not self.sliding.any():
            self._check_cone = True

    def _set(self, j: int, sliding: bool, time_s: float) -> None:
        self.sliding[j] = sliding
        self.model.geom_condim[self.info.rear_tyre_geoms[j]] = 1 if sliding else 3
        if sliding and self.first_slide_s is None:
            self.first_slide_s = float(time_s)

    def _apply(self, data: mujoco.MjData, normal: np.ndarray, slip: np.ndarray) -> np.ndarray:
        """Write the Coulomb force of each sliding rear tyre into ``xfrc_applied``; return the slip speeds."""
        info = self.info
        speed = np.sqrt((slip * slip).sum(axis=1))
        for j in (0, 1):
            b = info.rear_wheel_bodies[j]
            if not self.sliding[j] or normal[j] <= 0.0 or speed[j] == 0.0:
                data.xfrc_applied[b] = 0.0
                continue
            f = -info.tyre_road_mu * normal[j] * slip[j] / max(speed[j], SLIDE_REG_M_S)
            a = self._arm                                  # hub (the wheel's centre of mass) → contact point
            data.xfrc_applied[b, :3] = f
            data.xfrc_applied[b, 3:] = (a[1] * f[2] - a[2] * f[1], a[2] * f[0] - a[0] * f[2], a[0] * f[1] - a[1] * f[0])
        return speed

    def step(self, data: mujoco.MjData, nstep: int) -> None:
        """*nstep* MuJoCo steps with the explicit Coulomb force on the sliding rear tyres.

        While every sliding tyre slips faster than :data:`SLIDE_FAST_M_S` the force (magnitude
        μ_r·N, direction of a slip that turns slowly) is held over :data:`SLIDE_HOLD_STEPS`
        steps, stepped in C; slower, near the regularised region, it is recomputed every step.
        """
        m = self.model
        total, done = np.zeros(2), 0
        while done < nstep:
            n = self.contacts.forces(data)[0][2:]
            speed = self._apply(data, n, self.contacts.rear_slip(data))
            k = min(SLIDE_HOLD_STEPS if np.all(speed[self.sliding] > SLIDE_FAST_M_S) else 1, nstep - done)
            mujoco.mj_step(m, data, nstep=k)
            total += k * n
            done += k
        self._normal[:] = total / nstep
        data.xfrc_applied[list(self.info.rear_wheel_bodies)] = 0.0
