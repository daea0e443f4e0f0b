"""Self-contained HTML reports (matplotlib PNGs embedded as base64 data URIs; no network needed)."""
from __future__ import annotations

import base64
import html
import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from rollaway.identify.calibrate import FitResult  # noqa: E402

CSS = ("body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;font-size:90%}td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}"
       "th{background:#eee}td:first-child{text-align:left}.verdict{font-size:130%;padding:.5em;background:#eef6ee}"
       "img{max-width:100%}li{margin:.3em 0}")


def _png(fig) -> str:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90, bbox_inches="tight")
    plt.close(fig)
    return f'<img alt="figure" src="data:image/png;base64,{base64.b64encode(buf.getvalue()).decode()}">'


def _colors(n):
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


def signals_figure(fits: list[tuple[str, FitResult]]):
    """Measured points and model curves per test, both channels; one line style per model."""
    data = fits[0][1].data
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    cols = _colors(data.n_tests)
    styles = ["--", "-", ":", "-."]
    for i, tid in enumerate(data.tests):
        rows = np.flatnonzero(data.test_index == i)
        rows = rows[np.argsort(data.time_s[rows])]
        t = data.time_s[rows] / 60
        axes[0].plot(t, data.torque_Nm[rows], "o", color=cols[i], ms=4, label=tid)
        axes[1].plot(t, data.drum_temp_C[rows], "o", color=cols[i], ms=4)
        for j, (_, f) in enumerate(fits):
            axes[0].plot(t, f.prediction.torque_Nm[rows], styles[j % 4], color=cols[i], lw=1.2)
            axes[1].plot(t, f.prediction.drum_temp_C[rows], styles[j % 4], color=cols[i], lw=1.2)
    axes[0].set(xlabel="time [min]", ylabel="torque per drum [N·m]", title="torque: points measured, lines model")
    axes[1].set(xlabel="time [min]", ylabel="drum temperature [°C]", title="drum temperature")
    axes[0].legend(fontsize=7, ncol=2)
    if len(fits) > 1:
        axes[1].text(0.98, 0.95, "\n".join(f"{styles[j % 4]}  {n}" for j, (n, _) in enumerate(fits)),
                     transform=axes[1].transAxes, ha="right", va="top", fontsize=8, family="monospace")
    fig.tight_layout()
    return fig


def residual_figure(fit: FitResult, noise: dict, band: float = 2.5):
    """Residuals (measured − model) against time, temperature, hand force and direction; the noise band shaded."""
    data = fit.data
    rt, rq = fit.residuals()
    hot = data.time_s > 0
    covs = [("time [min]", data.time_s / 60), ("model drum temperature [°C]", fit.prediction.drum_temp_C),
            ("hand force [N]", data.hand_force_N), ("direction (−1 uphill, +1 downhill)", data.sign)]
    fig, axes = plt.subplots(2, 4, figsize=(14, 6), sharey="row")
    cols = _colors(data.n_tests)
    c = [cols[i] for i in data.test_index]
    for row, (r, m, sig, lab) in enumerate(((rq, np.ones(len(rq), bool), noise["torque"], "torque residual [N·m]"),
                                            (rt, hot, noise["temperature"], "temperature residual [°C]"))):
        for col, (name, x) in enumerate(covs):
            ax = axes[row, col]
            jitter = (np.random.default_rng(0).uniform(-0.15, 0.15, len(x)) if col == 3 else 0.0)
            ax.axhspan(-band * sig, band * sig, color="0.9", zorder=0)
            ax.axhline(0, color="0.5", lw=0.8)
            ax.scatter((x + jitter)[m], r[m], c=[c[k] for k in np.flatnonzero(m)], s=12)
            ax.set_xlabel(name, fontsize=8)
        axes[row, 0].set_ylabel(lab)
    fig.suptitle(f"residuals of {'baseline' + ''.join(' + ' + e for e in fit.effects)}; grey band ±{band:g}σ noise",
                 fontsize=10)
    fig.tight_layout()
    return fig


def ladder_figure(ladder):
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), gridspec_kw={"width_ratios": [1, 1.3, 1.3]})
    names = [n.strip() for n, _ in ladder.rungs]
    q = [f.rmse_torque_Nm for _, f in ladder.rungs]
    t = [f.rmse_temp_C for _, f in ladder.rungs]
    y = np.arange(len(names))[::-1]
    axes[0].barh(y + 0.2, q, 0.4, label="torque [N·m]", color="tab:blue")
    ax2 = axes[0].twiny()
    ax2.barh(y - 0.2, t, 0.4, label="temperature [°C]", color="tab:orange")
    axes[0].set_yticks(y, names, fontsize=8)
    axes[0].set_xlabel("torque RMSE [N·m] (blue)")
    ax2.set_xlabel("temperature RMSE [°C] (orange)")
    data = ladder.data
    before, after = ladder.baseline, ladder.final
    cols = _colors(data.n_tests)
    for i in range(data.n_tests):
        rows = np.flatnonzero(data.test_index == i)
        rows = rows[np.argsort(data.time_s[rows])]
        tm = data.time_s[rows] / 60
        axes[1].plot(tm, data.torque_Nm[rows], "o", ms=3.5, color=cols[i])
        axes[1].plot(tm, before.prediction.torque_Nm[rows], "--", color=cols[i], lw=1)
        axes[1].plot(tm, after.prediction.torque_Nm[rows], "-", color=cols[i], lw=1.2)
        axes[2].plot(tm, data.torque_Nm[rows] - before.prediction.torque_Nm[rows], "--o", ms=2.5, color=cols[i], lw=.8)
        axes[2].plot(tm, data.torque_Nm[rows] - after.prediction.torque_Nm[rows], "-s", ms=2.5, color=cols[i], lw=1)
    axes[1].set(xlabel="time [min]", ylabel="torque [N·m]", title="measured (o), baseline (--), refined (—)")
    axes[2].axhline(0, color="0.4", lw=0.8)
    axes[2].set(xlabel="time [min]", ylabel="torque residual [N·m]", title="residual before (--) and after (—)")
    fig.tight_layout()
    return fig


def params_table(fit: FitResult) -> str:
    rows = "".join(
        f"<tr><td>{html.escape(e.name)}</td><td>{e.value:.5g}</td><td>{e.stderr:.3g}</td><td>{e.ci95[0]:.4g}</td>"
        f"<td>{e.ci95[1]:.4g}</td><td>{html.escape(e.unit)}</td><td>[{e.lower:g}, {e.upper:g}]</td>"
        f"<td>{'at ' + e.at_bound + ' bound' if e.at_bound else ''}</td></tr>" for e in fit.estimates.values())
    return ("<table><tr><th>parameter</th><th>value</th><th>std. error</th><th>95 % low</th><th>95 % high</th>"
            f"<th>unit</th><th>bounds</th><th>warning</th></tr>{rows}</table>")


def _page(title: str, body: str) -> str:
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{CSS}</style></head><body><h1>{html.escape(title)}</h1>{body}"
            "<p style='color:#888;font-size:80%'>rollaway bench report — self-contained, no network needed.</p>"
            "</body></html>")


def _write(path, text):
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


def _ul(items):
    return "<ul>" + "".join(f"<li>{html.escape(w)}</li>" for w in items) + "</ul>"


def comparison_report(cmp, path) -> None:
    fit = cmp.fit
    body = (f"<p>Data: {html.escape(cmp.data.source)} — {len(cmp.data)} samples, {cmp.data.n_tests} tests. Model: "
            f"baseline{html.escape(''.join(' + ' + e for e in fit.effects))}.</p><h2>Where it fails</h2>"
            + _ul(cmp.words) + "<h2>Errors per test</h2><pre>" + html.escape(cmp.table()) + "</pre>"
            "<h2>Signals</h2>" + _png(signals_figure([("model", fit)]))
            + "<h2>Residuals</h2>" + _png(residual_figure(fit, {k: v.sigma for k, v in cmp.noise.items()}))
            + ("<h2>Parameters</h2>" + params_table(fit) if fit.estimates else ""))
    _write(path, _page("rollaway compare", body))


def diagnosis_report(diag, path) -> None:
    from rollaway.identify.ladder import Ladder
    from rollaway.identify.shape import shape_figure
    noise = {"torque": diag.noise_torque.sigma, "temperature": diag.noise_temp.sigma}
    rungs = [("paper defaults", diag.paper), ("calibrated baseline", diag.baseline)]
    if diag.refined is not diag.baseline:
        rungs.append(("baseline + " + " + ".join(diag.refined.effects), diag.refined))
    cand = "".join(f"<tr><td>{html.escape(c.effect)}</td><td>{c.delta_bic:.1f}</td><td>{c.fit.rmse_torque_Nm:.3g}</td>"
                   f"<td>{c.fit.rmse_temp_C:.3g}</td><td>{'' if c.cv_score is None else f'{c.cv_score:.1f}'}</td></tr>"
                   for c in diag.candidates)
    body = (f"<p class='verdict'>Verdict: <b>{html.escape(diag.verdict)}</b>"
            f"{' (indistinguishable from ' + html.escape(', '.join(diag.indistinguishable_from)) + ')' if diag.indistinguishable_from else ''}"
            f" — remaining structure: <b>{'yes' if diag.remaining_structure else 'no'}</b></p>"
            + _ul(diag.evidence)
            + "<h2>Candidates (best first)</h2><table><tr><th>effect</th><th>ΔBIC</th><th>torque RMSE N·m</th>"
              f"<th>temp RMSE °C</th><th>leave-one-test-out score</th></tr>{cand}</table>"
            + "<h2>Error ladder</h2>" + _png(ladder_figure(Ladder(diag.data, rungs)))
            + "<h2>Signals: calibrated baseline (--) and refined (—)</h2>"
            + _png(signals_figure([("baseline", diag.baseline), ("refined", diag.refined)]))
            + "<h2>Residuals of the calibrated baseline</h2>" + _png(residual_figure(diag.baseline, noise))
            + "<h2>Residuals of the refined model</h2>" + _png(residual_figure(diag.refined, noise))
            + (f"<h2>Form partial: what the data want</h2>" + _png(shape_figure(diag.shape, diag.shape.get("effect", diag.verdict)))
               if diag.shape else "")
            + "<h2>Refined model parameters (95 % intervals)</h2>" + params_table(diag.refined))
    _write(path, _page(f"rollaway diagnose — {diag.data.source}", body))


def ladder_report(ladder, path) -> None:
    body = ("<h2>Error ladder</h2><pre>" + html.escape(ladder.table()) + "</pre>" + _png(ladder_figure(ladder))
            + "<h2>Signals: calibrated baseline (--) and refined (—)</h2>"
            + _png(signals_figure([("baseline", ladder.baseline), ("refined", ladder.final)]))
            + "<h2>Parameters (95 % intervals)</h2>" + params_table(ladder.final)
            + (_ul(ladder.final.warnings) if ladder.final.warnings else ""))
    _write(path, _page(f"rollaway fit — {ladder.data.source}", body))
