"""The unit of work between the bench-log readers (:mod:`.sources`, :mod:`.asam_mdf`) and the reduction
(:mod:`.reduction`): consecutive rows of one file, already in canonical quantities and SI units."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.bench.columns import Resolved


@dataclass
class Text:
    """A text column of a batch: per-row codes into *names* (−1: empty)."""

    codes: np.ndarray
    names: list[str]

    @classmethod
    def constant(cls, value: str, n: int) -> "Text":
        return cls(np.zeros(n, np.int64), [value])


@dataclass
class Batch:
    """Consecutive rows of one file in canonical quantities and SI units."""

    where: str                    # the file, for messages
    first: int                    # line (CSV) or row (Parquet) number of the first row
    word: str                     # "line" or "row"
    test_id: Text
    direction: Text | None
    hand_force_N: np.ndarray | None
    time_s: np.ndarray
    drum_temp_C: np.ndarray
    torque_Nm: np.ndarray
    ambient_C: np.ndarray | None
    columns: dict[str, Resolved]  # quantity → the file's column (for messages)
    lines: np.ndarray | None = None  # each row's line number where rows are not consecutive lines (None: first + i)

    def __len__(self) -> int:
        return len(self.time_s)

    def line(self, i: int) -> int:
        return int(self.lines[i]) if self.lines is not None else self.first + int(i)

    def at(self, i: int) -> str:
        return f"{self.where}, {self.word} {self.line(i)}"

    def column(self, quantity: str) -> str:
        r = self.columns.get(quantity)
        return r.describe() if r else f"'{quantity}'"
