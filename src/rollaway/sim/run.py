"""``simulate(scenario)``: the MuJoCo car held by the drum brake, fixed-step or event-driven.

Both modes integrate the same compiled car (:func:`rollaway.sim.model.build_model`) with
the same 1 ms step and the same brake update every 20 ms
(:class:`rollaway.sim.brake_callback.BrakeController`); MuJoCo is stepped in C,
``mj_step(m, d, nstep=20)`` between brake updates.  Both stop at the scenario's duration,
or after the classification window that follows a roll-away (:mod:`rollaway.sim.outcome`).

``mode="fixed"``: the plain reference, every step of the span is integrated.

``mode="fast"``: the same, plus an honest event-driven skip.  Every
:data:`REST_CHECK_UPDATES` updates the car is tested for rest: over the last window its
speed along the slope stays below :data:`REST_SPEED_M_S` and the rear wheels turn slower
than :data:`REST_OMEGA_RAD_S` (so neither the brake nor the tyres slide).  At rest the
static problem is fully determined by what the rear hinges carry: the torque τ_i each
hinge's friction constraint transmits (read from MuJoCo, not assumed).  Nothing but the
brake capacity changes while the car stands, so as long as the drum torque of every
wheel, for the sense it is driven, stays ≥ τ_i·(1 + :data:`SKIP_MARGIN`) the car provably
stays at rest; time jumps (the state is kept) to the first brake update at which the
precomputed drum series falls below that level, and MuJoCo takes over again around the
crossing.  The tyres are never skipped over: a car whose tyres slide is not at rest.
The last :data:`REST_CHECK_UPDATES` updates of a hold are always integrated.
What is not integrated in a skip is the solver's creep (< 1 mm per hour, see tests), so
``creep_m`` of a fast run covers only the integrated spans.
"""
from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, fields
from pathlib import Path

import mujoco
import numpy as np

from rollaway.jsonsafe import to_jsonable
from rollaway.hold import time_to_slip_s, tyre_adhesion_margin
from rollaway.errors import check_choice
from rollaway.scenario import Scenario
from rollaway.sim import outcome as oc
from rollaway.sim.brake_callback import UPDATE_STEPS, BrakeController
from rollaway.sim.model import ModelInfo, build_model

MODES = ("fast", "fixed")
REST_CHECK_UPDATES = 25          # rest test every 0.5 s (25 updates of 20 ms) [assumed]
REST_SPEED_M_S = 1e-4            # [assumed] creep is ~1e-7 m/s; a slipping car exceeds this within 0.5 s
REST_OMEGA_RAD_S = 1e-3          # [assumed]
SKIP_MARGIN = 2e-3               # [assumed] 2× the measured hold/slip threshold error (< 0.1 %)
MIN_SKIP_UPDATES = 50            # skip only if it saves ≥ 1 s


@dataclass
class Trace:
    """What happened: one record per brake update (20 ms of simulated time) plus one per skip."""

    time_s: np.ndarray                # (n,)
    qpos: np.ndarray                  # (n, nq)
    qvel: np.ndarray                  # (n, nv)
    capacity_Nm: np.ndarray           # (n, 2) per-wheel capacity in effect until the next record
    sense: np.ndarray                 # (n, 2) driven sense per rear wheel (+1 forward, eq. 18; −1 eq. 19)
    displacement_m: np.ndarray        # (n,) along the slope, + downhill, from the t = 0 position
    speed_m_s: np.ndarray             # (n,) along the slope, + downhill
    wheel_angle_rad: np.ndarray       # (n,) mean rear hinge angle, + forward rotation
    skips: list                       # [(from_s, to_s)] spans jumped over at rest (fast mode)


@dataclass(frozen=True)
class SimResult:
    """Verdict of one simulated scenario (see :mod:`rollaway.sim.outcome` for the criteria)."""

    scenario: str
    mode: str
    outcome: str                        # held | brake_slip | tyre_skid
    rollaway_time_s: float | None       # None if held
    max_displacement_m: float           # max |travel along the slope| over the run
    creep_m: float                      # max |travel| before roll-away while capacity ≥ demand (integrated spans)
    min_margin: float                   # min over time of capacity/demand (rear axle)
    capacity_Nm_at_rollaway: float | None   # rear-axle brake capacity at the roll-away (None if held)
    demand_Nm_at_rollaway: float | None     # T_req, eq. (23) (None if held)
    slip_ratio: float | None            # rear-wheel slip ratio after the roll-away
    demand_Nm: float                    # T_req at the rear axle, eq. (23)
    analytic_time_to_slip_s: float | None   # brake-only prediction (rollaway.hold), None if it holds
    tyre_adhesion_margin: float         # analytic μ_r N_r / (m g sin θ)
    sim_time_s: float                   # simulated time span covered
    integrated_time_s: float            # of which MuJoCo integrated (fast mode skips the rest)
    wall_time_s: float
    drum_temp_C_end: float
    trace: Trace | None = field(repr=False, compare=False, default=None)

    def to_dict(self) -> dict:
        d = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "trace"}
        return to_jsonable(d)

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import sim_result_html
        return sim_result_html(self)


def _margin(capacity_Nm: float, demand_Nm: float) -> float:
    """Brake margin capacity/demand; ∞ on a flat road (no demand; reported as None in JSON)."""
    return capacity_Nm / demand_Nm if demand_Nm > 0 else np.inf


class _Run:
    def __init__(self, scenario: Scenario, mode: str):
        self.wall0 = time.perf_counter()          # wall time includes building the model
        self.scenario, self.mode = scenario, mode
        self.model, self.info = build_model(scenario)
        self.data = mujoco.MjData(self.model)
        horizon = scenario.duration_s + oc.POST_ROLLAWAY_S + 1.0
        self.ctrl = BrakeController(scenario, self.info, self.model, horizon)
        mujoco.mj_forward(self.model, self.data)
        i: ModelInfo = self.info
        self.pos = slice(i.car_qpos_adr, i.car_qpos_adr + 3)
        self.lin = slice(i.car_dof_adr, i.car_dof_adr + 3)
        self.p0 = self.data.qpos[self.pos].copy()
        self.rear_q = [int(self.model.jnt_qposadr[self.model.dof_jntid[d]]) for d in i.rear_dofs]
        n = len(self.ctrl.time_s) + 2
        self.t = np.zeros(n)
        self.qpos = np.zeros((n, self.model.nq))
        self.qvel = np.zeros((n, self.model.nv))
        self.cap = np.zeros((n, 2))
        self.sense = np.zeros((n, 2), dtype=int)
        self.n = 0
        self.skips: list = []
        self.min_margin = np.inf
        self.integrated_updates = 0

    def _record(self, cap) -> float:
        """Store the state; return the displacement along the slope."""
        d, r = self.data, self.n
        self.t[r] = d.time
        self.qpos[r] = d.qpos
        self.qvel[r] = d.qvel
        self.cap[r] = cap
        self.sense[r] = self.ctrl.sense
        self.n += 1
        return float((d.qpos[self.pos] - self.p0) @ self.info.downhill_unit)

    def _at_rest(self) -> bool:
        w = slice(self.n - REST_CHECK_UPDATES, self.n)
        if w.start < 1:
            return False
        speed = self.qvel[w, self.lin] @ self.info.downhill_unit
        omega = self.qvel[w][:, list(self.info.rear_dofs)]
        return bool(np.max(np.abs(speed)) < REST_SPEED_M_S and np.max(np.abs(omega)) < REST_OMEGA_RAD_S)

    def trace(self) -> Trace:
        n, u = self.n, self.info.downhill_unit
        qpos = self.qpos[:n]
        return Trace(time_s=self.t[:n], qpos=qpos, qvel=self.qvel[:n], capacity_Nm=self.cap[:n],
                     sense=self.sense[:n],                      displacement_m=(qpos[:, self.pos] - self.p0) @ u, speed_m_s=self.qvel[:n, self.lin] @ u,
                     wheel_angle_rad=qpos[:, self.rear_q].mean(axis=1), skips=list(self.skips))

    def _skip_target(self, k: int, k_end: int) -> int:
        """Last update index up to which the drum holds every wheel's carried torque with margin."""
        carried = np.abs(self.ctrl.friction_force(self.data))
        torque = self.ctrl.torque_Nm[(self.ctrl.sense > 0).astype(int), k:k_end]     # (2, n)
        below = np.nonzero(np.any(torque < carried[:, None] * (1.0 + SKIP_MARGIN), axis=0))[0]
        return k + (int(below[0]) if below.size else k_end - k)

    def run(self) -> SimResult:
        m, d, ctrl, info = self.model, self.data, self.ctrl, self.info
        demand = info.demand_axle_Nm
        k_end = ctrl.index(self.scenario.duration_s)
        k_stop, k = k_end, 0
        self._record(ctrl.update(m, d))
        rollaway_k = None
        while k < k_stop:
            cap = ctrl.update(m, d)
            margin = _margin(cap[0] + cap[1], demand)
            if margin < self.min_margin:
                self.min_margin = margin
            mujoco.mj_step(m, d, nstep=UPDATE_STEPS)
            k += 1
            self.integrated_updates += 1
            s = abs(self._record(cap))
            if rollaway_k is None:
                if s >= oc.ROLLAWAY_DISPLACEMENT_M:
                    rollaway_k = k
                    k_stop = min(k + int(round(oc.POST_ROLLAWAY_S / ctrl.period_s)), len(ctrl.time_s) - 1)
                elif self.mode == "fast" and k % REST_CHECK_UPDATES == 0 and self._at_rest():
                    k = self._skip(k, k_end, demand)
            elif s >= oc.POST_ROLLAWAY_M:
                break
        return self._result(rollaway_k, time.perf_counter() - self.wall0)

    def _skip(self, k: int, k_end: int, demand: float) -> int:
        """Jump over the span in which the car provably stays at rest; return the new update index."""
        ctrl, d = self.ctrl, self.data
        target = min(self._skip_target(k, k_end), k_end - REST_CHECK_UPDATES)
        if target - k < MIN_SKIP_UPDATES:
            return k
        span = ctrl.torque_Nm[(ctrl.sense > 0).astype(int), k:target].sum(axis=0)
        self.min_margin = min(self.min_margin, _margin(float(span.min()), demand))
        self.skips.append((float(d.time), float(ctrl.time_s[target])))
        d.time = ctrl.time_s[target]
        self._record(ctrl.capacity_Nm(target))
        return target

    def _creep(self, tr: Trace, held_end: int) -> float:
        """Max |travel| before the roll-away while the brake capacity was ≥ the demand."""
        ok = tr.capacity_Nm[:held_end].sum(axis=1) >= self.info.demand_axle_Nm
        return float(np.max(np.abs(tr.displacement_m[:held_end][ok]))) if ok.any() else 0.0

    def _result(self, rollaway_k, wall_s) -> SimResult:
        tr = self.trace()
        sc, info, ctrl = self.scenario, self.info, self.ctrl
        t, x = tr.time_s, tr.displacement_m
        t_roll = oc.crossing_time(t, x, oc.ROLLAWAY_DISPLACEMENT_M) if rollaway_k is not None else None
        if t_roll is not None and t_roll > sc.duration_s:
            t_roll = None
        slip = cap_roll = dem_roll = None
        held_end = len(t)
        if t_roll is not None:
            held_end = max(int(np.searchsorted(t, t_roll)), 1)
            slip = oc.slip_ratio(x, tr.wheel_angle_rad, info.wheel_radius_m, info.facing == "downhill",
                                 held_end - 1)
            cap_roll = float(tr.capacity_Nm[held_end - 1].sum())
            dem_roll = info.demand_axle_Nm
        t_slip = float(time_to_slip_s(sc.model, sc.hand_force_N, info.grade_pct, info.facing, sc.occupants,
                                      horizon_s=sc.duration_s))
        return SimResult(
            scenario=sc.name, mode=self.mode, outcome=oc.classify(t_roll is not None, slip or 0.0),
            rollaway_time_s=t_roll, max_displacement_m=float(np.max(np.abs(x))),
            creep_m=self._creep(tr, held_end), min_margin=float(self.min_margin),
            capacity_Nm_at_rollaway=cap_roll, demand_Nm_at_rollaway=dem_roll, slip_ratio=slip,
            demand_Nm=info.demand_axle_Nm, analytic_time_to_slip_s=None if np.isnan(t_slip) else t_slip,
            tyre_adhesion_margin=float(tyre_adhesion_margin(sc.params, info.grade_pct, info.facing, sc.occupants)),
            sim_time_s=float(t[-1]), integrated_time_s=self.integrated_updates * ctrl.period_s,
            wall_time_s=wall_s, drum_temp_C_end=float(ctrl.drum_temp_C[ctrl.index(t[-1])]), trace=tr)


def simulate(scenario: Scenario, *, render: str | Path | None = None, mode: str = "fast",
             render_options: dict | None = None) -> SimResult:
    """Simulate *scenario* in MuJoCo; optionally render it to *render* (.mp4, .gif or .png).

    *render_options*: keyword arguments of :func:`rollaway.sim.render.render_run` (size, fps,
    after_s, multisample).

    ``mode="fast"``: event-driven skip while provably at rest; ``"fixed"``: plain fixed-step.
    ``wall_time_s`` covers building the model and simulating, not the rendering.
    """
    check_choice(mode, MODES, "simulation mode")
    if render is not None:
        from rollaway.sim.render import check_render_path
        check_render_path(render)
    runner = _Run(scenario, mode)
    result = runner.run()
    if render is not None:
        from rollaway.sim.render import render_run
        render_run(runner, result, render, **{k: v for k, v in (render_options or {}).items() if v is not None})
    return result
