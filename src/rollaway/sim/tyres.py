"""The tyre–road contacts: forces and slip read from MuJoCo, and the sliding phase.

Two regimes, switched per rear wheel by :class:`TyrePhases`:

* **stick** (MuJoCo's own friction): condim 3, elliptic cone, ``impratio``
  :data:`rollaway.sim.model.STICK_IMPRATIO`.  A high impratio keeps a held tyre's creep small
  (MuJoCo documentation, "Preventing slip"), but with it a *sliding* contact bounces: the
  convex contact model couples slip to separation, and a stiff friction regulariser makes the
  normal force chatter (rear tyres unloaded on most steps, spikes of 100× the static load),
  which saturates the brake and turns "locked" wheels.
* **slide** (Coulomb's law applied explicitly): once a rear tyre's contact point slips faster
  than :data:`SLIDE_ENTER_M_S` *and* its drum can hold the wheel against the full sliding
  friction (capacity > μ_r·N·R, so the wheel stays locked), that tyre's contact becomes
  frictionless (condim 1, MuJoCo keeps only the normal force) and the friction force
  F = −μ_r·N·v̂ (Coulomb; N the contact's normal force of the previous step, v̂ the slip
  direction of the contact point) is applied at the contact point every step.  Below
  :data:`SLIDE_REG_M_S` of slip the force is scaled by |v|/:data:`SLIDE_REG_M_S` (a viscous
  regularisation that keeps the explicit step stable: damping·dt/m_car < 1).  The tyre goes
  back to the stick regime when its slip falls below :data:`SLIDE_REG_M_S` or its drum can no
  longer hold the wheel (the wheel then spins up and the tyre regrips, a brake slip that
  MuJoCo's friction handles).

All thresholds [assumed]; measured effect in tests/sim/test_skid.py.
"""
from __future__ import annotations

import mujoco
import numpy as np

from rollaway.sim.model import STICK_IMPRATIO, ModelInfo

SLIDE_ENTER_M_S = 4e-3      # [assumed] contact slip that starts the slide regime (creep is ~1e-7 m/s)
SLIDE_REG_M_S = 2e-3        # [assumed] regularisation speed of the explicit friction; also the exit speed
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

    def cone_margin(self, data: mujoco.MjData) -> float:
        """Least μ_r·N/|F_t| over the loaded tyre contacts (inf when none carries friction)."""
        n, ft = self.forces(data)
        mu = self.model.geom_friction[list(self.info.tyre_geoms), 0]
        loaded = ft > 0
        if not loaded.any():
            return np.inf
        return float(np.min(mu[loaded] * n[loaded] / ft[loaded]))

    def rear_slip(self, data: mujoco.MjData) -> np.ndarray:
        """(2, 3) world-frame slip velocity of the rear tyres' contact points (road-tangential part)."""
        nrm, r = self.info.road_normal, self.info.wheel_radius_m
        out = np.zeros((2, 3))
        for j, b in enumerate(self.info.rear_wheel_bodies):
            mujoco.mj_objectVelocity(self.model, data, _BODY, b, self._v6, 0)
            v = self._v6[3:] + np.cross(self._v6[:3], -r * nrm)
            out[j] = v - (v @ nrm) * nrm
        return out


class TyrePhases:
    """Switches each rear tyre between the stick and the slide regime (module docstring)."""

    def __init__(self, model: mujoco.MjModel, info: ModelInfo, contacts: TyreContacts):
        self.model, self.info, self.contacts = model, info, contacts
        self.sliding = np.zeros(2, dtype=bool)
        self.first_slide_s: float | None = None
        self._normal = np.zeros(2)
        self._zero3 = np.zeros(3)

    @property
    def any_sliding(self) -> bool:
        return bool(self.sliding.any())

    def update(self, data: mujoco.MjData, capacity_Nm: np.ndarray) -> None:
        """Choose each rear tyre's regime from its slip and whether its drum can lock the wheel."""
        slip = np.linalg.norm(self.contacts.rear_slip(data), axis=1)
        n = self.contacts.forces(data)[0][2:]
        mu, r = self.info.tyre_road_mu, self.info.wheel_radius_m
        holds_wheel = capacity_Nm > mu * n * r
        for j in (0, 1):
            if not self.sliding[j] and slip[j] > SLIDE_ENTER_M_S and holds_wheel[j]:
                self._set(j, True, data.time)
            elif self.sliding[j] and (slip[j] < SLIDE_REG_M_S or not holds_wheel[j]):
                self._set(j, False, data.time)
        self._normal[:] = n

    def _set(self, j: int, sliding: bool, time_s: float) -> None:
        self.sliding[j] = sliding
        self.model.geom_condim[self.info.rear_tyre_geoms[j]] = 1 if sliding else 3
        if sliding and self.first_slide_s is None:
            self.first_slide_s = float(time_s)

    def step(self, data: mujoco.MjData, nstep: int) -> None:
        """*nstep* MuJoCo steps with the explicit Coulomb force on the sliding rear tyres."""
        m, info = self.model, self.info
        mu, r, nrm = info.tyre_road_mu, info.wheel_radius_m, info.road_normal
        for _ in range(nstep):
            data.qfrc_applied[:] = 0.0
            n = self.contacts.forces(data)[0][2:]
            slip = self.contacts.rear_slip(data)
            for j in np.nonzero(self.sliding)[0]:
                speed = float(np.linalg.norm(slip[j]))
                if n[j] <= 0.0 or speed == 0.0:
                    continue
                force = -mu * n[j] * slip[j] / max(speed, SLIDE_REG_M_S)
                b = info.rear_wheel_bodies[j]
                mujoco.mj_applyFT(m, data, force, self._zero3, data.xpos[b] - r * nrm, b, data.qfrc_applied)
            mujoco.mj_step(m, data)
        data.qfrc_applied[:] = 0.0

    def reset(self) -> None:
        for j in (0, 1):
            self.model.geom_condim[self.info.rear_tyre_geoms[j]] = 3
        self.sliding[:] = False
        self.model.opt.impratio = STICK_IMPRATIO
