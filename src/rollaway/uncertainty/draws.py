"""From fitted-parameter uncertainty to roll-away risk.

A calibrated :class:`~rollaway.model.drum_model.DrumModel` carries the covariance of its fitted values.
:func:`draw_values` samples N parameter vectors from the multivariate normal it defines,
truncated to each parameter's physical bounds (rejection, then clipping of what is left);
:func:`rollaway_risk` evaluates the hold check for every draw at once (the draws are one more
broadcast axis of the drum chain) and reports the probability that the car rolls away and
the 5/50/95 percentiles of the least brake margin and of the slip time.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.model.drum_parameters import LEGACY_FREE, NOT_DRAWN
from rollaway.errors import UserError
from rollaway.model.drum_model import DrumModel
from rollaway.uncertainty.direction import (carried_over, mixture_parts, untested_direction,
                                            untested_direction_factor)

MAX_REJECTION_ROUNDS = 50
PERCENTILES = (5.0, 50.0, 95.0)
NOT_SURE = 0.05              # a band that gives the other answer at least this probability makes a verdict unsure


def draw_values(model: DrumModel, n: int, seed: int | None = 0, marginal: bool = False) -> dict[str, np.ndarray]:
    """N draws of the fitted values from the model's covariance, within bounds: {name: (n,) array}.

    The covariance is taken conditional on the held parameters the bands do not draw
    (:data:`~rollaway.model.drum_parameters.NOT_DRAWN`: the installation gap, at the set's value) — in a tested
    direction the road margin follows the torque the data pin, not how it splits between μ_d and the gap.
    *marginal*: draw them too (a direction the bench did not test, where that split decides the torque)."""
    if model.covariance is None:
        raise UserError(f"model '{model.name}' has no [covariance]; save a fitted model with 'rollaway fit DATA "
                        f"--save-model FILE.toml' (or add a [covariance] table) to use --uncertainty")
    if not (isinstance(n, (int, np.integer)) and 1 <= n <= 1_000_000):
        raise UserError(f"--uncertainty {n} must be a whole number of draws from 1 to 1000000, e.g. 1000")
    c = model.covariance if marginal else model.covariance.conditional(NOT_DRAWN)
    fitted = model.fitted_values()
    mean = np.array([fitted[k] for k in c.names], float)
    lo = np.array([model.bounds(k)[0] for k in c.names])
    hi = np.array([model.bounds(k)[1] for k in c.names])
    rng = np.random.default_rng(seed)
    sd = np.sqrt(np.clip(np.diag(c.matrix), 0.0, None))
    corr = c.matrix / np.outer(np.where(sd > 0, sd, 1.0), np.where(sd > 0, sd, 1.0))
    try:       # factor the correlation: variances of 1e-17 and 1e3 in one matrix would lose the small ones to rounding
        w, v = np.linalg.eigh(0.5 * (corr + corr.T))
    except np.linalg.LinAlgError:
        raise UserError(f"model '{model.name}': its covariance cannot be factored (not finite or not a covariance); "
                        f"save the model again with 'rollaway fit --save-model'") from None
    root = v * np.sqrt(np.clip(w, 0.0, None))

    def normal(size):
        return mean + (rng.standard_normal((size, len(mean))) @ root.T) * sd

    out = np.empty((n, len(mean)))
    todo = np.arange(n)
    for _ in range(MAX_REJECTION_ROUNDS):
        x = normal(todo.size)
        ok = np.all((x >= lo) & (x <= hi), axis=1)
        out[todo[ok]] = x[ok]
        todo = todo[~ok]
        if todo.size == 0:
            break
    if todo.size:                      # the mean sits at a bound: clip the rest
        out[todo] = np.clip(normal(todo.size), lo, hi)
    return {k: out[:, i] for i, k in enumerate(c.names)}


@dataclass(frozen=True)
class Risk:
    """Roll-away risk of one case under parameter uncertainty."""

    draws: int
    rollaway_probability: float
    least_margin_percentiles: dict[str, float]     # "p5", "p50", "p95" of min(brake least margin, tyre margin)
    brake_margin_percentiles: dict[str, float]     # of the brake's least margin alone
    slip_time_percentiles_s: dict[str, float | None]   # None: beyond the duration (holds)
    tyre_margin: float
    values: dict[str, np.ndarray]                  # the draws
    least_margin: np.ndarray                       # per draw of the calibrated model (alongside .values)
    slip_time_s: np.ndarray                        # per draw of the calibrated model (NaN: holds)
    detail: dict | None = None                     # shares of the band, beyond-the-data flags, models drawn

    @property
    def flags(self) -> list[str]:
        """Where the question lies beyond what the bench tested (the band was widened for it)."""
        return list((self.detail or {}).get("flags", []))

    @property
    def shares(self) -> dict[str, float]:
        """Each part's share of the band's variance: parameters, choice of effects, model error."""
        return dict((self.detail or {}).get("shares", {}))

    def as_dict(self) -> dict:
        return {"draws": self.draws, "rollaway_probability": self.rollaway_probability,
                "least_margin_percentiles": self.least_margin_percentiles,
                "brake_margin_percentiles": self.brake_margin_percentiles,
                "slip_time_percentiles_s": self.slip_time_percentiles_s, "tyre_margin": self.tyre_margin,
                **(self.detail or {})}

    def not_sure(self, holds: bool) -> str:
        """Words where the band gives the answer other than *holds* (the calibrated values') a probability of at
        least :data:`NOT_SURE`: ``"NOT SURE: roll-away probability 0.23 in the predictive band"``; else ``""``."""
        other = self.rollaway_probability if holds else 1.0 - self.rollaway_probability
        return (f"NOT SURE: {'roll-away' if holds else 'hold'} probability {other:.2f} in the predictive band"
                if other >= NOT_SURE else "")

    def band_words(self) -> str:
        """One line: the band's parts and what lies beyond the data."""
        sh = self.shares
        parts = ", ".join(f"{k.replace('_', ' ')} {v:.0%}" for k, v in sh.items()) if sh else "no spread"
        beyond = ("; BEYOND THE DATA: " + "; ".join(self.flags) + " (band widened)") if self.flags else ""
        if (self.detail or {}).get("carried_over"):
            beyond += ("; its torque carried over from the tested direction with the friction coefficient drawn "
                       "apart from mu_drum (one direction pins the torque scale only)")
        unseen = (self.detail or {}).get("unseen_hold_change", 0.0)
        if unseen > 0.0:
            from rollaway.uncertainty.predictive import HOLD_SD_CAP, hold_sd
            err = (self.detail or {}).get("hold_error_sd", min(hold_sd(unseen), HOLD_SD_CAP))
            others = [h for h in (self.detail or {}).get("hold_error_sd_sets", [])[1:] if abs(h - err) > 1e-3]
            span = (f"±{min(others):.1%}" + (f"–{max(others):.1%}" if max(others) - min(others) > 1e-3 else "")
                    if others else "")
            sets = f"; {span} for the competing effect sets, each by its own law" if others else ""
            beyond += (f"; after the bench's longest test the model's torque moves by up to {unseen:.0%} of what is "
                       f"left, unseen: that counts as an error of ±{err:.1%} (1σ{sets})")
        start = (self.detail or {}).get("start_decided", 0.0)
        if start > 0.0:
            beyond += (f"; the start of the hold decides {start:.0%} of the draws, which take the held-out error of "
                       "the tests' starts there too")
        return f"band from {parts}{beyond}"

    def _repr_html_(self) -> str:  # notebooks
        from rollaway.display import result_html
        rows = {"draws": self.draws, **{f"least margin {k}": v for k, v in self.least_margin_percentiles.items()},
                **{f"slip time {k} [s]": v for k, v in self.slip_time_percentiles_s.items()}}
        return result_html(f"roll-away probability {self.rollaway_probability:.3f}", rows,
                           self.rollaway_probability < 0.05)

    def draw_at_percentile(self, q: float) -> dict[str, float]:
        """The drawn values whose least margin is closest to its *q*-th percentile."""
        if not 0.0 <= q <= 100.0:
            raise UserError(f"percentile {q:g} must be within 0–100, e.g. 5 for a pessimistic draw")
        target = np.percentile(self.least_margin, q)
        i = int(np.argmin(np.abs(self.least_margin - target)))
        return {k: float(v[i]) for k, v in self.values.items()}


def _least_margins(model: DrumModel, n: int, seed, force_N: float, sign: float, t_req_Nm: np.ndarray,
                   initial_temp_C, duration_s: float, marginal: bool = False, carry: bool = False, start=None):
    """Parameter draws of *model* (none without a covariance; *marginal*: :func:`draw_values`), the margin function,
    each draw's least brake margin and the factor the start error put on it; *carry*: the torque carried over to
    the untested direction by :func:`untested_direction_factor`; *start*: (each draw's start error, the record's
    ``model_error_start``) on the torque at the start of the hold (:class:`rollaway.uncertainty.predictive.
    StartError`)."""
    from rollaway.hold import validate_hand_force
    from rollaway.hold.numeric import MarginFunction, least_margin

    vals = draw_values(model, n, seed, marginal) if model.covariance is not None else {}
    mu = vals.get("mu_drum", np.full(n, model.params.mu_drum))
    if carry:
        t_req_Nm = np.asarray(t_req_Nm, float) / untested_direction_factor(model, vals, n, sign, seed)
    fn = MarginFunction(model, np.full(n, float(validate_hand_force(force_N))), np.full(n, float(sign)),
                        t_req_Nm, mu, None, initial_temp_C, heat_transfer_W_m2K=vals.get("heat_transfer_W_m2K"),
                        values={k: v for k, v in vals.items() if k not in LEGACY_FREE})
    if start is None:
        return vals, fn, least_margin(fn, duration_s), np.ones(n)
    from rollaway.uncertainty.predictive import StartError, start_weight
    fn = StartError(fn, *start)
    least, when = least_margin(fn, duration_s, return_time=True)
    return vals, fn, least, 1.0 + fn.extra * start_weight(when, fn.start)    # the start error's share of the least


def zero_torque_force(model: DrumModel) -> float | None:
    """The hand force where eq. (24) gives u₆ = 0 (no clamp force) for *model*'s values [N], or None."""
    p = model.params
    return -p.u6_offset_m / p.u6_slope_m_per_N if p.u6_slope_m_per_N > 0 else None


def torque_level_ratio(model: DrumModel, hand_force_N: float, tested_N, sign: float, initial_temp_C,
                       duration_s: float) -> float | None:
    """The calibrated model's least torque over *duration_s* at the lowest tested hand force over that at
    *hand_force_N* (same direction *sign* and start temperature): how far the torque level falls below the tested
    forces (:func:`rollaway.uncertainty.predictive.force_distance`).  None above the lowest tested force or without a
    tested range; inf where the model gives no torque at *hand_force_N*."""
    from rollaway.hold.numeric import MarginFunction, least_margin
    if tested_N is None or hand_force_N >= float(tested_N[0]):
        return None
    fn = MarginFunction(model, np.array([float(hand_force_N), float(tested_N[0])]), float(sign), 1.0, None, None,
                        initial_temp_C)
    at_f, at_lo = (float(x) for x in least_margin(fn, duration_s))
    if not (np.isfinite(at_lo) and at_lo > 0.0):
        return None
    return at_lo / at_f if at_f > 0.0 else float("inf")


def unseen_hold_change(model: DrumModel, hand_force_N: float, sign: float, initial_temp_C, duration_s: float,
                       points: int = 61) -> float:
    """The largest change of the calibrated model's torque between the end of the bench's longest test (the
    predictive record's ``tested_duration_s``) and a time up to *duration_s*, relative to the torque at that time
    (same hand force, direction *sign* and start temperature): what a hold longer than the bench's asks the model to
    carry unseen (:func:`rollaway.uncertainty.predictive.hold_sd`), as a share of the torque where a margin is
    decided.  The law the model carries errs by a share of the change it carries (:data:`~rollaway.uncertainty.
    predictive.UNSEEN_HOLD_SHARE`), and that error counts against the torque left: where the drum cools on from a
    light pull, the clamp it loses can take most of the torque, and a few tenths of that loss are several times
    what is left.  0 within the tested hold; inf where the torque at the end of the tested hold or later is none
    (the error is then capped where it is used, :func:`hold_error`)."""
    from rollaway.hold.numeric import MarginFunction
    from rollaway.uncertainty.predictive import TOLERANCE
    tested = model.predictive.get("tested_duration_s")
    if not tested or not np.isfinite(tested) or duration_s <= (1.0 + TOLERANCE) * float(tested):
        return 0.0
    fn = MarginFunction(model, np.array([float(hand_force_N)]), np.array([float(sign)]), 1.0, None, None,
                        initial_temp_C)
    t = np.linspace(float(tested), float(duration_s), points)
    torque = np.asarray(fn(t, np.zeros(points, int)), float)
    if not (np.all(np.isfinite(torque)) and np.all(torque > 0.0)):
        return float("inf")
    return float(np.max(np.abs(torque - torque[0]) / torque))


def hold_error(model: DrumModel, hand_force_N: float, sign: float, initial_temp_C, duration_s: float) -> float:
    """The relative torque error of *model* carried beyond the bench's hold to *duration_s*: its own unseen change
    (:func:`unseen_hold_change`; each competing effect set carries its own law) through
    :func:`rollaway.uncertainty.predictive.hold_sd`, at most :data:`~rollaway.uncertainty.predictive.HOLD_SD_CAP`."""
    from rollaway.uncertainty.predictive import HOLD_SD_CAP, hold_sd
    return min(hold_sd(unseen_hold_change(model, hand_force_N, sign, initial_temp_C, duration_s)), HOLD_SD_CAP)


def own_record(pred: dict, part: DrumModel) -> dict:
    """The predictive record whose model error a part of the mixture draws: *part*'s own (an alternative effect set
    carries its own held-out error, :func:`rollaway.uncertainty.bands.model_error`), else the saved model's *pred*."""
    own = part.predictive
    return own if own is not pred and "model_error_rel_sd" in own else pred


def _half_width(x: np.ndarray) -> float:
    """Half the 5–95 % spread of *x*; inf where the upper end is infinite (no torque required), 0 where both are."""
    if not x.size:
        return 0.0
    if np.all(np.isfinite(x)):
        return 0.5 * float(np.percentile(x, 95) - np.percentile(x, 5))
    lo, hi = (float(np.percentile(x, q, method="inverted_cdf")) for q in (5, 95))
    return 0.0 if lo == hi else 0.5 * (hi - lo) if np.isfinite(hi) else float("inf")


def rollaway_risk(model: DrumModel, *, hand_force_N: float, grade_pct: float, direction: str, occupants: int,
                  duration_s: float, initial_temp_C: float | None = None, draws: int = 1000,
                  seed: int | None = 0) -> Risk:
    """Probability of a roll-away over [0, duration_s] and percentiles, from *draws* predictive draws.

    Each draw is one model (the calibrated one, or a competing effect set by its weight), one
    parameter vector from that model's covariance and one model error ε from that model's own held-out
    record (:func:`own_record`; the torque times 1 + ε, widened outside the tested range;
    :mod:`rollaway.uncertainty.predictive`).  The band's parts are reported
    as shares of its variance: parameters, choice of effects, model error.
    """
    from rollaway.hold import _effective, required_torque, tyre_adhesion_margin
    from rollaway.hold.numeric import Subset, first_slip_time
    from rollaway.uncertainty.predictive import (edge_sd, extrapolation, measured_factor, model_error_draws,
                                                 model_error_sd, start_error_draws)

    if not (isinstance(draws, (int, np.integer)) and 1 <= draws <= 1_000_000):
        raise UserError(f"--uncertainty {draws} must be a whole number of draws from 1 to 1000000, e.g. 1000")
    pred = model.predictive
    if model.covariance is None and not pred:
        draw_values(model, draws, seed)          # the error that says how to get a covariance
    g, sign = _effective(grade_pct, direction)
    t_req = float(required_torque(model.params, g, occupants))
    t0 = model.params.initial_drum_temp_C if initial_temp_C is None else float(initial_temp_C)
    f0 = zero_torque_force(model)
    level = torque_level_ratio(model, float(hand_force_N), pred.get("tested_hand_force_N"), sign, t0,
                               float(duration_s))
    factor, flags = extrapolation(pred, hand_force_N=float(hand_force_N), direction=direction, initial_temp_C=t0,
                                  duration_s=float(duration_s), zero_torque_force_N=f0, level_ratio=level)
    edge = edge_sd(pred, float(hand_force_N), f0, level)
    unseen = unseen_hold_change(model, float(hand_force_N), sign, t0, float(duration_s))
    rng = np.random.default_rng(seed)
    parts = mixture_parts(model, direction)
    counts = np.floor(np.array([w for w, _ in parts]) * draws).astype(int)
    counts[0] += draws - counts.sum()
    owner = np.repeat(np.arange(len(parts)), counts)
    eps = np.empty(draws)
    starts, holds = [], []
    rng_start = np.random.default_rng(None if seed is None else (int(seed), 19))
    for k, (_, m) in enumerate(parts):       # each effect set errs by its own held-out record
        own = own_record(pred, m)
        own_edge = edge if own is pred else edge_sd(own, float(hand_force_N), f0, level)
        own_measured = measured_factor(own, factor, float(hand_force_N), f0, level)
        hold = hold_error(m, float(hand_force_N), sign, t0, float(duration_s))
        holds.append(hold)
        eps[owner == k] = model_error_draws(own, int(counts[k]), factor, rng, own_edge, own_measured, hold)
        extra = start_error_draws(own, int(counts[k]), factor, rng_start, own_edge, own_measured, hold)
        starts.append(None if extra is None else (extra, own["model_error_start"]))
    brake = np.empty(draws)
    start_factor = np.ones(draws)
    t_slip = np.full(draws, np.nan)
    vals0 = {}
    for k, ((_, m), c) in enumerate(zip(parts, counts)):
        if c == 0:
            continue
        idx = np.flatnonzero(owner == k)
        vals, fn, least, start_factor[idx] = _least_margins(m, int(c), None if seed is None else seed + k, hand_force_N, sign,
                                         t_req / (1.0 + eps[idx]), initial_temp_C, duration_s,
                                         untested_direction(model, direction), bool(carried_over(model, sign)),
                                         starts[k])
        brake[idx] = least
        if k == 0:
            vals0 = vals
        slips = np.flatnonzero(least < 1.0)      # only draws whose brake gives way have a slip time
        if slips.size:
            t_slip[idx[slips]] = first_slip_time(Subset(fn, slips), duration_s)
    tyre = float(tyre_adhesion_margin(model.params, grade_pct, direction, occupants))
    least = np.minimum(brake, tyre)
    t_roll = np.where(tyre < 1.0, 0.0, t_slip)
    pct = {f"p{q:g}": float(np.percentile(least, q, method="inverted_cdf")) for q in PERCENTILES}
    pct_b = {f"p{q:g}": float(np.percentile(brake, q, method="inverted_cdf")) for q in PERCENTILES}
    t_inf = np.where(np.isnan(t_roll), np.inf, t_roll)       # a draw that holds slips "after the duration"
    tp = {f"p{q:g}": (lambda x: None if not np.isfinite(x) else float(x))(np.percentile(t_inf, q,
                                                                                      method="inverted_cdf"))
          for q in PERCENTILES}
    no_eps = brake / (1.0 + eps) / start_factor   # the margin scales with the torque: ε divides out exactly
    # law of total variance over the effect sets: within (parameters) + between (choice of effects); none where a
    # margin is infinite (no torque required: a level road)
    groups = [no_eps[owner == k] for k in range(len(parts)) if counts[k] > 0]
    finite = bool(np.all(np.isfinite(brake)))
    v_par = sum(g.size * float(np.var(g)) for g in groups) / draws if finite else 0.0
    v_mix, v_all = (float(np.var(no_eps)), float(np.var(brake))) if finite else (0.0, 0.0)
    total = max(v_all, 1e-300)
    shares = {"parameters": min(v_par / total, 1.0), "choice_of_effects": max(v_mix - v_par, 0.0) / total,
              "model_error": max(v_all - v_mix, 0.0) / total} if v_all > 0 else {}
    detail = {"shares": shares, "flags": flags, "extrapolation_factor": factor,
              "model_error_rel_sd": model_error_sd(
                  pred, factor, edge, measured_factor(pred, factor, float(hand_force_N), f0, level), holds[0]),
              "unseen_hold_change": unseen, "hold_error_sd": holds[0], "hold_error_sd_sets": holds,
              "models": [{"name": m.name, "weight": float(w), "draws": int(c)} for (w, m), c in zip(parts, counts)],
              "half_width": _half_width(least), "carried_over": bool(carried_over(model, sign)),
              "start_decided": float(np.mean(start_factor != 1.0))}
    main = owner == 0
    return Risk(draws, float(np.mean(least < 1.0)), pct, pct_b, tp, tyre, vals0, least[main], t_roll[main],
                detail)


def least_force_band(model: DrumModel, grades_pct, direction: str, occupants: int, duration_s: float,
                     initial_temp_C: float | None = None, draws: int = 100, seed: int | None = 0) -> dict:
    """5/50/95 percentiles of the least hand force that holds [N] at each grade, over predictive draws
    (parameters, competing effect sets, model error and the start's — as :func:`rollaway_risk`); NaN where the
    rear tyres slide or no force holds."""
    from rollaway.hold import _effective, required_torque, tyre_adhesion_margin
    from rollaway.hold.numeric import MarginFunction, least_hand_force
    from rollaway.uncertainty.predictive import (StartError, extrapolation, model_error_draws,
                                                 start_error_draws)

    grades = np.atleast_1d(np.asarray(grades_pct, float))
    rng = np.random.default_rng(seed)
    rng_start = np.random.default_rng(None if seed is None else (int(seed), 19))
    t0 = model.params.initial_drum_temp_C if initial_temp_C is None else float(initial_temp_C)
    force = float(np.mean(model.predictive.get("tested_hand_force_N", [250.0, 250.0])))
    factor, _ = extrapolation(model.predictive, hand_force_N=force, direction=direction, initial_temp_C=t0,
                              duration_s=duration_s)
    sign0 = float(np.ravel(_effective(grades[:1], direction)[1])[0])
    parts = mixture_parts(model, direction)
    counts = np.floor(np.array([w for w, _ in parts]) * draws).astype(int)
    counts[0] += draws - counts.sum()
    forces = []
    for k, ((_, m), c) in enumerate(zip(parts, counts)):
        if c == 0:
            continue
        vals = draw_values(m, int(c), None if seed is None else seed + k, untested_direction(model, direction)) \
            if m.covariance is not None else {}
        own = own_record(model.predictive, m)
        hold = hold_error(m, force, sign0, t0, float(duration_s))
        eps = model_error_draws(own, int(c), factor, rng, hold=hold)
        extra = start_error_draws(own, int(c), factor, rng_start, hold=hold)
        g, sign = _effective(grades, direction)
        t_req = np.asarray(required_torque(m.params, g, occupants), float)
        carry = carried_over(model, np.broadcast_to(sign, grades.shape))
        if np.any(carry):
            f = untested_direction_factor(m, vals, int(c), np.broadcast_to(sign, grades.shape),
                                          None if seed is None else seed + k)
            t_req = t_req[None, :] / np.where(carry[None, :], f, 1.0)
        rep = lambda a: np.repeat(np.asarray(a, float)[:, None], grades.size, axis=1).ravel()  # noqa: E731
        mu = rep(vals.get("mu_drum", np.full(c, m.params.mu_drum)))
        h = rep(vals.get("heat_transfer_W_m2K", np.full(c, m.params.heat_transfer_W_m2K)))
        fn = MarginFunction(m, np.zeros(c * grades.size), np.tile(np.broadcast_to(sign, grades.shape), c),
                            (np.broadcast_to(t_req, (c, grades.size)) / (1.0 + eps[:, None])).ravel(), mu, None,
                            t0, heat_transfer_W_m2K=h,
                            values={n: rep(v) for n, v in vals.items() if n not in LEGACY_FREE})
        if extra is not None:                  # the start of the hold errs by the record's start error too
            fn = StartError(fn, rep(extra), own["model_error_start"])
        forces.append(least_hand_force(fn, duration_s).reshape(c, grades.size))
    f = np.concatenate(forces, axis=0)
    f = np.where(np.isfinite(f), f, np.nan)
    tyre = np.asarray(tyre_adhesion_margin(model.params, grades, direction, occupants), float)
    with np.errstate(all="ignore"):
        pct = {f"p{q:g}": np.where(tyre >= 1.0, np.nanpercentile(f, q, axis=0), np.nan) for q in PERCENTILES}
    return pct
