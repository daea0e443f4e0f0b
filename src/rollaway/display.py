"""Notebook display of result objects (``_repr_html_``): the decision first, then a small table."""
from __future__ import annotations

import html
import math


def _cell(v) -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if isinstance(v, float):
        return f"{v:.4g}"
    return html.escape(str(v))


def result_html(headline: str, rows: dict, ok: bool | None = None) -> str:
    """A headline (green when *ok*, red when not, plain when None) over a two-column table of *rows*."""
    colour = "" if ok is None else ("color:#1a7f37;" if ok else "color:#c0392b;")
    body = "".join(f"<tr><td style='text-align:left'>{html.escape(str(k))}</td><td>{_cell(v)}</td></tr>"
                   for k, v in rows.items())
    return (f"<div><p style='font-weight:bold;{colour}'>{html.escape(headline)}</p>"
            f"<table>{body}</table></div>")


def sim_result_html(r) -> str:
    verdict = {"held": "HOLDS", "brake_slip": "ROLLS AWAY: the drum brake slips",
               "tyre_skid": "ROLLS AWAY: the rear tyres skid"}.get(r.outcome, r.outcome)
    keys = ("rollaway_time_s", "analytic_time_to_slip_s", "min_margin", "tyre_adhesion_margin", "max_displacement_m",
            "drum_temp_C_end", "sim_time_s", "wall_time_s")
    return result_html(f"{r.scenario}: {verdict}", {k: getattr(r, k, None) for k in keys}, r.outcome == "held")


def diagnosis_html(d) -> str:
    rows = {c.effect: f"ΔBIC {c.delta_bic:+.1f}, torque RMSE {c.fit.rmse_torque_Nm:.3g} N·m"
            for c in getattr(d, "candidates", [])[:5]}
    named = " + ".join(e["effect"] for e in getattr(d, "effects", []) or []) or d.verdict
    names = " or ".join([named] + [" + ".join(a["effects"]) for a in getattr(d, "alternatives", []) or []])
    return result_html(f"missing effect: {names}", rows, d.verdict != "none" or not d.remaining_structure)


def fit_html(f) -> str:
    rows = {e.name: f"{e.value:.5g} ± {e.stderr:.2g} {e.unit}" + (f" (at {e.at_bound} bound)" if e.at_bound else "")
            for e in f.estimates.values()}
    rows.update({"torque RMSE [N·m]": f.rmse_torque_Nm, "temperature RMSE [°C]": f.rmse_temp_C, "BIC": f.bic})
    return result_html("paper model" + "".join(" + " + e for e in f.effects), rows)


def sweep_html(res) -> str:
    t = res.table
    rows = {"points": res.n_points, "hold": int((t["verdict"] == "hold").sum()),
            "roll away": int((t["verdict"] == "roll").sum()), "failed": res.n_failed,
            "simulated in MuJoCo": int(t["simulated"].sum()), "paper check disagrees": res.n_disagree,
            "wall time [s]": res.wall_time_s}
    return result_html(f"sweep of {res.n_points} points", rows, res.n_failed == 0) + t.head(10)._repr_html_()
