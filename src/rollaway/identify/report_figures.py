"""The figures of the bench reports, as plotly.js figure specifications (plain dicts: data + layout).

The HTML reports draw them in the browser with plotly.js, inlined from the installed ``plotly``
package (:func:`rollaway.identify.report.plotly_js`), the way ``mujoco.sysid``'s reports do: zoom,
hover (test, time, value) and a click on a legend entry to hide a test or a model.  Building a
spec is only array slicing and rounding, so a report is written in a few tens of milliseconds
whatever the number of panels (drawing 22 matplotlib axes took ~1 s).

Times are in seconds everywhere (as in the tables); each test has one colour, named in the
legend with its direction and hand force; up to :data:`LEGEND_TESTS` tests get a trace (and a
legend entry) each, more share one trace per panel, coloured by test, named on hover.
"""
from __future__ import annotations

import base64
import textwrap

import numpy as np

TAB10 = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22",
         "#17becf"]
TAB20 = ["#1f77b4", "#aec7e8", "#ff7f0e", "#ffbb78", "#2ca02c", "#98df8a", "#d62728", "#ff9896", "#9467bd",
         "#c5b0d5", "#8c564b", "#c49c94", "#e377c2", "#f7b6d2", "#7f7f7f", "#c7c7c7", "#bcbd22", "#dbdb8d",
         "#17becf", "#9edae5"]
DASHES = ["dash", "solid", "dot", "dashdot"]
LEGEND_TESTS = 30
_AXIS = {"showline": True, "linecolor": "#888", "mirror": True, "ticks": "outside", "gridcolor": "#e8e8e8",
         "zeroline": False, "automargin": True}


def colors(n: int) -> list[str]:
    """One colour per test (matplotlib's tab10, or tab20 beyond ten tests)."""
    pal = TAB10 if n <= 10 else TAB20
    return [pal[i % len(pal)] for i in range(n)]


def legend_labels(data) -> list[str]:
    """'T1 downhill 200 N' per test, in test order."""
    info = {t["test_id"]: t for t in data.test_info()}
    return [f"{tid} {info[tid]['direction']} {info[tid]['hand_force_N']:.0f} N" for tid in data.tests]


def rows_of_test(data, i: int) -> np.ndarray:
    """Row indices of test *i*, in time order."""
    rows = np.flatnonzero(data.test_index == i)
    return rows[np.argsort(data.time_s[rows], kind="stable")]


def num(values) -> dict:
    """A numeric array as plotly.js's typed-array JSON (float32, base64; NaN draws a gap).

    Four bytes a value instead of a decimal string, and no per-value formatting: the report of
    10 000 samples is encoded in milliseconds.  Float32 carries 7 significant digits, more than a
    figure shows.
    """
    a = np.ascontiguousarray(values, dtype="<f4")
    return {"dtype": "f4", "bdata": base64.b64encode(a.tobytes()).decode("ascii")}


def unnum(spec) -> np.ndarray:
    """The array of a :func:`num` spec (for tests and for reading a report's figures back)."""
    return np.frombuffer(base64.b64decode(spec["bdata"]), dtype="<f4")


def grid(rows: int, cols: int, *, widths=None, left=0.0, right=1.0, hgap=0.05, vgap=0.16, titles=(),
         xtitles=(), ytitles=(), share_y_rows=False) -> tuple[dict, list[tuple[str, str]]]:
    """Layout axes for a rows × cols grid and the (xaxis, yaxis) trace references, row-major from top left."""
    widths = np.asarray(widths if widths is not None else [1.0] * cols, float)
    span = (right - left - hgap * (cols - 1)) / widths.sum()
    height = (1.0 - vgap * (rows - 1)) / rows
    layout, refs, notes = {}, [], []
    for r in range(rows):
        x = left
        for c in range(cols):
            k = r * cols + c + 1
            sx, sy = ("", "") if k == 1 else (str(k), str(k))
            y1 = 1.0 - r * (height + vgap)
            xa = {**_AXIS, "domain": [x, x + span * widths[c]], "anchor": f"y{sy}"}
            ya = {**_AXIS, "domain": [y1 - height, y1], "anchor": f"x{sx}"}
            if share_y_rows and c > 0:
                ya["matches"] = f"y{'' if r * cols + 1 == 1 else r * cols + 1}"
                ya["showticklabels"] = False
            if k - 1 < len(xtitles) and xtitles[k - 1]:
                xa["title"] = {"text": xtitles[k - 1]}
            if k - 1 < len(ytitles) and ytitles[k - 1]:
                ya["title"] = {"text": ytitles[k - 1]}
            layout[f"xaxis{sx}"], layout[f"yaxis{sy}"] = xa, ya
            if k - 1 < len(titles) and titles[k - 1]:
                notes.append({"text": f"<b>{titles[k - 1]}</b>", "xref": f"x{sx} domain", "yref": f"y{sy} domain",
                              "x": 0.5, "y": 1.0, "yanchor": "bottom", "showarrow": False})
            refs.append((f"x{sx}", f"y{sy}"))
            x += span * widths[c] + hgap
    layout["annotations"] = notes
    return layout, refs


def base_layout(height: int, axes: dict, **extra) -> dict:
    return {"height": height, "margin": {"l": 70, "r": 20, "t": 40, "b": 60}, "font": {"size": 13},
            "plot_bgcolor": "white", "hovermode": "closest", "legend": {"font": {"size": 12}}, **axes, **extra}


def points_by_test(data, x, y, ref, cols, labels, unit: str, first: bool, rows_mask=None,
                   mode="markers", size=6, **style) -> list[dict]:
    """Marker traces of (x, y): one per test (a legend group each), or one coloured by test beyond LEGEND_TESTS."""
    keep = np.ones(len(data), bool) if rows_mask is None else rows_mask
    hover = "%{text}<br>%{x:.4g}, %{y:.4g} " + unit + "<extra></extra>"
    named = "%{fullData.name}<br>%{x:.4g}, %{y:.4g} " + unit + "<extra></extra>"
    if data.n_tests > LEGEND_TESTS:
        order = np.flatnonzero(keep)
        k = data.test_index[order] % len(TAB20)       # colour by test: a number per point on a stepped scale
        scale = [[v, c] for j, c in enumerate(TAB20) for v in (j / len(TAB20), (j + 1) / len(TAB20))]
        return [{"type": "scattergl", "mode": "markers", "x": num(x[order]), "y": num(y[order]),
                 "xaxis": ref[0], "yaxis": ref[1], "showlegend": False, "hovertemplate": hover,
                 "text": np.asarray(data.tests, dtype=object)[data.test_index[order]].tolist(),
                 "marker": {"size": size - 1, "color": num(k + 0.5), "colorscale": scale, "cmin": 0,
                            "cmax": len(TAB20), "showscale": False}}]
    traces = []
    for i in range(data.n_tests):
        rows = rows_of_test(data, i)
        rows = rows[keep[rows]]
        traces.append({"type": "scatter", "mode": mode, "x": num(x[rows]), "y": num(y[rows]),
                       "xaxis": ref[0], "yaxis": ref[1], "name": labels[i], "legendgroup": labels[i],
                       "showlegend": first, "hovertemplate": named,
                       "marker": {"size": size, "color": cols[i]}, "line": {"color": cols[i]}, **style})
    return traces


def curves_by_test(data, y, ref, cols, name: str, dash: str, group: str, width=1.5, mode="lines",
                   symbol="circle", legend: bool = True) -> list[dict]:
    """Model curves (y against time) of every test in its colour, in one legend group per model."""
    out = []
    for i in range(data.n_tests):
        rows = rows_of_test(data, i)
        out.append({"type": "scatter", "mode": mode, "x": num(data.time_s[rows]), "y": num(y[rows]),
                    "xaxis": ref[0], "yaxis": ref[1], "name": name, "legendgroup": group, "showlegend": False,
                    "hoverinfo": "skip", "line": {"color": cols[i], "dash": dash, "width": width},
                    "marker": {"size": 5, "color": cols[i], "symbol": symbol}})
    if legend:                                                        # the legend entry of the group
        out.append({"type": "scatter", "mode": mode, "x": [None], "y": [None], "name": name, "legendgroup": group,
                    "xaxis": ref[0], "yaxis": ref[1], "line": {"color": "#333", "dash": dash, "width": width},
                    "marker": {"symbol": symbol, "color": "#333"}})
    return out


def prediction_on(fit, data):
    """*fit*'s prediction at the rows of *data*: its own where it was fitted on them, else computed there (a model
    selected on merged windows of a dense log and refitted on every row is drawn on one set of rows)."""
    if fit.data is data or (len(fit.data) == len(data) and np.array_equal(fit.data.time_s, data.time_s)):
        return fit.prediction
    return fit.model.predict(data, fit.values)


def signals_figure(fits) -> dict:
    """Measured points and model curves per test, both channels; one dash style per model (each drawn at the rows
    of the first model's data)."""
    data = fits[0][1].data
    axes, (rq, rt) = grid(1, 2, hgap=0.08, titles=["torque", "drum temperature"], xtitles=["time [s]"] * 2,
                          ytitles=["torque per drum [N·m]", "drum temperature [°C]"])
    cols, labels = colors(data.n_tests), legend_labels(data)
    traces = (points_by_test(data, data.time_s, data.torque_Nm, rq, cols, labels, "N·m", True)
              + points_by_test(data, data.time_s, data.drum_temp_C, rt, cols, labels, "°C", False))
    for j, (name, f) in enumerate(fits):
        pred = prediction_on(f, data)
        traces += curves_by_test(data, pred.torque_Nm, rq, cols, name, DASHES[j % 4], f"model {j}")
        traces += curves_by_test(data, pred.drum_temp_C, rt, cols, name, DASHES[j % 4], f"model {j}",
                                 legend=False)
    return {"data": traces, "layout": base_layout(460, axes)}


def residual_figure(fit, noise: dict, band: float = 2.5, title: str = "") -> dict:
    """Residuals (measured − model) against time, temperature, hand force and direction; the noise band shaded."""
    data = fit.data
    rt, rq = fit.residuals()
    covs = [("time [s]", data.time_s), ("model drum temperature [°C]", fit.prediction.drum_temp_C),
            ("hand force [N]", data.hand_force_N), ("direction (−1 uphill, +1 downhill)",
                                                     data.sign + np.random.default_rng(0).uniform(-0.15, 0.15,
                                                                                                  len(data)))]
    axes, refs = grid(2, 4, hgap=0.02, vgap=0.2, share_y_rows=True, xtitles=[c[0] for c in covs] * 2,
                      ytitles=["torque residual [N·m]", "", "", "", "temperature residual [°C]"])
    cols, labels = colors(data.n_tests), legend_labels(data)
    traces, shapes = [], []
    for row, (r, mask, sig, unit) in enumerate(((rq, None, noise["torque"], "N·m"),
                                                (rt, data.time_s > 0, noise["temperature"], "°C"))):
        for col, (_, x) in enumerate(covs):
            ref = refs[row * 4 + col]
            traces += points_by_test(data, x, r, ref, cols, labels, unit, row == 0 and col == 0, rows_mask=mask)
            shapes.append({"type": "rect", "xref": f"{ref[0]} domain", "yref": ref[1], "x0": 0, "x1": 1,
                           "y0": -band * sig, "y1": band * sig, "fillcolor": "#e6e6e6", "line": {"width": 0},
                           "layer": "below"})
            shapes.append({"type": "line", "xref": f"{ref[0]} domain", "yref": ref[1], "x0": 0, "x1": 1,
                           "y0": 0, "y1": 0, "line": {"color": "#888", "width": 1}, "layer": "below"})
    head = title or f"residuals; grey band ±{band:g}σ of the measurement noise"
    return {"data": traces, "layout": base_layout(620, axes, shapes=shapes,
                                                  title={"text": head, "x": 0.01, "font": {"size": 14}},
                                                  margin={"l": 70, "r": 20, "t": 50, "b": 60})}


def ladder_figure(data, rungs) -> dict:
    """RMSE per rung on each channel (own axis each), and the torque curves and residuals before/after.

    *rungs*: ``(name, fit)`` pairs, the paper model first, then the calibrated one (the "before"),
    the last one is the "after" (as in :class:`rollaway.identify.ladder.Ladder`).
    """
    axes, refs = grid(2, 2, hgap=0.1, vgap=0.2,
                      titles=["torque error", "temperature error", "measured and model", "residual before and after"],
                      xtitles=["torque RMSE [N·m]", "temperature RMSE [°C]", "time [s]", "time [s]"],
                      ytitles=["", "", "torque per drum [N·m]", "torque residual [N·m]"])
    names = [textwrap.fill(n.strip(), 30).replace("\n", "<br>") for n, _ in rungs]
    traces = []
    for ref, vals, color, unit in ((refs[0], [f.rmse_torque_Nm for _, f in rungs], "#1f77b4", "N·m"),
                                   (refs[1], [f.rmse_temp_C for _, f in rungs], "#ff7f0e", "°C")):
        traces.append({"type": "bar", "orientation": "h", "x": num(vals), "y": names, "xaxis": ref[0],
                       "yaxis": ref[1], "marker": {"color": color}, "showlegend": False,
                       "text": [f"{v:.3g}" for v in vals], "textposition": "outside", "cliponaxis": False,
                       "hovertemplate": "%{y}: %{x:.4g} " + unit + "<extra></extra>"})
    for k in (1, 2):
        axes[f"yaxis{'' if k == 1 else k}"].update(autorange="reversed", type="category")
    axes["yaxis2"]["showticklabels"] = False
    for k, vals in (("xaxis", [f.rmse_torque_Nm for _, f in rungs]),
                    ("xaxis2", [f.rmse_temp_C for _, f in rungs])):
        axes[k]["range"] = [0.0, 1.25 * max([v for v in vals if np.isfinite(v)] + [1e-9])]   # room for the labels
    before, after = (prediction_on(f, data) for f in (rungs[1][1], rungs[-1][1]))
    cols, labels = colors(data.n_tests), legend_labels(data)
    traces += points_by_test(data, data.time_s, data.torque_Nm, refs[2], cols, labels, "N·m", True, size=5)
    traces += curves_by_test(data, before.torque_Nm, refs[2], cols, "calibrated paper model", "dash",
                             "before", width=1)
    traces += curves_by_test(data, after.torque_Nm, refs[2], cols, "refined model", "solid", "after")
    traces += curves_by_test(data, data.torque_Nm - before.torque_Nm, refs[3], cols,
                             "residual, calibrated paper model", "dash", "before", width=1, mode="lines+markers")
    traces += curves_by_test(data, data.torque_Nm - after.torque_Nm, refs[3], cols,
                             "residual, refined model", "solid", "after", mode="lines+markers", symbol="square")
    shapes = [{"type": "line", "xref": f"{refs[3][0]} domain", "yref": refs[3][1], "x0": 0, "x1": 1, "y0": 0,
               "y1": 0, "line": {"color": "#666", "width": 1}, "layer": "below"}]
    return {"data": traces, "layout": base_layout(760, axes, shapes=shapes)}


def shape_figure(shape: dict, effect: str) -> dict:
    """The catalogue's factor and the data's (flexible, linear-spline) factor against the covariate."""
    axes, _ = grid(1, 1, titles=[f"{effect}: form partial — catalogue vs data"],
                   xtitles=[f"{shape['covariate']} [{shape['unit']}]"], ytitles=[f"factor on {shape['hook']}"])
    flex, knots = shape["flexible"], shape["flexible"]["knots"]
    traces = [{"type": "scatter", "mode": "markers", "x": num(shape["catalogue"]["x"]),
               "y": num(shape["catalogue"]["factor"]), "name": f"catalogue form ({effect})",
               "marker": {"size": 4, "color": "#1f77b4"}},
              {"type": "scatter", "mode": "lines", "x": num(flex["x"]), "y": num(flex["factor"]),
               "name": "what the data want (linear spline)", "line": {"color": "#d62728", "width": 2.5}},
              {"type": "scatter", "mode": "markers", "x": num(knots),
               "y": num(np.interp(knots, flex["x"], flex["factor"])), "name": "spline knots",
               "marker": {"size": 8, "color": "#d62728"}}]
    return {"data": traces, "layout": base_layout(420, axes)}
