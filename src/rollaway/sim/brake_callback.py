"""The drum parking brake as a time-varying static-friction capacity of the rear wheel hinges.

Each rear wheel gets one drum (the hand lever drives both through an equaliser, eq. 24 is
per drum), so its hinge's ``dof_frictionloss`` is the torque of one drum, eq. (17b):
T_gen(t) = μ_d · F_l(t) · r_d with F_l from eqs. (16a/b), (18)–(21), (24) and the drum
temperature from the cooling law, eq. (10) — all from the scenario's drum model
(:meth:`rollaway.model.drum_model.DrumModel.evaluate`, effects included), so the simulated car feels
whatever the model knows (e.g. a calibrated clamp-force loss).

Direction (eqs. 18–21): the shoe's self-energising depends on the sense of the torque the
brake resists.  A wheel driven *forward* (positive hinge rotation about the car's +y axis,
what gravity does to a car facing downhill) gets the eq. (18) capacity (``"downhill"``), a
wheel driven backward the eq. (19) capacity (``"uphill"``).  Per wheel and per update the
driven sense is the sign of the wheel speed when it turns (|ω| > :data:`OMEGA_TURNING_RAD_S`),
otherwise the opposite of the sign of the hinge's friction-constraint force (what the brake
is resisting at rest).

Update period: the capacity is written every :data:`UPDATE_STEPS` MuJoCo steps (20 ms at the
1 ms step [assumed]); the drum model changes on the cooling time scale τ ≈ 1000 s, so the
capacity changes by < 0.003 % between updates.  The torque series is precomputed on the
update grid (vectorised drum model), so an update costs one array lookup.
"""
from __future__ import annotations

import mujoco
import numpy as np

from rollaway.errors import UserError
from rollaway.hold import validate_hand_force
from rollaway.hold.scenario import Scenario
from rollaway.sim.model import ModelInfo

UPDATE_STEPS = 20                 # MuJoCo steps between brake updates [assumed]
OMEGA_TURNING_RAD_S = 1e-3        # a wheel turning faster than this is "driven" in its sense of rotation
_FRICTION_DOF = int(mujoco.mjtConstraint.mjCNSTR_FRICTION_DOF)


CHUNK_UPDATES = 180_000           # torque series computed per hour of simulated time (20 ms grid), bounded memory


class BrakeController:
    """Precomputed drum torque on the update grid; writes the rear hinges' frictionloss.

    ``torque_Nm`` (2, n) and ``time_s`` (n,) hold the series on the update grid for updates
    ``k0 .. k0 + n − 1`` (a chunk of :data:`CHUNK_UPDATES`, or the whole horizon when
    ``chunk_updates`` is None); :meth:`torque` and :meth:`first_below` walk the chunks, so a
    week-long run needs a few MB, not GB.
    """

    def __init__(self, scenario: Scenario, info: ModelInfo, model: mujoco.MjModel, horizon_s: float,
                 chunk_updates: int | None = CHUNK_UPDATES):
        self.info = info
        self.scenario = scenario
        self.period_s = UPDATE_STEPS * model.opt.timestep
        self.n_updates = int(np.ceil(horizon_s / self.period_s)) + 2
        self.chunk = self.n_updates if chunk_updates is None else int(chunk_updates)
        self._force = float(validate_hand_force(scenario.hand_force_N))
        self.k0 = -1
        self._load(0)
        # driven sense per rear wheel: +1 forward.  Gravity drives a car facing downhill forward.
        start = 1 if info.facing == "downhill" else -1
        self.sense = np.array([start, start], dtype=int)
        self._dofs = np.array(info.rear_dofs)

    def _load(self, k: int) -> None:
        """Compute the chunk of the torque series that holds update *k*."""
        k0 = (k // self.chunk) * self.chunk
        if k0 == self.k0:
            return
        self.k0 = k0
        self.time_s = (k0 + np.arange(min(self.chunk, self.n_updates - k0))) * self.period_s
        p, force, scenario = self.scenario.params, self._force, self.scenario
        fwd = scenario.model.evaluate(self.time_s, force, "downhill")   # eq. (18), effects included
        rev = scenario.model.evaluate(self.time_s, force, "uphill")     # eq. (19)
        for name, series in (("downhill", fwd), ("uphill", rev)):
            if np.any(series.self_locked):
                raise UserError(f"{scenario.source or scenario.name}: the shoe self-locks when driven {name} with "
                                f"mu_drum = {p.mu_drum:g} (l_f − μ_d·l_fr ≤ 0, eqs. 18–21): the 1D model has no "
                                f"finite torque to simulate; lower mu_drum")
        # torque[0] when driven backward (eq. 19), torque[1] when driven forward (eq. 18)
        self.torque_Nm = np.stack([rev.torque_Nm, fwd.torque_Nm])
        if not np.all(np.isfinite(self.torque_Nm)):
            raise UserError(f"{scenario.source or scenario.name}: the drum torque is not finite (hand_force_N = "
                            f"{force:g}, mu_drum = {p.mu_drum:g}); give a physical hand force and drum friction")
        self.drum_temp_C = fwd.drum_temp_C

    def index(self, time_s: float) -> int:
        return min(int(round(time_s / self.period_s)), self.n_updates - 1)

    def torque(self, k: int, sense=None) -> np.ndarray:
        """Per-wheel drum torque at update *k* for the driven *sense* (default: the current one)."""
        s = self.sense if sense is None else np.asarray(sense)
        self._load(k)
        return self.torque_Nm[(s > 0).astype(int), k - self.k0]

    capacity_Nm = torque

    def drum_temp(self, k: int) -> float:
        self._load(k)
        return float(self.drum_temp_C[k - self.k0])

    def first_below(self, k_from: int, k_to: int, level_Nm: float) -> int:
        """First update in [k_from, k_to) at which the summed torque of both wheels (current
        sense) is below *level_Nm*, or *k_to*; ``least_Nm`` is the least summed torque before it."""
        rows = (self.sense > 0).astype(int)
        k, least = k_from, np.inf
        while k < k_to:
            self._load(k)
            stop = min(k_to, self.k0 + len(self.time_s))
            total = self.torque_Nm[rows, k - self.k0:stop - self.k0].sum(axis=0)
            below = np.nonzero(total < level_Nm)[0]
            end = int(below[0]) if below.size else total.size
            if end:
                least = min(least, float(total[:end].min()))
            if below.size:
                self.least_Nm = least
                return k + end
            k = stop
        self.least_Nm = least
        return k_to

    def friction_force(self, data: mujoco.MjData) -> np.ndarray:
        """Force of each rear hinge's friction constraint row (0 when the row is absent)."""
        nefc = data.nefc
        # fast path: with no equality constraints the dof-friction rows come first, in dof order
        if nefc >= 2 and data.efc_type[0] == _FRICTION_DOF and data.efc_type[1] == _FRICTION_DOF \
                and data.efc_id[0] == self._dofs[0] and data.efc_id[1] == self._dofs[1]:
            return data.efc_force[:2].copy()
        out = np.zeros(2)
        for r in np.nonzero(data.efc_type[:nefc] == _FRICTION_DOF)[0]:
            j = np.nonzero(self._dofs == data.efc_id[r])[0]
            if j.size:
                out[j[0]] = data.efc_force[r]
        return out

    def update(self, model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
        """Set the rear frictionloss for the current time; return the per-wheel capacity [N·m]."""
        omega = data.qvel[self._dofs]
        force = self.friction_force(data)
        for i in (0, 1):
            if abs(omega[i]) > OMEGA_TURNING_RAD_S:
                self.sense[i] = 1 if omega[i] > 0 else -1
            elif force[i] != 0.0:
                self.sense[i] = -1 if force[i] > 0 else 1
        cap = self.torque(self.index(data.time))
        model.dof_frictionloss[self._dofs] = cap
        return cap
