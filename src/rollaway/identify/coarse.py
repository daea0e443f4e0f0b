"""A coarser copy of dense measurements for model selection.

Selection fits every candidate effect, several times; on a dense log (a reduced 10–100 Hz log
keeps ~250 window means a test) that is most of ``diagnose``'s time, while the choice between
effects does not need every window.  :func:`coarsen` merges consecutive rows of each test into
groups (count-weighted means of time and both channels, counts added, so the fits weight each
merged row by σ/√count), keeping every test's first row (its T_0) alone and never merging over
more than :data:`MAX_WINDOW_S`: the model is evaluated at a group's mean time, and the cooling
curve's curvature over 180 s moves the mean by ≤ 0.25 °C at the hot start, a quarter of the noise of a mean of three 1-minute samples.  The
final model is refitted on all rows.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

SELECTION_ROWS = 800          # above this many rows, selection runs on a coarser copy
MAX_WINDOW_S = 180.0          # no group spans more than this [s]: curvature moves a mean by ≤ 0.3 of its SE [assumed]


def coarsen(data, max_rows: int = SELECTION_ROWS):
    """*data* with consecutive rows of each test merged (or *data* itself when already small enough)."""
    n = len(data)
    if n <= max_rows:
        return data
    k = math.ceil(n / max_rows)
    count = np.ones(n) if data.count is None else np.asarray(data.count, float)
    groups = np.empty(n, dtype=np.int64)
    next_group = 0
    order = np.lexsort((data.time_s, data.test_index))
    for i in range(data.n_tests):
        rows = order[data.test_index[order] == i]
        t = data.time_s[rows]
        dt = float(np.median(np.diff(t))) if rows.size > 1 else MAX_WINDOW_S
        kt = max(1, min(k, int(MAX_WINDOW_S // max(dt, 1e-9))))
        g = np.concatenate([[0], 1 + np.arange(rows.size - 1) // kt])
        groups[rows] = next_group + g
        next_group += int(g[-1]) + 1
    if next_group >= n:
        return data
    w = np.bincount(groups, count, next_group)

    def mean(x):
        return np.bincount(groups, np.asarray(x, float) * count, next_group) / w
    first = np.zeros(next_group, dtype=np.int64)
    first[groups[::-1]] = np.arange(n)[::-1]          # a representative row of each group (its first)
    out = dataclasses.replace(
        data, test_id=data.test_id[first], direction=data.direction[first], hand_force_N=data.hand_force_N[first],
        time_s=mean(data.time_s), drum_temp_C=mean(data.drum_temp_C), torque_Nm=mean(data.torque_Nm),
        ambient_C=None if data.ambient_C is None else mean(data.ambient_C),
        line=None if data.line is None else data.line[first], notes=[], torque_sigma_Nm=None, temp_sigma_C=None,
        count=w)
    return out                      # groups are numbered test by test, in time: rows stay in that order


__all__ = ["MAX_WINDOW_S", "SELECTION_ROWS", "coarsen"]
