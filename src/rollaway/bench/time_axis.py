"""Time axes that are not in seconds from the lever: milliseconds with no unit in the header, Unix time stamps.

A DAQ export often writes time in ms (or µs) and says so nowhere, or writes the wall-clock time
(seconds or milliseconds since 1970).  Read as seconds, a 1-hour test in ms lasts 3.6·10⁶ s (42 days)
and an epoch axis starts in the year 2020 — numbers a parking-brake test cannot have.  Both are
refused with the unit they look like and how to say it; a time column whose unit the header or the
column map states is taken as stated (a test that really lasts longer than :data:`MAX_TEST_S`).
"""
from __future__ import annotations

from datetime import datetime, timezone

# A bench test of a parked drum brake lasts minutes to hours (the drum cools with τ ≈ 1000 s); two days is
# far beyond any (assumed, not from the paper).  A longer one read as seconds is another unit.
MAX_TEST_S = 2 * 86400.0
SCALES = ((1e3, "ms"), (1e6, "us"), (1e9, "ns"))
EPOCH_S = (9.46e8, 2.53e9)          # Unix time stamps of the years 2000–2050, in seconds


def epoch_hint(value: float) -> str | None:
    """'a Unix time stamp in ms (2024-05-01 ...)' when *value* reads as one, else None."""
    for scale, unit in ((1.0, "s"), *SCALES):
        s = abs(float(value)) / scale
        if EPOCH_S[0] <= s <= EPOCH_S[1]:
            when = datetime.fromtimestamp(s, tz=timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
            return f"a Unix time stamp in {unit} ({when})"
    return None


def epoch_message(at: str, column: str, value: float) -> str | None:
    """The one-line error for a time cell that is a wall-clock time stamp, or None."""
    hint = epoch_hint(value)
    if hint is None:
        return None
    return (f"{at}, column {column}: {value:.10g} looks like {hint}, not the time since the lever was applied; "
            f"export each test's time from its start (subtract the first time stamp), so that it starts at 0")


def long_test_message(where: str, column: str, header: str, test: str, duration_s: float) -> str | None:
    """The one-line error for a test that lasts longer than :data:`MAX_TEST_S` read as seconds, or None."""
    if duration_s <= MAX_TEST_S:
        return None
    scale, unit = next(((sc, u) for sc, u in SCALES if duration_s / sc <= MAX_TEST_S), SCALES[-1])
    bare = header.split("[")[0].strip() or header
    return (f"{where}, column {column}: test '{test}' lasts {duration_s:.4g} s ({duration_s / 86400:.0f} days) read "
            f"as seconds — the time looks like {unit} ({duration_s / scale:.4g} s); give its unit: --columns "
            f"'time_s={bare}[{unit}]' (or a header '{bare} [{unit}]'; a test that truly lasts that long: "
            f"--columns 'time_s={bare}[s]')")
