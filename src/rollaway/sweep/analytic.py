"""The analytic pass of a sweep: every point at once, one vectorised call per quantity.

For each point (docs/model.md, "Model chain" item 9, via :mod:`rollaway.hold`):

* ``brake_margin_min``: the paper's brake hold margin 2·T_gen(t)/T_req, least over the hold.
  ΔT(t) is monotone and the torque affine in ΔT, so the least value is at t = 0 or t = duration;
* ``tyre_margin``: rear-tyre adhesion margin μ_r·N_r / (m g sin θ) (not in the paper);
* ``paper_verdict``: the paper's 1D check, brake only: "hold" when brake_margin_min ≥ 1;
* ``analytic_outcome``: both conditions: held, brake_slip or tyre_skid (the weaker one at t = 0
  decides which gives way first);
* ``in_band``: the point is near the hold/roll-away boundary, so it is simulated (see :func:`in_band`).

A point whose values the model cannot take (grade beyond ±100 %, 7 occupants, μ_d above 2)
gets its validation message in ``error`` and NaN results; the others are computed.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from rollaway.errors import UserError
from rollaway.hold import (self_locking, hold_margin, invalid_grade, invalid_hand_force, invalid_occupants, min_brake_margin,
                           minimum_hand_force_N, time_to_slip_s, tyre_adhesion_margin, validate_occupants)
from rollaway.model.parameters import SPEC_BY_NAME
from rollaway.physics.drum import DIRECTIONS
from rollaway.hold.scenario import MAX_DURATION_S, Scenario
from rollaway.sweep.columns import label_codes, label_column

OUTCOMES = ("held", "brake_slip", "tyre_skid", "self_locking")


def valid_mask(df: pd.DataFrame) -> np.ndarray:
    """True where every axis value is one the scenario validation accepts (vectorised)."""
    d = df["duration_s"].to_numpy(float)
    ok = ~invalid_grade(df["grade_pct"]) & ~invalid_occupants(df["occupants"]) & ~invalid_hand_force(df["hand_force_N"])
    ok &= np.isfinite(d) & (d > 0) & (d <= MAX_DURATION_S)
    for key in ("mu_drum", "initial_drum_temp_C", "tyre_road_mu"):
        v, spec = df[key].to_numpy(float), SPEC_BY_NAME[key]
        ok &= np.isfinite(v) & (v >= spec.lower) & (v <= spec.upper)
    ok &= df["direction"].isin(DIRECTIONS).to_numpy()
    return ok


def point_changes(row) -> dict:
    """The Scenario.replace() changes of one point (a mapping with the AXES keys)."""
    from rollaway.sweep.spec import AXES
    out = {a: row[a] for a in AXES}
    occ = float(out["occupants"])
    out["occupants"] = int(occ) if occ == int(occ) else occ
    return out


def invalid_message(base: Scenario, row) -> str:
    """The scenario validation's own message for a point that failed :func:`valid_mask`."""
    try:
        base.replace(**point_changes(row))
        validate_occupants(row["occupants"])      # whole numbers: checked by the model, not the scenario
    except (UserError, ValueError, TypeError) as exc:
        return f"bad input: {exc}"
    return "bad input: value outside the model's range"


def in_band(brake_margin, tyre_margin, band) -> np.ndarray:
    """Near the boundary: brake or tyre margin within [band low, band high] (default [0.95, 1.08]).

    Why this band: MuJoCo's brake hold/slip threshold matches the analytic one to < 0.5 %, so
    far from 1 the analytic verdict stands.  Near 1 the two models differ in what the 1D check
    cannot see: tyre adhesion, and the coupling of brake and tyres.  Measured with every point
    simulated (3 647 simulations: the 10 000-point benchmark's [0.9, 1.15] band, and
    ``scenarios/sweeps/grade-load.toml`` and ``materials.toml`` with ``--simulate all``), every
    point where MuJoCo's verdict differed from the analytic brake + tyre verdict had its smaller
    margin within [0.998, 1.03], while its brake margin reached 5.1 when the tyre margin was
    near 1 — hence a band on *either* margin.  [0.95, 1.08] covers that spread with ≥ 2.5×
    headroom, more on the hold side (a wrong "holds" is the dangerous error), and keeps a
    10 000-point sweep under 2 minutes on 2 cores ([0.9, 1.15]: 2.6 minutes).  Widen ``band``
    in the sweep file for a new vehicle or parameter set until the disagreements stay inside.
    """
    lo, hi = band
    b, t = np.asarray(brake_margin), np.asarray(tyre_margin)
    return ((b >= lo) & (b <= hi)) | ((t >= lo) & (t <= hi))


def with_rollaway_probability(table: pd.DataFrame, base: Scenario, draws: int, seed: int = 0) -> pd.DataFrame:
    """Add ``rollaway_probability`` per valid point (*draws* predictive draws of the base model, one loop per
    point) and ``beyond_bench_data``: where the point lies outside what the bench tested."""
    from rollaway.uncertainty.draws import rollaway_risk
    out = table.copy()
    prob = np.full(len(out), np.nan)
    beyond = np.full(len(out), "", dtype=object)
    for i in np.flatnonzero((out["error"] == "").to_numpy()):
        r = out.iloc[i]
        s = base.replace(mu_drum=float(r["mu_drum"]), initial_drum_temp_C=float(r["initial_drum_temp_C"]),
                         tyre_road_mu=float(r["tyre_road_mu"]))
        risk = rollaway_risk(s.model, hand_force_N=float(r["hand_force_N"]), grade_pct=float(r["grade_pct"]),
                             direction=str(r["direction"]), occupants=int(r["occupants"]),
                             duration_s=float(r["duration_s"]), draws=draws, seed=seed)
        prob[i], beyond[i] = risk.rollaway_probability, "; ".join(risk.flags)
    out["rollaway_probability"] = prob
    out["beyond_bench_data"] = beyond.astype(str)
    return out


CHUNK_POINTS = 250_000     # points per vectorised call: bounds the temporaries of a 2e6-point pass

# result column -> (fill for invalid points, dtype); label columns hold codes into LABELS
_RESULTS = {"brake_margin_min": (np.nan, float), "tyre_margin": (np.nan, float), "margin": (np.nan, float),
            "analytic_time_to_slip_s": (np.nan, float), "min_hand_force_N": (np.nan, float),
            "paper_verdict": (0, np.int32), "analytic_outcome": (0, np.int32),
            "analytic_rollaway_time_s": (np.nan, float), "in_band": (False, bool)}
LABELS = {"paper_verdict": ("", "hold", "roll", "self_locking"), "analytic_outcome": ("",) + OUTCOMES}


def _margins(p, v: pd.DataFrame, band) -> dict[str, np.ndarray]:
    """The analytic results of the valid points *v* (one vectorised call per quantity)."""
    dir_labels: list[str] = []
    g = v["grade_pct"].to_numpy(float)
    d_codes = label_codes(v["direction"], dir_labels)
    d = np.asarray(dir_labels, dtype=str)[d_codes]        # a numpy string array without a Python str per row
    n, f = v["occupants"].to_numpy(float), v["hand_force_N"].to_numpy(float)
    mu, t0 = v["mu_drum"].to_numpy(float), v["initial_drum_temp_C"].to_numpy(float)
    mu_r, dur = v["tyre_road_mu"].to_numpy(float), v["duration_s"].to_numpy(float)

    m_start = hold_margin(p, 0.0, f, g, d, n, mu_drum=mu, initial_temp_C=t0)
    brake = min_brake_margin(p, f, g, d, n, dur, mu, None, t0)
    tyre = tyre_adhesion_margin(p, g, d, n, mu_r)
    t_slip = time_to_slip_s(p, f, g, d, n, mu, None, t0, horizon_s=dur)
    f_min = minimum_hand_force_N(p, g, d, n, dur, mu, None, t0)

    tyre_first = (tyre < 1.0) & (tyre <= m_start)
    outcome = np.where(np.minimum(brake, tyre) >= 1.0, "held", np.where(tyre_first, "tyre_skid", "brake_slip"))
    locked = self_locking(p, g, d, mu)             # eqs. 18–21: outside the 1D model, never "held"
    outcome = np.where(locked, "self_locking", outcome)
    f_min = np.where(locked | (tyre < 1.0), np.nan, f_min)   # no hand force holds where the tyres slide
    t_roll = np.where(outcome == "held", np.nan, np.where(outcome == "tyre_skid", 0.0, t_slip))
    return {"brake_margin_min": brake, "tyre_margin": tyre, "margin": np.minimum(brake, tyre),
            "analytic_time_to_slip_s": t_slip, "min_hand_force_N": f_min,
            "paper_verdict": np.where(locked, 3, np.where(brake >= 1.0, 1, 2)),
            "analytic_outcome": np.select([outcome == o for o in OUTCOMES], np.arange(1, len(OUTCOMES) + 1)),
            "analytic_rollaway_time_s": t_roll, "in_band": in_band(brake, tyre, band) & ~locked}


def analytic_pass(base: Scenario, points: pd.DataFrame, band) -> pd.DataFrame:
    """Analytic margins and verdicts of every point (*points* with result columns; inputs shared, not copied).

    The points go through :func:`_margins` in slices of :data:`CHUNK_POINTS`, so memory stays
    bounded for the largest sweeps; invalid points get NaN results and their message in ``error``.
    """
    out = points.copy(deep=False)
    ok = valid_mask(points)
    cols = {name: np.full(len(points), fill, dtype=dtype) for name, (fill, dtype) in _RESULTS.items()}
    for lo in range(0, len(points), CHUNK_POINTS):
        sl = slice(lo, lo + CHUNK_POINTS)
        chunk_ok = ok[sl]
        chunk = points.iloc[sl]
        if not chunk_ok.any():
            continue
        res = _margins(base.model, chunk if chunk_ok.all() else chunk[chunk_ok], band)
        for name, values in res.items():
            view = cols[name][sl]
            view[chunk_ok] = values
    for name, values in cols.items():
        out[name] = label_column(values, LABELS[name]) if name in LABELS else values
    bad = np.flatnonzero(~ok)
    messages = [invalid_message(base, points.iloc[i]) for i in bad]
    index = {m: i + 1 for i, m in enumerate(dict.fromkeys(messages))}
    codes = np.zeros(len(points), dtype=np.int32)
    codes[bad] = [index[m] for m in messages]
    out["error"] = label_column(codes, [""] + list(index))
    return out
