"""``simulate(scenario)``: the MuJoCo car held by the drum brake, fixed-step or event-driven.

Both modes integrate the same car (:func:`rollaway.sim.model.car_model`, compiled once per
structure and reconfigured per scenario) with the same 1 ms step and the same brake update
every 20 ms (:class:`rollaway.sim.brake_callback.BrakeController`); MuJoCo is stepped in C,
``mj_step(m, d, nstep=20)`` between brake updates, except while a rear tyre slides
(:mod:`rollaway.sim.tyres`: explicit Coulomb friction, one step at a time).

**Settled start**: the car is placed, then relaxed into static equilibrium with the brake
locked (:data:`SETTLE_STEPS` steps, velocities zeroed after each), so the contacts and
constraint forces are warm at t = 0 and nothing kicks the car; travel is measured from there.

``mode="fixed"``: the plain reference, every step of the span is integrated.

``mode="fast"``: the same, plus an honest event-driven skip.  Every :data:`REST_CHECK_UPDATES`
updates the car is tested for rest: over the last window its speed along the slope stays
below :data:`REST_SPEED_M_S`, the rear wheels turn slower than :data:`REST_OMEGA_RAD_S`, and
the rear tyres hold with margin (Σμ_r·N/|ΣF_t| ≥ 1 + :data:`SKIP_MARGIN`, from MuJoCo's
contact forces; the front wheels roll freely and carry no slope force), so neither brake nor tyres slide.  At
rest the static problem is fully determined by what the rear hinges carry (Στ, read from
MuJoCo): the tyres' loads do not change while the car stands, only the brake capacity does,
and MuJoCo's friction-loss constraint sticks while what it must transmit is below its bound.
So while the summed drum torque (for the sense each wheel is driven) stays ≥ Στ·(1 +
:data:`SKIP_MARGIN`) the car provably stays at rest, and time jumps (state kept) to the last
such update, next to the crossing; MuJoCo integrates the crossing.  What a skip does not integrate is the solver's creep
(< 1 mm per hour), so ``creep_m`` of a fast run covers only the integrated spans.

**Classification window**: after a roll-away the run goes on until the slip ratio is
unambiguous (:meth:`_Run._classified`; ``full_window=True`` always runs the whole window of
:mod:`rollaway.sim.outcome`).  **End of run**: a run that reaches its duration with the car
moving, a tyre sliding or the brake saturated is a roll-away at the motion's onset, status
``rolling_at_end``; a car held although the brake margin fell below 1 (within the solver's
threshold error) is ``held`` with status ``held_at_limit``.  **Divergence**
(:mod:`rollaway.sim.divergence`): outcome ``diverged`` with ``diverged_reason``.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, fields
from pathlib import Path

import mujoco
import numpy as np

from rollaway.errors import check_choice
from rollaway.hold import time_to_slip_s, tyre_adhesion_margin
from rollaway.jsonsafe import to_jsonable
from rollaway.hold.scenario import Scenario
from rollaway.sim import outcome as oc
from rollaway.sim.brake_callback import UPDATE_STEPS, BrakeController
from rollaway.sim.divergence import DivergenceGuard
from rollaway.sim.model import build_model, car_model, check_constants
from rollaway.sim.trace import DECIMATE_UPDATES, Recorder, Trace
from rollaway.sim.tyres import TyreContacts, TyrePhases

MODES = ("fast", "fixed")
STATUSES = ("ok", "rolling_at_end", "held_at_limit", "diverged")
EXIT_DIVERGED = 3                # `rollaway simulate` exit code of a diverged run
REST_CHECK_UPDATES = 10          # rest test every 0.2 s (10 updates of 20 ms) [assumed]
REST_SPEED_M_S = 1e-4            # [assumed] creep is ~1e-7 m/s; the skip proof itself is the force margins
REST_OMEGA_RAD_S = 1e-3          # [assumed]
SKIP_MARGIN = 2e-4               # [assumed] capacity over the measured carried torque kept when jumping
TYRE_SKIP_MARGIN = 1e-3          # [assumed] rear tyres' friction reserve required to skip
MIN_SKIP_UPDATES = 50            # skip only if it saves ≥ 1 s
SETTLE_STEPS = 150               # [assumed] relaxation steps before t = 0 (contact time constant 4 ms)
LOCK_NM = 1e7                    # brake torque that locks the wheels while settling
MAX_SETTLE_M = 0.01              # [assumed] settling sinks the car ~0.1 mm; more means the contacts fail
MIN_WINDOW_UPDATES = 10          # classification: at least 0.2 s after the roll-away [assumed]
MIN_WINDOW_M = 0.02              # ... and 2 cm more travel [assumed]
CLEAR_SLIP = 0.1                 # slip ratio within 0.1 of 0 or 1 (full and latter half) is unambiguous [assumed]


@dataclass(frozen=True)
class SimResult:
    """Verdict of one simulated scenario (see :mod:`rollaway.sim.outcome` for the criteria).

    Attributes
    ----------
    outcome : str
        ``held``, ``brake_slip`` (the wheels turn), ``tyre_skid`` (a rear tyre slides) or ``diverged``.
    rollaway_time_s : float or None
        When the car had moved more than 5 cm along the slope [s]; None if held.
    max_displacement_m : float
        Largest travel along the slope over the run [m].
    min_margin : float
        Least rear-drum capacity / demand T_req (eq. 23) over the run [–].
    demand_Nm : float
        T_req at the rear axle [N·m].
    analytic_time_to_slip_s : float or None
        The analytic check's brake slip time [s] (:func:`rollaway.hold`), None if it holds.
    tyre_adhesion_margin : float
        Analytic μ_r·N_r / (m g sin θ) [–].
    drum_temp_C_end : float
        Drum temperature at the end [°C].
    status : str
        ``ok``, ``rolling_at_end``, ``held_at_limit`` or ``diverged`` (docs: the simulator).
    wall_time_s : float
        Wall time of building and simulating [s] (not rendering).
    trace : Trace
        The recorded run: ``time_s``, ``displacement_m``, ``speed_m_s``, ``capacity_Nm`` (per rear wheel), ...
    """

    scenario: str
    mode: str
    outcome: str                        # held | brake_slip | tyre_skid | diverged
    rollaway_time_s: float | None       # None if held (or diverged)
    max_displacement_m: float           # max |travel along the slope| over the run
    creep_m: float                      # max |travel| before roll-away while capacity ≥ demand (integrated spans)
    min_margin: float                   # min over time of capacity/demand (rear axle)
    capacity_Nm_at_rollaway: float | None   # rear-axle brake capacity at the roll-away (None if held)
    demand_Nm_at_rollaway: float | None     # T_req, eq. (23) (None if held)
    slip_ratio: float | None            # rear-wheel slip ratio after the roll-away (mean of both wheels)
    demand_Nm: float                    # T_req at the rear axle, eq. (23)
    analytic_time_to_slip_s: float | None   # brake-only prediction (rollaway.hold), None if it holds
    tyre_adhesion_margin: float         # analytic μ_r N_r / (m g sin θ)
    sim_time_s: float                   # simulated time span covered
    integrated_time_s: float            # of which MuJoCo integrated (fast mode skips the rest; includes trials)
    wall_time_s: float
    drum_temp_C_end: float
    status: str = "ok"                  # ok | rolling_at_end | held_at_limit | diverged
    diverged_reason: str | None = None
    tyre_slide_s: float | None = None   # when a rear tyre first entered the slide regime
    wheel_slip_ratios: tuple | None = None  # (left, right) rear slip ratios; the larger decides tyre_skid
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
    def __init__(self, scenario: Scenario, mode: str, *, physics_only: bool = True, full_window: bool = False,
                 gravity_tilt_rad: float = 0.0):
        self.wall0 = time.perf_counter()          # wall time includes building the model
        self.scenario, self.mode, self.full_window = scenario, mode, full_window
        self.model, self.info = (car_model(scenario, gravity_tilt_rad=gravity_tilt_rad) if physics_only
                                 else build_model(scenario))
        self.data = mujoco.MjData(self.model)
        horizon = scenario.duration_s + oc.POST_ROLLAWAY_S + 1.0
        self.ctrl = BrakeController(scenario, self.info, self.model, horizon,
                                    **({} if physics_only else {"chunk_updates": None}))
        self.contacts = TyreContacts(self.model, self.info)
        self.phases = TyrePhases(self.model, self.info, self.contacts)
        i = self.info
        self.pos = slice(i.car_qpos_adr, i.car_qpos_adr + 3)
        self.lin = slice(i.car_dof_adr, i.car_dof_adr + 3)
        self.rear = list(i.rear_dofs)
        self.rear_q = [int(self.model.jnt_qposadr[self.model.dof_jntid[d]]) for d in i.rear_dofs]
        self._settle()
        self.p0 = self.data.qpos[self.pos].copy()
        self.guard = DivergenceGuard(self.data, scenario.params.gravity_m_s2, i.theta_rad)
        self.rec = Recorder(self.model.nq, self.model.nv)
        self.skips: list = []
        self.min_margin = np.inf
        self.integrated_updates = 0
        self._rest_max = np.zeros(2)              # max |speed|, max |ω| since the last rest check

    def _settle(self) -> None:
        """Relax the placed car into static equilibrium with the brake locked; t = 0 afterwards."""
        m, d = self.model, self.data
        check_constants(m, self.info)
        self.ctrl.update(m, d)
        m.dof_frictionloss[self.rear] = LOCK_NM
        placed = d.qpos[self.pos].copy()
        guard = DivergenceGuard(d, self.scenario.params.gravity_m_s2, self.info.theta_rad)
        for _ in range(SETTLE_STEPS):
            mujoco.mj_step(m, d)
            d.qvel[:] = 0.0
        sink = float((d.qpos[self.pos] - placed) @ self.info.road_normal)
        self.diverged = guard.check(d, 0.0, 0.0, 0.0)
        if self.diverged is None and abs(sink) > MAX_SETTLE_M:
            self.diverged = (f"settling moved the car {sink:+.3g} m along the road normal (the contacts cannot "
                             f"carry it; at most {MAX_SETTLE_M} m is plausible)")
        d.time = 0.0
        mujoco.mj_forward(m, d)

    def _travel(self) -> tuple[float, float, float]:
        """(displacement along the slope, speed along the slope, offset along the road normal)."""
        d, u = self.data, self.info.downhill_unit
        dp = d.qpos[self.pos] - self.p0
        return float(dp @ u), float(d.qvel[self.lin] @ u), float(dp @ self.info.road_normal)

    def _record(self, cap) -> None:
        d = self.data
        self.rec.append(d.time, d.qpos, d.qvel, cap, self.ctrl.sense)

    def _advance(self, cap) -> None:
        """One brake update's worth of steps in the current tyre regime."""
        self.phases.update(self.data, cap)
        if self.phases.any_sliding:
            self.phases.step(self.data, UPDATE_STEPS)
        else:
            mujoco.mj_step(self.model, self.data, nstep=UPDATE_STEPS)

    def run(self) -> SimResult:
        m, d, ctrl, info = self.model, self.data, self.ctrl, self.info
        demand = info.demand_axle_Nm
        k_end = ctrl.index(self.scenario.duration_s)
        k_stop, k = k_end, 0
        cap = ctrl.update(m, d)
        self._record(cap)
        rollaway_k = rollaway_rec = None
        if self.diverged:
            k_stop = 0
        while k < k_stop:
            cap = ctrl.update(m, d)
            if k < k_end:
                self.min_margin = min(self.min_margin, _margin(cap[0] + cap[1], demand))
            self._advance(cap)
            k += 1
            self.integrated_updates += 1
            x, v, z = self._travel()
            self.diverged = self.guard.check(d, x, v, z)
            if self.diverged:
                break
            omega = float(np.max(np.abs(d.qvel[self.rear])))
            self._rest_max = np.maximum(self._rest_max, [abs(v), omega])
            moving = abs(v) >= REST_SPEED_M_S or omega >= REST_OMEGA_RAD_S or self.phases.any_sliding
            if moving or rollaway_k is not None or k % DECIMATE_UPDATES == 0 or k >= k_stop:
                self._record(cap)
            if rollaway_k is None:
                if abs(x) >= oc.ROLLAWAY_DISPLACEMENT_M:
                    rollaway_k, rollaway_rec = k, self.rec.n - 1
                    k_stop = min(k + int(round(oc.POST_ROLLAWAY_S / ctrl.period_s)), ctrl.n_updates - 1)
                elif k % REST_CHECK_UPDATES == 0:
                    at_rest = bool(np.all(self._rest_max < [REST_SPEED_M_S, REST_OMEGA_RAD_S]))
                    self._rest_max[:] = 0.0
                    if self.mode == "fast" and at_rest and not self.phases.any_sliding:
                        k = self._skip(k, k_end, demand)
            elif abs(x) >= oc.POST_ROLLAWAY_M or (not self.full_window and self._classified(rollaway_k, rollaway_rec, k)):
                break
        return self._result(rollaway_k is not None, time.perf_counter() - self.wall0)

    # -- fast mode ---------------------------------------------------------------------------
    def _skip(self, k: int, k_end: int, demand: float) -> int:
        """Jump over the span in which the car provably stays at rest; return the new update index.

        At rest the rear hinges together carry Στ (MuJoCo's friction-constraint forces) and the
        rear tyres have friction reserve; only the drum capacity changes while the car stands.
        MuJoCo's friction-loss constraint sticks while the torque it must transmit is below its
        bound, so the car stays at rest while Σ capacity ≥ Στ·(1 + :data:`SKIP_MARGIN`) (the split
        between the wheels may shift; the axle total is what must be held).  Time jumps to the
        last such update, as close to the crossing as the margin allows.
        """
        ctrl, d = self.ctrl, self.data
        if self.contacts.rear_margin(d) < 1.0 + TYRE_SKIP_MARGIN:
            return k                                  # the tyres are at their limit: they may be sliding slowly
        carried = float(np.abs(ctrl.friction_force(d)).sum())
        target = min(ctrl.first_below(k, k_end, carried * (1.0 + SKIP_MARGIN)), k_end - REST_CHECK_UPDATES)
        if target - k < MIN_SKIP_UPDATES:
            return k
        self.min_margin = min(self.min_margin, _margin(ctrl.least_Nm, demand))
        self.skips.append((float(d.time), float(target * ctrl.period_s)))
        d.time = target * ctrl.period_s
        self._record(ctrl.torque(target))
        return target

    # -- classification ---------------------------------------------------------------------
    def _classified(self, rollaway_k: int, r0: int, k: int) -> bool:
        """True once each rear wheel's slip ratio since the roll-away (and over its latter half) is clearly 0 or 1."""
        if k - rollaway_k < MIN_WINDOW_UPDATES:
            return False
        x = self._series()[0]
        if abs(x[-1] - x[r0]) < MIN_WINDOW_M:
            return False
        half = (len(x) - r0) // 2
        for s_all, s_late in zip(self._wheel_slips(x, self.rec.view("qpos"), r0),
                                 self._wheel_slips(x, self.rec.view("qpos"), r0 + half)):
            if not (max(abs(s_all), abs(s_late)) < CLEAR_SLIP or min(s_all, s_late) > 1 - CLEAR_SLIP):
                return False
        return True

    def _wheel_slips(self, x: np.ndarray, qpos: np.ndarray, start: int) -> list[float]:
        """Slip ratio of each rear wheel from record *start* to the last (:func:`outcome.slip_ratio`)."""
        fwd, R = self.info.facing == "downhill", self.info.wheel_radius_m
        return [oc.slip_ratio(x, qpos[:, q], R, fwd, start) for q in self.rear_q]

    def _series(self) -> tuple[np.ndarray, np.ndarray]:
        qpos = self.rec.view("qpos")
        return (qpos[:, self.pos] - self.p0) @ self.info.downhill_unit, qpos[:, self.rear_q].mean(axis=1)

    def trace(self) -> Trace:
        x, phi = self._series()
        qvel = self.rec.view("qvel")
        return Trace(time_s=self.rec.view("t"), qpos=self.rec.view("qpos"), qvel=qvel,
                     capacity_Nm=self.rec.view("cap"), sense=self.rec.view("sense"), displacement_m=x,
                     speed_m_s=qvel[:, self.lin] @ self.info.downhill_unit, wheel_angle_rad=phi,
                     skips=list(self.skips))

    def _creep(self, tr: Trace, held_end: int) -> float:
        """Max |travel| before the roll-away while the brake capacity was ≥ the demand."""
        ok = tr.capacity_Nm[:held_end].sum(axis=1) >= self.info.demand_axle_Nm
        return float(np.max(np.abs(tr.displacement_m[:held_end][ok]))) if ok.any() else 0.0

    def _end_state(self, tr: Trace) -> tuple[str, int | None]:
        """Status of a run that reached its duration without a roll-away, and the motion's onset record."""
        d, ctrl = self.data, self.ctrl
        cap = tr.capacity_Nm[-1]
        carried = np.abs(ctrl.friction_force(d))
        saturated = bool(cap.sum() > 0 and carried.sum() >= cap.sum() * (1 - 1e-6)) or \
            _margin(float(cap.sum()), self.info.demand_axle_Nm) < 1.0
        moving = np.abs(tr.speed_m_s) >= REST_SPEED_M_S
        moving |= np.max(np.abs(tr.qvel[:, self.rear]), axis=1) >= REST_OMEGA_RAD_S
        if moving[-1] or saturated or self.phases.any_sliding:
            still = np.nonzero(~moving)[0]
            onset = int(still[-1]) + 1 if still.size else 0
            below = np.nonzero(tr.capacity_Nm.sum(axis=1) < self.info.demand_axle_Nm)[0]
            if below.size and (not moving[-1] or below[0] < onset):
                onset = int(below[0])
            return "rolling_at_end", min(onset, len(tr.time_s) - 1)
        if self.min_margin < 1.0:
            return "held_at_limit", None
        return "ok", None

    def _result(self, rolled: bool, wall_s) -> SimResult:
        tr = self.trace()
        sc, info, ctrl = self.scenario, self.info, self.ctrl
        t, x = tr.time_s, tr.displacement_m
        t_roll = oc.crossing_time(t, x, oc.ROLLAWAY_DISPLACEMENT_M) if rolled else None
        if t_roll is not None and t_roll > sc.duration_s:
            t_roll = None
        status, onset = "ok", None
        if self.diverged:
            status, t_roll = "diverged", None
        elif t_roll is None:
            status, onset = self._end_state(tr)
            if onset is not None:
                t_roll = float(t[onset])
        slip = cap_roll = dem_roll = wheel_slips = None
        held_end = len(t)
        if t_roll is not None:
            held_end = max(int(np.searchsorted(t, t_roll)), 1) if onset is None else max(onset, 1)
            wheel_slips = self._wheel_slips(x, tr.qpos, held_end - 1)
            slip = float(np.mean(wheel_slips))
            cap_roll = float(tr.capacity_Nm[held_end - 1].sum())
            dem_roll = info.demand_axle_Nm
        tyre_margin = float(tyre_adhesion_margin(sc.params, info.grade_pct, info.facing, sc.occupants))
        if slip is not None and not np.isfinite(slip):      # no travel yet: the lower limit gave way
            slip = 1.0 if tyre_margin < _margin(cap_roll, dem_roll) else 0.0
            wheel_slips = [slip, slip]
        t_slip = float(time_to_slip_s(sc.model, sc.hand_force_N, info.grade_pct, info.facing, sc.occupants,
                                      horizon_s=sc.duration_s))
        outcome = "diverged" if self.diverged else oc.classify(t_roll is not None, max(wheel_slips or [0.0]))
        return SimResult(
            scenario=sc.name, mode=self.mode, outcome=outcome,
            rollaway_time_s=t_roll, max_displacement_m=float(np.max(np.abs(x))),
            creep_m=self._creep(tr, held_end), min_margin=float(self.min_margin),
            capacity_Nm_at_rollaway=cap_roll, demand_Nm_at_rollaway=dem_roll, slip_ratio=slip,
            wheel_slip_ratios=None if wheel_slips is None else tuple(float(w) for w in wheel_slips),
            demand_Nm=info.demand_axle_Nm, analytic_time_to_slip_s=None if np.isnan(t_slip) else t_slip,
            tyre_adhesion_margin=tyre_margin,
            sim_time_s=float(t[-1]), integrated_time_s=self.integrated_updates * ctrl.period_s,
            wall_time_s=wall_s, drum_temp_C_end=ctrl.drum_temp(ctrl.index(t[-1])), status=status,
            diverged_reason=self.diverged, tyre_slide_s=self.phases.first_slide_s, trace=tr)


def simulate(scenario: Scenario, *, render: str | Path | None = None, mode: str = "fast",
             render_options: dict | None = None, full_window: bool = False) -> SimResult:
    """Simulate *scenario* in MuJoCo; optionally render it to *render* (.mp4, .gif or .png).

    *render_options*: keyword arguments of :func:`rollaway.sim.render.render_run` (size, fps,
    after_s, multisample).

    ``mode="fast"``: event-driven skip while provably at rest; ``"fixed"``: plain fixed-step.
    ``full_window``: run the whole classification window after a roll-away (default: stop
    once the mode is unambiguous).  ``wall_time_s`` covers building (or reconfiguring) the
    model and simulating, not the rendering.  A diverged run is not rendered.
    """
    check_choice(mode, MODES, "simulation mode")
    if render is not None:
        from rollaway.sim.render import check_render_path
        check_render_path(render)
    runner = _Run(scenario, mode, physics_only=render is None, full_window=full_window or render is not None)
    result = runner.run()
    if render is not None and result.outcome != "diverged":
        from rollaway.sim.render import render_run
        render_run(runner, result, render, **{k: v for k, v in (render_options or {}).items() if v is not None})
    return result
