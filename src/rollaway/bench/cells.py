"""Row-by-row checks of a batch of a bench log, the same for every reader: numbers finite and in their physical
ranges (a time far out of range named as the unit it looks like), every row a test id and a known direction.

:func:`cell_problems` lists them for :class:`rollaway.bench.reduction.Reducer`, which also checks each test
as a whole; :func:`line_of` orders problems by the line they name, so that whichever check found a problem,
the first listed is the first in the file.

:func:`spikes` picks out the isolated samples of a dense log whose measured value lies outside its physical range
(a thermocouple dropout, a transducer glitch, a heavy noise tail at 100 Hz): there one bad sample among a million is
a spike, not a wrong unit, and the reducer drops it and says so.
"""
from __future__ import annotations

import re

import numpy as np

from rollaway.bench.batch import Batch
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


SPIKE_MIN_ROWS = 10_000      # [assumed] a batch this long is a dense log, where one sample out of range is a spike
SPIKE_SHARE = 1e-4           # [assumed] at most this share of a batch's rows (more: a unit or a wiring fault)
MEASURED = ("drum_temp_C", "torque_Nm", "ambient_C")


def spikes(b) -> np.ndarray:
    """Rows of batch *b* to drop as spikes (bool): in a batch of ≥ :data:`SPIKE_MIN_ROWS` rows, a measured value
    (drum temperature, torque, ambient) finite but outside its physical range, the rows before and after it in the
    same test in range, and no more than :data:`SPIKE_SHARE` of the rows such; otherwise none (the range check
    names the first such cell)."""
    n = len(b)
    drop = np.zeros(n, bool)
    if n < SPIKE_MIN_ROWS:
        return drop
    for q in MEASURED:
        x = getattr(b, q)
        if x is None:
            continue
        lo, hi, _ = LIMITS[q]
        drop |= np.isfinite(x) & ((x < lo) | (x > hi))
    k = np.flatnonzero(drop)
    if k.size == 0 or k.size > SPIKE_SHARE * n or k[0] == 0 or k[-1] == n - 1:
        return np.zeros(n, bool)
    codes = b.test_id.codes
    isolated = ~drop[k - 1] & ~drop[k + 1] & (codes[k - 1] == codes[k]) & (codes[k + 1] == codes[k])
    return drop if np.all(isolated) else np.zeros(n, bool)


def without(b, rows: np.ndarray):
    """Batch *b* less the rows where *rows* is true (line numbers kept)."""
    keep = ~rows
    sub = lambda x: None if x is None else x[keep]  # noqa: E731
    return Batch(b.where, b.first, b.word, type(b.test_id)(b.test_id.codes[keep], b.test_id.names),
                 None if b.direction is None else type(b.direction)(b.direction.codes[keep], b.direction.names),
                 sub(b.hand_force_N), b.time_s[keep], b.drum_temp_C[keep], b.torque_Nm[keep], sub(b.ambient_C),
                 b.columns, (np.arange(len(b)) + b.first if b.lines is None else b.lines)[keep])


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
