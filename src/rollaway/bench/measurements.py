"""Bench measurements: load and validate the bench CSV format.

One row per sample, columns ``test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm``
and optionally ``ambient_C`` (a logged ambient, one reading per sample).  Each test starts at
``time_s = 0`` (lever applied); its drum-temperature reading there is a noisy measurement of
its T_0 (``test_initial_temp_C``; the fits estimate T_0 with the other parameters); ``torque_Nm``
is per drum.  Every problem is reported
with file, line and column; nothing is guessed.
"""
from __future__ import annotations

import csv
import difflib
import math
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
        self.tests = list(dict.fromkeys(self.test_id.tolist()))
        index = {t: i for i, t in enumerate(self.tests)}
        self.test_index = np.array([index[t] for t in self.test_id], dtype=int)
        self.sign = np.where(self.direction == "downhill", 1.0, -1.0)
        t0 = np.empty(len(self.tests))
        for i in range(len(self.tests)):
            rows = np.flatnonzero(self.test_index == i)
            t0[i] = self.drum_temp_C[rows[np.argmin(self.time_s[rows])]]
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

    @classmethod
    def from_frame(cls, frame, source: str = "<DataFrame>") -> "Measurements":
        """Validate a pandas DataFrame with the CSV's columns (rows numbered as CSV lines 2, 3, …)."""
        header = [str(c) for c in frame.columns]
        rows = [["" if _isnan(v) else str(v) for v in r] for r in frame.itertuples(index=False)]
        return _parse(header, [(i + 2, r) for i, r in enumerate(rows)], source)

    def _repr_html_(self) -> str:  # notebooks
        return (f"<b>Measurements</b> {self.source}: {len(self)} samples, {self.n_tests} tests"
                + self.to_frame().head(8)._repr_html_())


def _isnan(v) -> bool:
    return isinstance(v, float) and math.isnan(v)


def load_measurements(path: str | Path, window_s: float | None = 0) -> Measurements:
    """Read and validate a measurement CSV; raise UserError listing every problem.

    The file is tokenized here (Python's csv module: exact line numbers, every bad cell listed); the rules
    for each test (one force and direction, time order, start at 0, rows before the lever, the time unit)
    are the streaming reader's (:class:`rollaway.bench.reduction.Reducer`), so a log gives the same rows or
    the same error whichever reader takes it.  *window_s*: 0 every sample a row, None automatic."""
    path = Path(path)
    if not path.is_file():
        raise UserError(f"measurement file '{path}' does not exist; check the path")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise UserError(f"{path}, line 1: not a UTF-8 text file; save the measurements as UTF-8 CSV") from None
    if "\x00" in text:
        line = text[:text.index("\x00")].count("\n") + 1
        raise UserError(f"{path}, line {line}: a NUL byte; this is not a text CSV file — export the data again")
    from rollaway.bench.readers import sniff_dialect
    lines = text.splitlines()
    filled = [x for x in lines if x.strip()]
    delim, decimal = sniff_dialect(filled[0], filled[1] if len(filled) > 1 else "") if filled else (",", ".")
    numbered = csv_rows(lines, path, delim)
    if not numbered:
        raise UserError(f"{path}, line 1: the file is empty; expected the header "
                        f"{','.join(REQUIRED)}")
    (hline, header), body = numbered[0], numbered[1:]
    return _parse([h.strip() for h in header], body, str(path), hline, window_s, (delim, decimal))


def csv_rows(lines, path, delimiter: str = ",") -> list[tuple[int, list[str]]]:
    """(line number, cells) of the header (the first row with a cell that is not blank) and of every non-empty
    row after it (as pyarrow reads them); a broken quote or an oversized cell is a UserError."""
    reader = csv.reader(lines, delimiter=delimiter)
    numbered = []
    try:
        for row in reader:
            if any(c.strip() for c in row) if not numbered else row:
                numbered.append((reader.line_num, row))
    except csv.Error as exc:
        raise UserError(f"{path}, line {reader.line_num}: {exc}; a cell that long or broken quoting is not bench "
                        f"data — check the quotes on this line") from None
    return numbered


def _parse(header: list[str], body: list[tuple[int, list[str]]], src: str, hline: int = 1,
           window_s: float | None = 0, dialect: tuple[str, str] = (",", ".")) -> Measurements:
    """Header and cells as the streaming reader tokenizes them (a ragged row, a cell that is not a number: listed
    here); empty cells, test ids, directions, ranges and each test's rules: the reducer's."""
    from rollaway.bench.readers import check_names, parse_number, ragged_message
    check_names(header, f"{src}, line {hline}")
    problems: list[str] = []
    known = REQUIRED + OPTIONAL
    notes = []
    for name in sorted({h for h in header if header.count(h) > 1}):
        problems.append(f"{src}, line {hline}, column '{name}': duplicate column; keep one")
    for name in REQUIRED:
        if name not in header:
            extra = [h for h in header if h not in known]
            close = difflib.get_close_matches(name, extra, n=1, cutoff=0.5)
            hint = f" (the header has '{close[0]}': rename it '{name}')" if close else ""
            problems.append(f"{src}, line {hline}, column '{name}': missing column{hint}; the header "
                            f"must contain {','.join(REQUIRED)} (optional ambient_C)")
    ignored = [h for h in header if h not in known]
    if ignored:
        notes.append(f"{src}: ignoring column(s) {', '.join(repr(h) for h in ignored)} (not part of the format)")
    if problems:
        _raise(problems)
    if not body:
        _raise([f"{src}, line {hline + 1}: no data rows after the header; add one row per sample"])
    col = {name: header.index(name) for name in known if name in header}
    values: dict[str, list] = {name: [] for name in col}
    for lineno, row in body:            # in file order, as the streaming reader finds them
        if len(row) != len(header):
            problems.append(ragged_message(src, lineno, len(row), len(header), dialect[0]))
            continue
        for name, j in col.items():
            if name in ("test_id", "direction"):
                values[name].append(row[j].strip())
                continue
            v = parse_number(row[j], dialect[1])
            if v is None:
                problems.append(f"{src}, line {lineno}, column '{name}': {row[j].strip()!r} is not a number; give a "
                                f"value in {LIMITS[name][2]}")
            values[name].append(math.nan if v is None else v)
    if problems:
        _raise(problems)
    return _through_reducer(values, np.array([n for n, _ in body]), src, hline, window_s, notes)


def _through_reducer(values: dict, lines: np.ndarray, src: str, hline: int, window_s, notes) -> Measurements:
    """The per-test rules and the rows of :class:`rollaway.bench.reduction.Reducer` (one set of rules)."""
    from rollaway.bench.batch import Batch, Text
    from rollaway.bench.reduction import Reducer

    def text(cells):
        names = [c for c in dict.fromkeys(cells) if c]
        index = {c: i for i, c in enumerate(names)}
        return Text(np.array([index.get(c, -1) for c in cells], np.int64), names)

    arr = {k: np.array(v, float) for k, v in values.items() if k not in ("test_id", "direction")}
    red = Reducer(keep_raw=2 ** 62 if window_s == 0 else None)
    red.add(Batch(src, hline + 1, "line", text(values["test_id"]), text(values["direction"]), arr["hand_force_N"],
                  arr["time_s"], arr["drum_temp_C"], arr["torque_Nm"], arr.get("ambient_C"), {}, lines))
    return red.finish(src, 1, window_s, notes)


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
