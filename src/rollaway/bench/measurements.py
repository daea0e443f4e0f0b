"""Bench measurements: load and validate the bench CSV format (the strict loader of small files).

One row per sample, columns ``test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm``
and optionally ``ambient_C`` (a logged ambient, one reading per sample).  Each test starts at
``time_s = 0`` (lever applied); its drum-temperature reading there is a noisy measurement of
its T_0 (``test_initial_temp_C``; the fits estimate T_0 with the other parameters); ``torque_Nm``
is per drum.  Every problem is reported
with file, line and column; nothing is guessed.  The file is tokenized here; the rules of each test
are :class:`rollaway.bench.reduction.Reducer`'s, as for the streaming reader.  :class:`Measurements`
itself lives in :mod:`rollaway.bench.dataset` (imported from here as before).
"""
from __future__ import annotations

import csv
import difflib
import io
import math
from pathlib import Path

import numpy as np

from rollaway.errors import UserError

from rollaway.bench.dataset import (LIMITS, MAX_LISTED, NUMERIC, OPTIONAL, REQUIRED,  # noqa: F401 (re-exported)
                                    Measurements, _raise)


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
    numbered = csv_rows(io.StringIO(text, newline=""), path, delim)     # line ends as pyarrow sees them
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
        notes.append(f"{src}: ignoring column(s) {', '.join(repr(h) for h in ignored[:6])}"
                     f"{', ...' if len(ignored) > 6 else ''} (not used)")
    if problems:
        _raise(problems)
    if not body:
        _raise([f"{src}, line {hline + 1}: no data rows after the header; add one row per sample"])
    col = {name: header.index(name) for name in known if name in header}
    fast = _columns_at_once(header, body, col, dialect[1])
    if fast is not None:
        return _through_reducer(fast, np.array([n for n, _ in body]), src, hline, window_s, notes)
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


def _columns_at_once(header: list[str], body: list[tuple[int, list[str]]], col: dict, decimal: str) -> dict | None:
    """The cells of :func:`_parse`, each numeric column converted in one call where every row has the header's
    width and every numeric cell is a plain number (``float`` of the stripped cell: what
    :func:`rollaway.bench.readers.parse_number` accepts, less its missing-value marks and cells with ``_``, which
    ``float`` reads and it does not); None otherwise: the cells one by one, with every bad one listed."""
    width = len(header)
    if decimal != "." or any(len(row) != width for _, row in body):
        return None
    cells = list(zip(*(row for _, row in body)))
    out = {}
    for name, j in col.items():
        if name in ("test_id", "direction"):
            out[name] = [c.strip() for c in cells[j]]
            continue
        column = cells[j]
        if any("_" in c for c in column):
            return None
        try:
            out[name] = np.array(column, float)
        except ValueError:                 # a missing-value mark, a unit, a typo: listed by the slow path
            return None
    return out


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


def from_frame(frame, source: str = "<DataFrame>", window_s: float | None = 0) -> Measurements:
    """Validate a pandas DataFrame with the CSV's columns (rows numbered as CSV lines 2, 3, …)."""
    header = [str(c) for c in frame.columns]
    rows = [["" if _isnan(v) else str(v) for v in r] for r in frame.itertuples(index=False)]
    return _parse(header, [(i + 2, r) for i, r in enumerate(rows)], source, 1, window_s)
