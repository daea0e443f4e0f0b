"""Bench measurements in memory: :class:`Measurements`, validated samples flattened over tests, and the
physical ranges every reader checks the samples against.

Read by :mod:`rollaway.bench.measurements` (the strict CSV loader) and :mod:`rollaway.bench.sources` (the
streaming reader), both through :class:`rollaway.bench.reduction.Reducer`.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rollaway.errors import UserError

REQUIRED = ("test_id", "direction", "hand_force_N", "time_s", "drum_temp_C", "torque_Nm")
OPTIONAL = ("ambient_C",)
NUMERIC = ("hand_force_N", "time_s", "drum_temp_C", "torque_Nm", "ambient_C")
LIMITS = {"hand_force_N": (0.0, 5000.0, "N"), "time_s": (0.0, 1e7, "s"), "drum_temp_C": (-60.0, 1000.0, "°C"),
          "torque_Nm": (-1e5, 1e5, "N·m"), "ambient_C": (-60.0, 80.0, "°C")}
MAX_LISTED = 20


@dataclass
class Measurements:
    """Validated samples, flattened over tests (arrays of equal length, file order)."""

    test_id: np.ndarray
    direction: np.ndarray
    hand_force_N: np.ndarray
    time_s: np.ndarray
    drum_temp_C: np.ndarray
    torque_Nm: np.ndarray
    ambient_C: np.ndarray | None = None
    source: str = "<data>"
    line: np.ndarray | None = None
    notes: list[str] = field(default_factory=list)
    torque_sigma_Nm: np.ndarray | None = None   # per-sample noise level (set by diagnose; weights the fits)
    temp_sigma_C: np.ndarray | None = None      # per-sample drum-temperature noise level (idem)
    count: np.ndarray | None = None             # raw samples averaged into each row (None: one each)
    reduction: object | None = None             # rows read/kept/reduced, raw-rate noise (identify.reduction)

    def __post_init__(self):
        ids = np.asarray(self.test_id)
        uniq, first_row, inverse = np.unique(ids, return_index=True, return_inverse=True)
        rank = np.argsort(first_row, kind="stable")                  # tests in order of appearance
        where = np.empty(len(rank), dtype=int)
        where[rank] = np.arange(len(rank))
        self.tests = uniq[rank].tolist()
        self.test_index = where[inverse.ravel()]
        self.sign = np.where(self.direction == "downhill", 1.0, -1.0)
        # each test's reading at its earliest time (the first such row): its T_0
        order = np.lexsort((self.time_s, self.test_index))
        first = order[np.r_[0, np.flatnonzero(np.diff(self.test_index[order])) + 1]] if len(order) else order
        t0 = np.asarray(self.drum_temp_C, float)[first]
        self.test_initial_temp_C = t0
        self.initial_temp_C = t0[self.test_index]

    def __len__(self) -> int:
        return len(self.time_s)

    @property
    def n_tests(self) -> int:
        return len(self.tests)

    def test_info(self) -> list[dict]:
        """One dict per test: id, direction, hand force, T_0, number of samples, duration."""
        out = []
        for i, t in enumerate(self.tests):
            rows = self.test_index == i
            first = np.flatnonzero(rows)[0]
            out.append({"test_id": t, "direction": str(self.direction[first]),
                        "hand_force_N": float(self.hand_force_N[first]),
                        "initial_temp_C": float(self.test_initial_temp_C[i]),
                        "samples": int(rows.sum() if self.count is None else self.count[rows].sum()),
                        "duration_s": float(self.time_s[rows].max())})
        return out

    def rows_info(self) -> dict:
        """Rows read from the log, kept, and seen by the fits (after a reduction), for reports and JSON."""
        red = self.reduction
        if red is None:
            return {"rows_read": len(self), "rows_kept": len(self), "rows": len(self), "window_s": None,
                    "notes": list(self.notes)}
        return {"rows_read": red.rows_read, "rows_kept": red.rows_kept, "rows": len(self), "window_s": red.window_s,
                "notes": list(self.notes)}

    def subset(self, mask) -> "Measurements":
        """Rows where *mask* is true (whole tests keep their T_0)."""
        m = np.asarray(mask, bool)
        return Measurements(self.test_id[m], self.direction[m], self.hand_force_N[m], self.time_s[m],
                            self.drum_temp_C[m], self.torque_Nm[m],
                            None if self.ambient_C is None else self.ambient_C[m], self.source,
                            None if self.line is None else self.line[m], list(self.notes),
                            None if self.torque_sigma_Nm is None else self.torque_sigma_Nm[m],
                            None if self.temp_sigma_C is None else self.temp_sigma_C[m],
                            None if self.count is None else self.count[m], self.reduction)

    def to_frame(self):
        import pandas as pd
        cols = {"test_id": self.test_id, "direction": self.direction, "hand_force_N": self.hand_force_N,
                "time_s": self.time_s, "drum_temp_C": self.drum_temp_C, "torque_Nm": self.torque_Nm}
        if self.ambient_C is not None:
            cols["ambient_C"] = self.ambient_C
        return pd.DataFrame(cols)

    def to_csv(self, path: str | Path) -> None:
        self.to_frame().to_csv(path, index=False, float_format="%.6g")

    def _repr_html_(self) -> str:  # notebooks
        return (f"<b>Measurements</b> {self.source}: {len(self)} samples, {self.n_tests} tests"
                + self.to_frame().head(8)._repr_html_())


def _raise(problems: list[str]) -> None:
    shown = problems[:MAX_LISTED]
    more = len(problems) - len(shown)
    msg = shown[0]
    if len(problems) > 1:
        msg += f" (and {len(problems) - 1} more problem{'s' if len(problems) > 2 else ''})"
        msg += "".join(f"\n  {p}" for p in shown[1:])
        if more:
            msg += f"\n  … {more} more"
    raise UserError(msg)
