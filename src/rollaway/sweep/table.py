"""The sweep's result table: analytic columns joined with the simulated records.

One row per point, columns in this order:

* inputs: ``point_index``, ``point_id`` and the eight axes (see :data:`rollaway.sweep.spec.AXES`);
* analytic (every point): ``brake_margin_min``, ``tyre_margin``, ``margin`` (the smaller),
  ``analytic_time_to_slip_s``, ``min_hand_force_N``, ``paper_verdict`` (brake only, as in the
  paper), ``analytic_outcome`` (brake and tyres), ``analytic_rollaway_time_s``, ``in_band``;
* simulated (MuJoCo, where run): ``simulated``, ``sim_outcome``, ``sim_rollaway_time_s``,
  ``sim_max_displacement_m``, ``sim_min_margin``, ``sim_creep_m``;
* result: ``outcome`` (simulated where available, else analytic), ``verdict`` (hold / roll),
  ``rollaway_time_s``, ``agree`` (paper verdict = verdict), ``disagreement`` (why not),
  ``error`` (bad input or failed simulation), ``wall_time_s`` (the point's own compute time;
  analytic points share the vectorised pass).
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from rollaway.sweep.spec import AXES

SIM_COLUMNS = ("sim_outcome", "sim_rollaway_time_s", "sim_max_displacement_m", "sim_min_margin", "sim_creep_m")
ANALYTIC_COLUMNS = ("brake_margin_min", "tyre_margin", "margin", "analytic_time_to_slip_s", "min_hand_force_N",
                    "paper_verdict", "analytic_outcome", "analytic_rollaway_time_s", "in_band")
COLUMNS = (("point_index", "point_id") + AXES + ANALYTIC_COLUMNS + ("simulated",) + SIM_COLUMNS
           + ("outcome", "verdict", "rollaway_time_s", "agree", "disagreement", "error", "wall_time_s"))
THRESHOLD_AGREEMENT = 0.005   # MuJoCo's hold/slip threshold matches the analytic one to < 0.5 %


def _num(v) -> float:
    return np.nan if v is None else float(v)


def explain(row) -> str:
    """Why the paper's 1D verdict differs from the best available outcome ('' when they agree)."""
    paper, outcome = row["paper_verdict"], row["outcome"]
    if not outcome or (paper == "hold") == (outcome == "held"):
        return ""
    b, tyre = row["brake_margin_min"], row["tyre_margin"]
    near = abs(b - 1.0) <= THRESHOLD_AGREEMENT
    if not row["simulated"]:
        return (f"rear tyres skid (analytic adhesion margin {tyre:.3f} < 1; not simulated): "
                f"the paper's 1D check ignores tyres")
    t = row["sim_rollaway_time_s"]
    at = f" at t = {t:.3g} s" if np.isfinite(t) else ""
    if outcome == "tyre_skid":
        return (f"tyre skid{at} (simulated): rear adhesion margin {tyre:.3f}"
                f"{' < 1' if tyre < 1 else ', dynamic load transfer'} — the paper's 1D check ignores tyres")
    if outcome == "brake_slip":
        why = ("within the simulator's 0.5 % threshold agreement" if near else
               "the simulated brake gives way before the analytic margin says")
        return f"brake slip{at} (simulated) vs analytic hold (brake margin {b:.4f}): {why}"
    ts = row["analytic_time_to_slip_s"]
    when = f"brake slip at t = {ts:.0f} s" if np.isfinite(ts) else "roll-away"
    why = ("within the simulator's 0.5 % threshold agreement" if near else
           "the simulated car held where the analytic check lets go")
    return f"simulated hold vs analytic {when} (brake margin {b:.4f}): {why}"


def build_table(analytic: pd.DataFrame, records: dict[str, dict], analytic_wall_s: float) -> pd.DataFrame:
    """Join the analytic frame with the journal's simulated records into the result table."""
    df = analytic.copy()
    recs = [records.get(pid) for pid in df["point_id"]]
    has = np.array([r is not None for r in recs])
    sim_err = np.array(["" if r is None else (r.get("error") or "") for r in recs], dtype=object)
    simulated = has & (sim_err == "")
    df["simulated"] = simulated
    for col in SIM_COLUMNS:
        vals = [None if r is None else r.get(col) for r in recs]
        df[col] = ([v or "" for v in vals] if col == "sim_outcome" else [_num(v) for v in vals])
    df["error"] = np.where(df["error"] != "", df["error"], sim_err)
    ok = df["error"] == ""
    df["outcome"] = np.where(simulated, df["sim_outcome"], np.where(ok, df["analytic_outcome"], ""))
    df["verdict"] = np.where(df["outcome"] == "", "", np.where(df["outcome"] == "held", "hold", "roll"))
    df["rollaway_time_s"] = np.where(simulated, df["sim_rollaway_time_s"], df["analytic_rollaway_time_s"])
    agree = pd.Series(pd.array([None] * len(df), dtype="boolean"), index=df.index)
    known = df["verdict"] != ""
    agree[known] = (df.loc[known, "paper_verdict"] == df.loc[known, "verdict"]).to_numpy()
    df["agree"] = agree
    text = np.full(len(df), "", dtype=object)
    for i in np.flatnonzero((agree == False).to_numpy(dtype=bool, na_value=False)):  # noqa: E712
        text[i] = explain(df.iloc[i])
    df["disagreement"] = text
    share = analytic_wall_s / max(len(df), 1)
    df["wall_time_s"] = [float(r.get("wall_time_s", 0.0)) + share if r is not None else share for r in recs]
    df["sim_outcome"] = df["sim_outcome"].astype(str)
    for col in ("paper_verdict", "analytic_outcome", "outcome", "verdict", "disagreement", "error", "direction"):
        df[col] = df[col].astype(str)
    extra = [c for c in ("rollaway_probability",) if c in df.columns]   # with --uncertainty
    return df[list(COLUMNS) + extra]
