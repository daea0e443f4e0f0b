"""The error ladder as a matplotlib figure (PNG files; :meth:`rollaway.identify.ladder.Ladder.plot`).

The HTML reports draw the same content with plotly.js (:func:`rollaway.identify.report_figures.ladder_figure`).
"""
from __future__ import annotations

import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from rollaway.identify.report_figures import colors, legend_labels, rows_of_test  # noqa: E402

STYLE = {"font.size": 11, "axes.titlesize": 11, "axes.labelsize": 11, "legend.fontsize": 10,
         "xtick.labelsize": 10, "ytick.labelsize": 10}


def ladder_figure(ladder):
    """RMSE per rung on each channel (own axis each), and the torque curves and residuals before/after."""
    with plt.rc_context(STYLE):
        fig, axes = plt.subplots(1, 4, figsize=(15, 4.6), gridspec_kw={"width_ratios": [1, 1, 1.4, 1.4]})
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
        data, before, after = ladder.data, ladder.baseline, ladder.final
        cols = colors(data.n_tests)
        for i in range(data.n_tests):
            rows = rows_of_test(data, i)
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
        handles = ([Line2D([], [], color=c, marker="o", ls="", label=lab) for c, lab in zip(cols, legend_labels(data))]
                   + [Line2D([], [], color="0.2", ls="--", label="calibrated paper model"),
                      Line2D([], [], color="0.2", ls="-", label="refined model")])
        fig.legend(handles=handles, loc="center right", fontsize=9)
        fig.subplots_adjust(left=0.17, right=0.84, bottom=0.13, top=0.92, wspace=0.3)
        return fig
