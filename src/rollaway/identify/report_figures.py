"""The figures of the bench reports (matplotlib, fixed margins: no layout pass at all).

Times are in seconds everywhere (as in the tables); each test has one colour, named in a
legend with its direction and hand force; fonts are at least 10 pt at the size shown.
"""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

STYLE = {"font.size": 11, "axes.titlesize": 11, "axes.labelsize": 11, "legend.fontsize": 10,
         "xtick.labelsize": 10, "ytick.labelsize": 10}
LINESTYLES = ["--", "-", ":", "-."]


def figure(*args, **kw):
    with plt.rc_context(STYLE):
        return plt.subplots(*args, **kw)


def colors(n):
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


def test_labels(data) -> list[str]:
    """'T1 downhill 200 N' per test, in test order."""
    info = {t["test_id"]: t for t in data.test_info()}
    return [f"{tid} {info[tid]['direction']} {info[tid]['hand_force_N']:.0f} N" for tid in data.tests]


def _rows(data, i):
    rows = np.flatnonzero(data.test_index == i)
    return rows[np.argsort(data.time_s[rows])]


def signals_figure(fits):
    """Measured points and model curves per test, both channels; one line style per model."""
    with plt.rc_context(STYLE):
        data = fits[0][1].data
        fig, axes = figure(1, 2, figsize=(11, 4.6))
        cols = colors(data.n_tests)
        for i in range(data.n_tests):
            rows = _rows(data, i)
            t = data.time_s[rows]
            axes[0].plot(t, data.torque_Nm[rows], "o", color=cols[i], ms=4)
            axes[1].plot(t, data.drum_temp_C[rows], "o", color=cols[i], ms=4)
            for j, (_, f) in enumerate(fits):
                axes[0].plot(t, f.prediction.torque_Nm[rows], LINESTYLES[j % 4], color=cols[i], lw=1.2)
                axes[1].plot(t, f.prediction.drum_temp_C[rows], LINESTYLES[j % 4], color=cols[i], lw=1.2)
        axes[0].set(xlabel="time [s]", ylabel="torque per drum [N·m]", title="torque")
        axes[1].set(xlabel="time [s]", ylabel="drum temperature [°C]", title="drum temperature")
        tests = [Line2D([], [], color=c, marker="o", ls="", label=lab) for c, lab in zip(cols, test_labels(data))]
        models = [Line2D([], [], color="0.2", ls=LINESTYLES[j % 4], label=name) for j, (name, _) in enumerate(fits)]
        axes[0].legend(handles=tests, title="measured", ncol=2, fontsize=9, loc="best")
        axes[1].legend(handles=models, title="model", loc="best")
        fig.subplots_adjust(left=0.07, right=0.99, bottom=0.12, top=0.92, wspace=0.2)
        return fig


def residual_figure(fit, noise: dict, band: float = 2.5, title: str = ""):
    """Residuals (measured − model) against time, temperature, hand force and direction; the noise band shaded."""
    with plt.rc_context(STYLE):
        data = fit.data
        rt, rq = fit.residuals()
        hot = data.time_s > 0
        covs = [("time [s]", data.time_s), ("model drum temperature [°C]", fit.prediction.drum_temp_C),
                ("hand force [N]", data.hand_force_N), ("direction (−1 uphill, +1 downhill)", data.sign)]
        fig, axes = figure(2, 4, figsize=(13, 6), sharey="row")
        cols = colors(data.n_tests)
        c = np.array([cols[i] for i in data.test_index])
        jitter = np.random.default_rng(0).uniform(-0.15, 0.15, len(data))
        for row, (r, m, sig, lab) in enumerate(((rq, np.ones(len(rq), bool), noise["torque"], "torque residual [N·m]"),
                                                (rt, hot, noise["temperature"], "temperature residual [°C]"))):
            for col, (name, x) in enumerate(covs):
                ax = axes[row, col]
                ax.axhspan(-band * sig, band * sig, color="0.9", zorder=0)
                ax.axhline(0, color="0.5", lw=0.8)
                xx = x + (jitter if col == 3 else 0.0)
                ax.scatter(xx[m], r[m], c=c[m], s=14)
                ax.set_xlabel(name)
            axes[row, 0].set_ylabel(lab)
        tests = [Line2D([], [], color=col, marker="o", ls="", label=lab) for col, lab in zip(cols, test_labels(data))]
        fig.legend(handles=tests, loc="center right", title="test")
        fig.suptitle(title or f"residuals; grey band ±{band:g}σ of the measurement noise")
        fig.subplots_adjust(left=0.07, right=0.83, bottom=0.1, top=0.93, wspace=0.08, hspace=0.3)
        return fig


def ladder_figure(ladder):
    """RMSE per rung on each channel (own axis each), and the torque curves and residuals before/after."""
    with plt.rc_context(STYLE):
        fig, axes = figure(1, 4, figsize=(15, 4.6), gridspec_kw={"width_ratios": [1, 1, 1.4, 1.4]})
        import textwrap
        names = [textwrap.fill(n.strip(), 22) for n, _ in ladder.rungs]
        y = np.arange(len(names))[::-1]
        for ax, vals, unit, color, what in (
                (axes[0], [f.rmse_torque_Nm for _, f in ladder.rungs], "N·m", "tab:blue", "torque"),
                (axes[1], [f.rmse_temp_C for _, f in ladder.rungs], "°C", "tab:orange", "temperature")):
            ax.barh(y, vals, 0.6, color=color)
            for yi, v in zip(y, vals):
                ax.text(v, yi, f" {v:.3g}", va="center", fontsize=10)
            ax.set_xlim(0, max(vals + [1e-9]) * 1.35)
            ax.set_xlabel(f"{what} RMSE [{unit}]")
            ax.set_title(f"{what} error")
        axes[0].set_yticks(y, names)
        axes[1].set_yticks(y, [""] * len(y))
        data = ladder.data
        before, after = ladder.baseline, ladder.final
        cols = colors(data.n_tests)
        for i in range(data.n_tests):
            rows = _rows(data, i)
            tm = data.time_s[rows]
            axes[2].plot(tm, data.torque_Nm[rows], "o", ms=3.5, color=cols[i])
            axes[2].plot(tm, before.prediction.torque_Nm[rows], "--", color=cols[i], lw=1)
            axes[2].plot(tm, after.prediction.torque_Nm[rows], "-", color=cols[i], lw=1.2)
            axes[3].plot(tm, data.torque_Nm[rows] - before.prediction.torque_Nm[rows], "--o", ms=2.5, color=cols[i],
                         lw=.8)
            axes[3].plot(tm, data.torque_Nm[rows] - after.prediction.torque_Nm[rows], "-s", ms=2.5, color=cols[i], lw=1)
        axes[2].set(xlabel="time [s]", ylabel="torque per drum [N·m]", title="measured and model")
        axes[3].axhline(0, color="0.4", lw=0.8)
        axes[3].set(xlabel="time [s]", ylabel="torque residual [N·m]", title="residual before and after")
        handles = ([Line2D([], [], color=c, marker="o", ls="", label=lab) for c, lab in zip(cols, test_labels(data))]
                   + [Line2D([], [], color="0.2", ls="--", label="calibrated paper model"),
                      Line2D([], [], color="0.2", ls="-", label="refined model")])
        fig.legend(handles=handles, loc="center right", fontsize=9)
        fig.subplots_adjust(left=0.17, right=0.84, bottom=0.13, top=0.92, wspace=0.3)
        return fig
