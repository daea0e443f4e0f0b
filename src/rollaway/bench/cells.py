"""Row-by-row checks of a batch of a bench log, the same for every reader: numbers finite and in their physical
ranges (a time far out of range named as the unit it looks like), every row a test id and a known direction.

:func:`cell_problems` lists them for :class:`rollaway.bench.reduction.Reducer`, which also checks each test
as a whole; :func:`line_of` orders problems by the line they name, so that whichever check found a problem,
the first listed is the first in the file.
"""
from __future__ import annotations

import re

import numpy as np

from rollaway.bench.dataset import LIMITS
from rollaway.bench.time_axis import epoch_message, long_test_message
from rollaway.errors import suggest
from rollaway.physics.drum import DIRECTIONS


def cell_problems(b) -> list[str]:
    """The problems of the rows of batch *b* (file, line, column and fix each)."""
    problems: list[str] = []
    values = {"hand_force_N": b.hand_force_N, "time_s": b.time_s, "drum_temp_C": b.drum_temp_C,
              "torque_Nm": b.torque_Nm, "ambient_C": b.ambient_C}
    for q, x in values.items():
        if x is not None:
            _check_numbers(b, q, x, problems, lower=q != "time_s")
    codes = b.test_id.codes
    if np.any(codes < 0):
        i = int(np.flatnonzero(codes < 0)[0])
        problems.append(f"{b.at(i)}, column {b.column('test_id')}: empty; give every row its test id")
    dcodes = b.direction.codes
    for k, name in enumerate(b.direction.names):
        if name not in DIRECTIONS and np.any(dcodes == k):
            i = int(np.flatnonzero(dcodes == k)[0])
            problems.append(f"{b.at(i)}, column {b.column('direction')}: unknown direction {name!r}"
                            f"{suggest(name.lower(), DIRECTIONS)}; use 'downhill' or 'uphill'")
    if np.any(dcodes < 0):
        i = int(np.flatnonzero(dcodes < 0)[0])
        problems.append(f"{b.at(i)}, column {b.column('direction')}: empty; give 'downhill' or 'uphill'")
    return problems


def _check_numbers(b, q: str, x: np.ndarray, problems: list[str], lower: bool = True) -> None:
    lo, hi, unit = LIMITS[q]
    lo = lo if lower else -hi
    bad = ~np.isfinite(x)
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        problems.append(f"{b.at(i)}, column {b.column(q)}: empty cell or not a finite number ({int(bad.sum())} such "
                        f"cell{'s' if bad.sum() > 1 else ''} in these rows); give a measured value or delete the row")
        return
    out = (x < lo) | (x > hi)
    if np.any(out):
        i = int(np.flatnonzero(out)[0])
        longest = float(np.max(np.abs(x[b.test_id.codes == b.test_id.codes[i]])))
        if q == "time_s" and (hint := _time_hint(b, i, x[i], longest)):
            problems.append(hint)
            return
        r = b.columns.get(q)
        read = f" (read as {r.unit})" if r is not None and r.unit else ""
        problems.append(f"{b.at(i)}, column {b.column(q)}: {x[i]:g} {unit} is outside [{lo:g}, {hi:g}]{read}; check "
                        f"the unit (map it with --columns '{q}=<column>[unit]')")


def _time_hint(b, i: int, t: float, longest: float) -> str | None:
    """The message for a time *t* far beyond a bench test: a Unix time stamp, or (no unit stated) ms, µs or ns
    (judged by the *longest* time of its test in the batch)."""
    epoch = epoch_message(b.at(i), b.column("time_s"), t)
    r = b.columns.get("time_s")
    if epoch or (r is not None and r.unit):
        return epoch
    code = int(b.test_id.codes[i])
    return long_test_message(b.at(i), b.column("time_s"), r.header if r else "time_s",
                             b.test_id.names[code] if code >= 0 else "?", longest)


def line_of(problem: str) -> int:
    """The line (or row) a problem names, to list problems in file order whichever check found them."""
    m = re.search(r", (?:line|row) (\d+)", problem)
    return int(m.group(1)) if m else 0
