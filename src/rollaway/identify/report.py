"""Self-contained HTML reports of the bench workflow (interactive plotly.js figures inlined; no network needed).

Each page reads as an engineer's page: the verdict and what it means for the design first
(the FMVSS 135 case, 400 N on a 20 % grade, with the fitted model against the paper's), then
the evidence as real tables (errors, candidates with their leave-one-test-out score, fit
statistics in the manner of lmfit's ``fit_report``: initial and fitted values, errors,
evaluations, convergence, reduced χ², correlation matrix, bound warnings), then the figures.

Figures are plotly.js specifications (:mod:`rollaway.identify.report_figures`) drawn in the
browser; plotly.js itself is copied into the page from the installed ``plotly`` package (about
5 MB), so the page works offline and the report is written in tens of milliseconds.

The result objects are read defensively (``getattr`` with defaults), so fields added to them
later do not break the pages.
"""
from __future__ import annotations

import html
import itertools
import json
import math
import re
from functools import lru_cache
from pathlib import Path

import numpy as np

CSS = ("body{font:15px/1.45 system-ui,sans-serif;max-width:1180px;margin:1.5em auto;padding:0 1em;color:#222}"
       "h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ddd}"
       "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:4px 9px;text-align:right}"
       "th{background:#f0f0f0}td:first-child,th:first-child{text-align:left}"
       ".verdict{font-size:1.15em;padding:.7em 1em;border-left:6px solid #3a7;background:#eef7f0}"
       ".verdict.bad{border-color:#c43;background:#fbeeee}.note{color:#555;font-size:.93em}"
       "td.warn{color:#b30;text-align:left}img{max-width:100%}.plot{width:100%}li{margin:.3em 0}.sub{color:#666}")

DESIGN_CASE = {"preset": "fmvss135", "hand_force_N": 400.0, "grade_pct": 20.0, "occupants": 5,
               "initial_temp_C": 200.0, "duration_s": 300.0, "long_s": 3600.0}
REQUIRED_MARGIN = 1.2    # [assumed] a design margin of 20 % over the demand, the sweep's design-chart line


def esc(text) -> str:
    """HTML-escape *text* and turn the few markdown marks used in messages (*x*, `x`) into HTML."""
    t = html.escape(str(text))
    t = re.sub(r"`([^`]+)`", r"<code>\1</code>", t)
    return re.sub(r"\*([^*\s][^*]*)\*", r"<em>\1</em>", t)


_PLOT_IDS = itertools.count(1)
PLOT_CONFIG = {"displaylogo": False, "responsive": True, "toImageButtonOptions": {"format": "png", "scale": 2}}


def plot(fig: dict) -> str:
    """A figure spec (``{"data": [...], "layout": {...}}``) as a div and the script that draws it."""
    div = f"rollaway-plot-{next(_PLOT_IDS)}"
    spec = json.dumps([fig["data"], fig["layout"], PLOT_CONFIG], separators=(",", ":"), allow_nan=False)
    spec = spec.replace("</", "<\\/")          # test ids come from user files: never close the script early
    return (f"<div class='plot' id='{div}'></div>"
            f"<script>Plotly.newPlot('{div}',...{spec});</script>")


@lru_cache(maxsize=1)
def plotly_js() -> str:
    """The text of plotly.min.js from the installed ``plotly`` package (found without importing it)."""
    import importlib.util
    from rollaway.errors import UserError
    spec = importlib.util.find_spec("plotly")
    path = Path(spec.submodule_search_locations[0]) / "package_data" / "plotly.min.js" if spec else None
    if path is None or not path.is_file():
        raise UserError("--report: the HTML reports need plotly.js from the 'plotly' package; "
                        "run: python -m pip install plotly")
    return path.read_text(encoding="utf-8")


def table(head: list[str], rows: list[list], cls: list[str] | None = None) -> str:
    """An HTML table; floats formatted with 4 significant digits, None as an en dash."""
    def cell(v):
        if v is None or (isinstance(v, float) and math.isnan(v)):
            return "–"
        if isinstance(v, float):
            return f"{v:.4g}"
        return esc(v)
    th = "".join(f"<th>{esc(h)}</th>" for h in head)
    body = "".join("<tr>" + "".join(f"<td{' class=' + cls[i] if cls and cls[i] else ''}>{cell(v)}</td>"
                                    for i, v in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><tr>{th}</tr>{body}</table>"


def ul(items) -> str:
    return "<ul>" + "".join(f"<li>{esc(w)}</li>" for w in items) + "</ul>"


def page(title: str, body: str) -> str:
    script = f"<script>{plotly_js()}</script>" if "class='plot'" in body else ""
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style>{script}</head><body><h1>{html.escape(title)}</h1>{body}"
            "<p class='note'>rollaway bench report; self-contained, no network needed (plotly.js is included). "
            "Figures: drag to zoom, double-click to reset, click a legend entry to hide it. "
            "The model is described in docs/model.md.</p></body></html>")


def write(path, text) -> None:
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


def model_name(fit) -> str:
    effects = list(getattr(fit, "effects", []) or [])
    return "paper model" + "".join(" + " + e for e in effects)


# ---- the design consequence ------------------------------------------------------------------

def design_margins(fits: list[tuple[str, object]], case: dict = DESIGN_CASE) -> list[dict]:
    """Least brake margin 2·T(t)/T_req of the design case for each (name, FitResult), both directions.

    The torque comes from each fit's own bench model (its effects and fitted values) for one
    drum pulled with the case's hand force from its initial temperature; T_req is eq. (23)
    (:func:`rollaway.hold.required_torque`).
    """
    from rollaway.hold import required_torque
    from rollaway.hold import min_brake_margin
    out = []
    for name, fit in fits:
        model = fit.model.drum_model(fit.values)       # the calibrated drum model (per-test values left out)
        t_req = float(required_torque(model.params, case["grade_pct"], case["occupants"]))
        row = {"model": name, "demand_Nm": t_req}
        for d in ("downhill", "uphill"):
            for key, dur in (("short", case["duration_s"]), ("long", case["long_s"])):
                row[f"{d}_{key}"] = float(min_brake_margin(model, case["hand_force_N"], case["grade_pct"], d,
                                                           case["occupants"], dur,
                                                           initial_temp_C=case["initial_temp_C"]))
        out.append(row)
    return out


def design_section(fits: list[tuple[str, object]]) -> tuple[str, str]:
    """(sentence, HTML table) of the design case for the given models (the last is the one to trust)."""
    c = DESIGN_CASE
    try:
        rows = design_margins(fits)
    except Exception as exc:  # a plugin effect that cannot run on the design case: say so, keep the page
        return f"The design case could not be evaluated ({exc}).", ""
    last, first = rows[-1], rows[0]
    worst = min(last["downhill_short"], last["uphill_short"])
    worst_p = min(first["downhill_short"], first["uphill_short"])
    verdict = ("the car would ROLL AWAY in the regulation test" if worst < 1.0 else
               f"it holds{' with at least' if worst >= REQUIRED_MARGIN else ', but with less than'} the "
               f"{REQUIRED_MARGIN - 1:.0%} design margin")
    sentence = (f"Design consequence ({c['preset'].upper()}: {c['hand_force_N']:.0f} N on the lever, "
                f"{c['grade_pct']:.0f} % grade, {c['occupants']} occupants, {c['duration_s']:.0f} s from "
                f"{c['initial_temp_C']:.0f} °C): with the {last['model']} the least brake margin is {worst:.2f}"
                + (f" (the {first['model']} gives {worst_p:.2f}, a change of {worst / worst_p - 1:+.0%})"
                   if len(rows) > 1 else "") + f"; {verdict}.")
    tested = float(np.max(fits[-1][1].data.time_s)) if getattr(fits[-1][1], "data", None) is not None else 0.0
    if 0.0 < tested < c["duration_s"] / 1.02:       # the case's hold lies beyond the bench's (its bands widen)
        sentence += (f" Beyond the bench data: its tests lasted at most {tested:.0f} s; the bands of `rollaway hold "
                     f"--uncertainty` count what the model carries unseen over the rest of the hold.")
    tab = table(["model", f"downhill, {c['duration_s']:.0f} s", f"uphill, {c['duration_s']:.0f} s",
                 f"downhill, {c['long_s']:.0f} s", f"uphill, {c['long_s']:.0f} s"],
                [[r["model"], r["downhill_short"], r["uphill_short"], r["downhill_long"], r["uphill_long"]]
                 for r in rows])
    note = (f"<p class='note'>Least brake margin 2·T(t)/T_req over the hold (1 = the brake just holds; "
            f"T_req = {last['demand_Nm']:.0f} N·m at the rear axle, eq. 23). The paper's check asks for ≥ 1; "
            f"{REQUIRED_MARGIN:g} is the design target [assumed].</p>")
    return sentence, tab + note


# ---- fit statistics ----------------------------------------------------------------------

def fit_statistics(fit, noise: dict | None = None) -> str:
    """lmfit-style statistics of a FitResult: per stage evaluations, convergence, reduced χ², correlation."""
    ests = getattr(fit, "estimates", {}) or {}
    if not ests:
        return "<p>No parameter was fitted (the model at given values).</p>"
    info = getattr(fit, "fit_info", {}) or {}
    stages = info.get("stages", [])
    initial = {k: v for s in stages for k, v in (s.get("initial") or {}).items()}
    prows = []
    for e in ests.values():
        rel = abs(e.stderr / e.value) if e.value else math.nan
        prows.append([e.name, initial.get(e.name), e.value, e.stderr, f"{rel:.1%}" if math.isfinite(rel) else "–",
                      e.ci95[0], e.ci95[1], e.unit, f"[{e.lower:g}, {e.upper:g}]",
                      f"at {e.at_bound} bound: interval not meaningful" if e.at_bound else ""])
    html_ = table(["parameter", "initial", "fitted", "std. error", "rel. error", "95 % low", "95 % high", "unit",
                   "bounds", "warning"], prows, cls=[""] * 9 + ["warn"])
    noise = noise or {}
    srows = []
    k_by = {"temperature": 0, "torque": 0}
    for s in stages:
        k_by[s.get("channel", "")] = len(s.get("names", []))
    for ch, rss, n in (("temperature", getattr(fit, "rss_temp", math.nan), getattr(fit, "n_temp", 0)),
                       ("torque", getattr(fit, "rss_torque", math.nan), getattr(fit, "n_torque", 0))):
        st = next((s for s in stages if s.get("channel") == ch), {})
        sig = noise.get(ch)
        dof = max(n - k_by.get(ch, 0), 1)
        chi2 = rss / (sig ** 2 * dof) if sig else None
        srows.append([ch, n, k_by.get(ch, 0), st.get("nfev"), "yes" if st.get("success", True) else "NO",
                      math.sqrt(rss / max(n, 1)), chi2, st.get("message", "")])
    html_ += table(["channel (fit stage)", "data points", "variables", "evaluations", "converged", "RMSE",
                    "reduced χ²", "optimizer message"], srows)
    html_ += (f"<p class='note'>AIC {fit.aic:.1f}, BIC {fit.bic:.1f}, k = {fit.k}. Reduced χ² = RSS / (σ²·(n − k)) "
              "with σ the noise level estimated from the data without the physics: ≈ 1 means the model explains the "
              "data down to the noise, ≫ 1 that something is missing.</p>")
    for s in stages:
        names, corr = s.get("names", []), s.get("correlation")
        if corr is None or len(names) < 2:
            continue
        short = [n.split(".")[-1] for n in names]
        rows = [[short[i]] + [float(corr[i][j]) for j in range(len(names))] for i in range(len(names))]
        html_ += f"<p>Correlation of the {esc(s.get('channel', ''))} stage's parameters:</p>" + table([""] + short, rows)
        strong = [(names[i], names[j], corr[i][j]) for i in range(len(names)) for j in range(i)
                  if abs(corr[i][j]) > 0.9]
        if strong:
            html_ += ul([f"{a} and {b} are correlated {c:+.2f}: the data barely separate them" for a, b, c in strong])
    warnings = getattr(fit, "warnings", []) or []
    if warnings:
        html_ += "<p>Warnings:</p>" + ul(warnings)
    return html_


# ---- the pages -----------------------------------------------------------------------------

def _noise(obj) -> dict:
    n = getattr(obj, "noise", None)
    if isinstance(n, dict):
        return {k: getattr(v, "sigma", v) for k, v in n.items()}
    return {"torque": getattr(getattr(obj, "noise_torque", None), "sigma", None),
            "temperature": getattr(getattr(obj, "noise_temp", None), "sigma", None)}


def comparison_report(cmp, path) -> None:
    from rollaway.identify.report_figures import residual_figure, signals_figure
    fit, data = cmp.fit, cmp.data
    noise = _noise(cmp)
    verdict, good = cmp.verdict()
    design, design_tab = design_section([("paper model", fit)] if not fit.effects else
                                        [(model_name(fit), fit)])
    body = (f"<p class='verdict{'' if good else ' bad'}'>{esc(verdict)}</p><p>{esc(design)}</p>"
            f"<p class='sub'>Data: {esc(data.source)}: {len(data)} samples, {data.n_tests} tests. Model: "
            f"{esc(model_name(fit))} {'calibrated to these data' if fit.k else 'at the parameter set values'}.</p>")
    rows = []
    for t in cmp.per_test + [{"test_id": "all tests", "direction": "", "hand_force_N": None, "initial_temp_C": None,
                              **cmp.overall}]:
        q, h = t["torque"], t["temperature"]
        rows.append([t["test_id"], t["direction"], t["hand_force_N"], t["initial_temp_C"], q["rmse"], q["bias"],
                     q["worst"], q["worst_at_s"], h["rmse"], h["bias"], h["worst"], h["worst_at_s"]])
    body += ("<h2>Errors per test (measured − model)</h2>"
             + table(["test", "direction", "hand force [N]", "T₀ [°C]", "torque RMSE [N·m]", "bias [N·m]",
                      "worst [N·m]", "at [s]", "temp. RMSE [°C]", "bias [°C]", "worst [°C]", "at [s]"], rows)
             + f"<p class='note'>Noise level: torque σ ≈ {noise.get('torque') or math.nan:.3g} N·m, drum temperature "
               f"σ ≈ {noise.get('temperature') or math.nan:.3g} °C.</p>")
    body += "<h2>Where it fails</h2>" + ul(cmp.findings(limit=6))
    if design_tab:
        body += "<h2>Design case</h2>" + design_tab
    body += "<h2>Signals</h2>" + plot(signals_figure([(model_name(fit), fit)]))
    body += "<h2>Residuals</h2>" + plot(residual_figure(fit, noise))
    if fit.estimates:
        body += "<h2>Fitted parameters</h2>" + fit_statistics(fit, noise)
    write(path, page(f"rollaway compare: {data.source}", body))


def _candidate_rows(diag) -> list[list]:
    from rollaway.identify.selection import SHORTFALL_WORDS as SHORT, nested_shortfall
    base_cv = getattr(diag, "baseline_cv", None)
    rows = [["paper model, calibrated (reference)", 0.0, diag.baseline.rmse_torque_Nm, diag.baseline.rmse_temp_C,
             base_cv, "–"]]
    for c in diag.candidates:
        cv = getattr(c, "cv_score", None)
        better = getattr(c, "cv_better_tests", None)
        rows.append([c.effect, c.delta_bic, c.fit.rmse_torque_Nm, c.fit.rmse_temp_C, cv if cv is not None else
                     SHORT if nested_shortfall(c.fit, diag.baseline) else "not cross-validated (ΔBIC not below −10)",
                     f"{better} of {diag.data.n_tests}" if better is not None else "–"])
    return rows


def diagnosis_report(diag, path) -> None:
    from rollaway.identify.report_figures import ladder_figure, residual_figure, signals_figure
    noise = _noise(diag)
    verdict = getattr(diag, "verdict", "none")
    alts = getattr(diag, "alternatives", []) or []
    named = [e["effect"] for e in getattr(diag, "effects", []) or []]
    if verdict != "none" and alts:
        from rollaway.identify.ambiguity import verdict_line
        head = f"Missing effect: {verdict_line(verdict, alts, named=named)}."
    elif verdict != "none":
        head = (f"Missing effect{'s' if len(named) > 1 else ''} found: {' + '.join(named) or verdict}. "
                + (("The residual still has structure: the data want a form the catalogue does not write (the shape "
                    "below)." if getattr(diag, "shape", None) else "The residual still has structure that no "
                    "catalogue effect explains.") if getattr(diag, "remaining_structure", False) else
                   "With it the residual is consistent with the measurement noise."))
    elif getattr(diag, "remaining_structure", False):
        head = ("No effect of the catalogue explains the data: the residual still has structure. "
                "An effect outside the catalogue (or several together) is missing.")
    else:
        head = "No missing effect detected: the paper model, calibrated, explains the data down to the noise."
        from rollaway.identify.detection import blind
        missed = blind(getattr(diag, "detection", []) or [])
        if missed:
            head += f" These data could miss effects of the size real drums show: {', '.join(missed)}."
    good = verdict != "none" or not getattr(diag, "remaining_structure", False)
    fits = [("paper model", diag.paper), ("calibrated paper model", diag.baseline)]
    if diag.refined is not diag.baseline:
        fits.append((model_name(diag.refined) + " (refined)", diag.refined))
    design, design_tab = design_section(fits)
    body = (f"<p class='verdict{'' if good else ' bad'}'>{esc(head)}</p><p>{esc(design)}</p>"
            f"<p class='sub'>Data: {esc(diag.data.source)}: {len(diag.data)} samples, {diag.data.n_tests} tests.</p>"
            "<h2>Evidence</h2>" + ul(getattr(diag, "evidence", [])))
    if design_tab:
        body += "<h2>Design case</h2>" + design_tab
    if getattr(diag, "detection", None):
        body += ("<h2>What this campaign could have missed</h2>"
                 + table(["effect", "size parameter", "least size found 4 times in 5", "typical size", "ratio"],
                         [[r["effect"], r["parameter"], f"{r['least_size']:.3g} {r['unit']}",
                           f"{r['typical']:.3g} {r['unit']}", f"{r['ratio']:.2g}"] for r in diag.detection])
                 + "<p class='note'>A ratio above 1: an effect of the size real drums show could hide in these data "
                   "(rollaway.identify.detection).</p>")
    drum = getattr(diag, "drum", None)
    if drum is not None:
        body += (f"<h2>Your drum: what these data identify</h2><p class='sub'>{esc(drum.selection)}; singular values "
                 f"{', '.join(f'{x:.3g}' for x in drum.singular_values) or '–'}</p>"
                 + table(["parameter", "status", "value", "± (1σ)", "95 % interval", "assumed value", "note"],
                         [[n, e.status, e.value, e.stderr, "" if e.ci95 is None else f"{e.ci95[0]:.4g} – {e.ci95[1]:.4g}",
                           e.assumed_value, e.reason or f"stands for the {e.as_dict()['stands_for']}"]
                          for n, e in drum.entries.items()])
                 + "<p class='note'>Fixed and untested parameters stay at their assumed values; their assumed spread "
                   "(in brackets in the note) is carried into the uncertainty bands of the saved model.</p>")
    pred = getattr(diag, "refined", None) and diag.refined.fit_info.get("predictive")
    if pred:
        alts = diag.refined.fit_info.get("alternatives") or []
        rows = [["model error (leave-one-test-out, relative torque, 1σ)",
                 f"{pred['model_error_rel_sd']:.3%} (Student-t, {pred['model_error_dof']} dof)"],
                *[[f"{side} tested force predicted from the others (relative torque, 1σ)",
                   f"{pred[k][0]:.3%} at distance {pred[k][1]:.2f}"]
                  for side in ("lowest", "highest") if (k := f"model_error_edge_{side[:-3]}") in pred],
                *[["start of each test predicted from the others (relative torque, 1σ)",
                   f"{st[0]:.3%} over its first {st[1]:g} s, fading by {st[2]:g} s"]
                  for st in [pred.get("model_error_start")] if st],
                ["tested hand force [N]", "{:g} – {:g}".format(*pred["tested_hand_force_N"])],
                ["tested T_0 [°C]", "{:.0f} – {:.0f}".format(*pred["tested_initial_temp_C"])],
                ["tested hold [s]", f"{pred['tested_duration_s']:g}"],
                ["tested directions", ", ".join(pred["tested_directions"])],
                ["competing effect sets (pseudo-BMA weight)",
                 ", ".join(f"{' + '.join(f.effects) or 'no effect'} ({w:.2f})" for w, f in alts) or "none"]]
        body += ("<h2>Predictive record of the saved model</h2>" + table(["", "value"], rows)
                 + "<p class='note'>hold/check/sweep/chart --uncertainty draw parameters, these competing effect "
                   "sets by weight and a model error ε (torque × (1 + ε)); a question outside the tested range is "
                   "flagged and widens ε. Each answer reports the share of its band that each part contributes."
                   "</p>")
    body += ("<h2>Candidates, best first</h2>"
             + table(["effect", "ΔBIC", "torque RMSE [N·m]", "temp. RMSE [°C]", "leave-one-test-out score [–]",
                      "held-out tests predicted better"], _candidate_rows(diag))
             + "<p class='note'>ΔBIC: change of the Bayesian information criterion against the calibrated paper "
               "model (negative is better; below −10 is very strong evidence). Leave-one-test-out score: each test "
               "is predicted by the model calibrated on the other tests; the score is the sum over held-out tests "
               "of the squared errors divided by the noise variance, Σ(r/σ)², both channels (dimensionless; lower "
               "is better; about the number of samples when the model predicts down to the noise). Only "
               "candidates with ΔBIC below −10 are cross-validated.</p>")
    body += "<h2>Fit of the refined model</h2>" + fit_statistics(diag.refined, noise)
    body += "<h2>Error ladder</h2>" + plot(ladder_figure(diag.baseline.data, fits))   # the selection's rows
    body += ("<h2>Signals: calibrated paper model (dashed) and refined (solid)</h2>"
             + plot(signals_figure([("calibrated paper model", diag.baseline), ("refined", diag.refined)])))
    body += "<h2>Residuals of the calibrated paper model</h2>" + plot(residual_figure(diag.baseline, noise))
    if diag.refined is not diag.baseline:
        body += "<h2>Residuals of the refined model</h2>" + plot(residual_figure(diag.refined, noise))
    shape = getattr(diag, "shape", None)
    if shape:                       # "form": "partial": what the data want against the catalogue's form
        from rollaway.identify.report_figures import shape_figure
        body += "<h2>Form partial: the shape the data want</h2>" + plot(shape_figure(shape, shape.get("effect",
                                                                                                      verdict)))
    write(path, page(f"rollaway diagnose: {diag.data.source}", body))


def ladder_report(ladder, path) -> None:
    from rollaway.identify.report_figures import ladder_figure, signals_figure
    rows = []
    ref = ladder.rungs[1][1].bic if len(ladder.rungs) > 1 else None
    for name, f in ladder.rungs:
        rows.append([name.strip(), f.rmse_torque_Nm, f.rmse_temp_C, (f.bic - ref) if f.k and ref is not None else None,
                     f.k])
    verdict, good = ladder.verdict() if hasattr(ladder, "verdict") else ("", True)
    design, design_tab = design_section([(n.strip(), f) for n, f in ladder.rungs[::max(len(ladder.rungs) - 1, 1)]])
    body = (f"<p class='verdict{'' if good else ' bad'}'>{esc(verdict)}</p><p>{esc(design)}</p>"
            "<h2>Error ladder</h2>" + table(["model", "torque RMSE [N·m]", "temp. RMSE [°C]",
                                             "ΔBIC vs calibrated paper model", "fitted parameters"], rows)
            + plot(ladder_figure(ladder.data, ladder.rungs)))
    if design_tab:
        body += "<h2>Design case</h2>" + design_tab
    body += ("<h2>Fit of the last rung</h2>" + fit_statistics(ladder.final)
             + "<h2>Signals: calibrated paper model (dashed) and refined (solid)</h2>"
             + plot(signals_figure([("calibrated paper model", ladder.baseline), ("refined", ladder.final)])))
    write(path, page(f"rollaway fit: {ladder.data.source}", body))


# kept for callers of the former single-module layout
def __getattr__(name):
    if name in ("signals_figure", "residual_figure", "ladder_figure"):
        from rollaway.identify import report_figures
        return getattr(report_figures, name)
    raise AttributeError(name)
