"""High-rate bench logs reduced to window means that keep what the fits need, read in one streaming pass.

A log at 10–1000 Hz holds far more samples than the physics has degrees of freedom: over a
window of w seconds the model is a straight line to within a tiny fraction of the noise, so
the window's mean (at the window's mean time) with its standard error carries the data's
information about the parameters (what the within-window slope adds is of relative order
(w/T)², T the test's length).  The reduction keeps, per test:

* the t = 0 sample as it is (it measures T_0);
* per window: the number of samples n, the mean time, the mean of each channel;
* the noise of each channel estimated **at the raw rate** from the degree-1 pseudo-residuals of
  consecutive samples (the combination of three samples that cancels any straight line; its
  variance is σ² whatever the sampling, :mod:`rollaway.bench.noise`), torque as
  σ² = a² + (b·M)² (absolute + relative part) fitted over the log; the full mean square (not a
  trimmed one: heavy tails do enter the variance of a mean) — so a reduced row's standard error
  is σ(level)/√n.

The reduced :class:`~rollaway.bench.measurements.Measurements` carry ``count`` (n per row),
the per-row standard errors (``torque_sigma_Nm``, ``temp_sigma_C``) and :class:`Reduction`
(rows read, kept, reduced; the raw-rate noise), so every fit weights each row by its own
information and the noise checks compare residuals with the raw-rate noise.  Memory is one
batch of the log plus a few numbers per second of log.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from rollaway.errors import UserError
from rollaway.bench.dataset import LIMITS, MAX_LISTED, Measurements, _raise
from rollaway.bench.noise import Noise, sample_sigma
from rollaway.bench.rawnoise import dispersion, raw_noise
from rollaway.bench.cells import cell_problems, line_of, spikes, without
from rollaway.bench.time_axis import epoch_message, long_test_message

BIN_S = 1.0                 # statistics are kept per second of log, windows are whole numbers of seconds
# A window mean differs from the model at the window's mean time by f''·w²/24 (the curvature of the physics:
# cooling, creep, relaxation, time constants ≥ 10 min); relative to its standard error σ/√(rate·w) that
# is ∝ w^2.5·√rate, and it adds up coherently over the log's w⁻¹ windows: a fitted parameter moves by
# ∝ w²·√rate of its standard error (0.30 at 15 s and 100 Hz, measured on synth's logs).  The automatic
# window keeps w²·√rate ≤ WINDOW_C (≤ 0.1 standard error): 27 s at 1 Hz, 15 s at 10 Hz, 8 s at 100 Hz.
WINDOW_C = 750.0
MIN_ROWS = 60               # windows per test at least (a short test keeps its time resolution)
MIN_PER_WINDOW = 8          # reduce only when a window holds at least this many samples (median test)
MIN_TEST_WINDOWS = 5        # ... and the median test spans at least this many automatic windows: a 2-s test at
                            # 100 Hz in 1-s windows keeps 3 rows, fewer than a drum calibration frees parameters;
                            # 5–9-s tests keep 5–9 (10 000 raw rows of them took up to 5.2 s to diagnose, reduced
                            # 1.6 s, with as many right and false names over 40 random logs)
KEEP_RAW_ROWS = 200_000     # raw rows kept in memory for a log that turns out not to need reducing
# sufficient statistics per bin: n, Σt, ΣT, ΣM, Σambient, n_e, Σe_T², Σe_M²
N, ST, STEMP, SQ, SAMB, NE, E2T, E2Q = range(8)
WIDTH = 8


@dataclass
class Reduction:
    """What was read and what the fits see."""

    rows_read: int
    rows_kept: int
    rows: int                       # rows after reduction
    window_s: float | None          # None: not reduced
    files: int
    noise_torque: Noise | None = None
    noise_temp: Noise | None = None
    notes: list[str] = field(default_factory=list)

    @property
    def reduced(self) -> bool:
        return self.window_s is not None

    def summary(self) -> str:
        files = f" from {self.files} files" if self.files > 1 else ""
        text = f"read {self.rows_read:,} rows{files}, kept {self.rows_kept:,}"
        if not self.reduced:
            return text + ", not reduced (each sample is a row)"
        return (text + f", reduced to {self.rows:,} rows ({self.window_s:g} s window means, standard errors from the "
                f"noise at the raw rate: torque σ ≈ {self.noise_torque.sigma:.3g} N·m, drum temperature σ ≈ "
                f"{self.noise_temp.sigma:.3g} °C)")

    def as_dict(self) -> dict:
        return {"rows_read": self.rows_read, "rows_kept": self.rows_kept, "rows": self.rows,
                "window_s": self.window_s, "files": self.files,
                "noise_torque": None if self.noise_torque is None else self.noise_torque.as_dict(),
                "noise_temp": None if self.noise_temp is None else self.noise_temp.as_dict()}


class _Test:
    """Running state of one test: its constants, the last samples, its bins."""

    def __init__(self, name: str, direction: str, force: float, where: str):
        self.name, self.direction, self.force, self.where = name, direction, force, where
        self.n = 0
        self.last_t = -math.inf
        self.last_where = where
        self.carry = np.zeros((0, 3))         # last two samples (t, T, M) for the pseudo-residuals
        self.first = None                     # the t = 0 sample: (T, M, ambient)
        self.bins: list[np.ndarray] = []
        self.stats: list[np.ndarray] = []
        self.raw: list[tuple] = []            # raw rows while the log may be small
        self.e4 = np.zeros(2)                 # Σe⁴ (temperature, torque)
        self.before_zero = 0                  # its rows before time 0 (not kept)


class Reducer:
    """Validates and accumulates batches (:mod:`rollaway.bench.sources`); :meth:`finish` builds the data."""

    def __init__(self, keep_raw: int | None = None):
        self.tests: dict[str, _Test] = {}
        self.rows = 0
        self.before_zero = 0                  # rows logged before the lever was applied (t < 0): not kept
        self.keep_raw = KEEP_RAW_ROWS if keep_raw is None else keep_raw
        self.has_ambient: bool | None = None
        self.time_column: tuple[str, str, bool] | None = None   # (as described, header cell, unit stated)
        self.spikes = 0                       # isolated samples out of their physical range, dropped
        self.first_spike = ""

    # -- one batch -------------------------------------------------------------------------
    def add(self, b) -> None:
        n = len(b)
        self.rows += n
        if self.time_column is None:
            r = b.columns.get("time_s")
            self.time_column = (b.column("time_s"), r.header if r else "time_s", bool(r and r.unit))
        if self.has_ambient is None:
            self.has_ambient = b.ambient_C is not None
        elif self.has_ambient != (b.ambient_C is not None):
            raise UserError(f"{b.where}, column 'ambient_C': some files log the ambient and others do not; give it "
                            f"in every file or in none")
        drop = spikes(b)
        if drop.any():
            i = int(np.flatnonzero(drop)[0])
            if not self.spikes:
                q = next(q for q in ("drum_temp_C", "torque_Nm", "ambient_C") if getattr(b, q) is not None
                         and not LIMITS[q][0] <= getattr(b, q)[i] <= LIMITS[q][1])
                self.first_spike = f"{b.at(i)}, column {b.column(q)}: {getattr(b, q)[i]:g} {LIMITS[q][2]}"
            self.spikes += int(drop.sum())
            b = without(b, drop)
        problems = cell_problems(b)
        codes = b.test_id.codes
        if problems:
            _raise(sorted(problems, key=line_of))
        order = np.argsort(codes, kind="stable")
        splits = np.flatnonzero(np.diff(codes[order])) + 1
        for rows in np.split(order, splits):
            if rows.size:
                self._segment(b, rows, problems)
            if len(problems) >= MAX_LISTED:
                break
        if problems:
            _raise(sorted(problems, key=line_of))

    def _segment(self, b, rows: np.ndarray, problems: list[str]) -> None:
        name = b.test_id.names[int(b.test_id.codes[rows[0]])]
        direction = b.direction.names[int(b.direction.codes[rows[0]])]
        force = b.hand_force_N[rows]
        st = self.tests.get(name)
        if st is None:
            st = self.tests[name] = _Test(name, direction, float(force[0]), b.at(rows[0]))
        dirs = np.asarray(b.direction.names, dtype=object)[b.direction.codes[rows]]
        for col, what, have, first in (("hand_force_N", "hand forces", force, st.force),
                                       ("direction", "directions", dirs, st.direction)):
            ok = have == first
            if not np.all(ok):
                i = int(np.flatnonzero(~ok)[0])
                shown = f"{have[i]:g}" if col == "hand_force_N" else have[i]
                was = f"{first:g}" if col == "hand_force_N" else first
                problems.append(f"{b.at(rows[i])}, column {b.column(col)}: test '{name}' has two {what} ({was} at "
                                f"{st.where.split(', ')[-1]}, {shown} here); one test is one lever application — "
                                f"give it a new test_id")
                return
        t = b.time_s[rows]
        prev = np.concatenate([[st.last_t], t[:-1]])
        bad = t <= prev
        if np.any(bad):
            i = int(np.flatnonzero(bad)[0])
            before = st.last_where if i == 0 else b.at(rows[i - 1])
            how = "duplicate time" if t[i] == prev[i] else "time decreases"
            problems.append(f"{b.at(rows[i])}, column {b.column('time_s')}: {how} in test '{name}' ({prev[i]:g} s at "
                            f"{before.split(', ')[-1]}, then {t[i]:g} s); sort the rows of each test by time and "
                            f"remove repeated ones")
            return
        if t[0] < 0:                        # a pre-trigger stretch before the lever was applied: not kept
            st.last_t, st.last_where = float(t[t < 0][-1]), b.at(rows[int(np.sum(t < 0)) - 1])
            self.before_zero += int(np.sum(t < 0))
            st.before_zero += int(np.sum(t < 0))
            rows, t, force = rows[t >= 0], t[t >= 0], force[t >= 0]
            if not rows.size:
                return
        if st.n == 0 and t[0] != 0.0:
            epoch = epoch_message(b.at(rows[0]), b.column("time_s"), t[0])
            if epoch:
                problems.append(epoch)
                return
            problems.append(f"{b.at(rows[0])}, column {b.column('time_s')}: test '{name}' starts at {t[0]:g} s; each "
                            f"test must start at time 0 (lever applied), which defines its T_0 — shift its times")
            return
        temp, torque = b.drum_temp_C[rows], b.torque_Nm[rows]
        amb = b.ambient_C[rows] if b.ambient_C is not None else np.zeros(rows.size)
        if self.rows - self.before_zero <= self.keep_raw:
            st.raw.append((t, temp, torque, amb))
        elif self.keep_raw >= 0:            # too many to keep: the log will be reduced (free what was kept)
            for other in self.tests.values():
                other.raw = []
            self.keep_raw = -1
        start = 0
        if st.n == 0:
            st.first = (float(temp[0]), float(torque[0]), float(amb[0]))
            start = 1
        st.n += rows.size
        st.last_t = float(t[-1])
        st.last_where = b.at(rows[-1])
        # pseudo-residuals of every 3 consecutive samples (the previous batch's last two included)
        seq = np.concatenate([st.carry, np.column_stack([t, temp, torque])])
        st.carry = seq[-2:]
        e_bin, e2 = None, None
        if len(seq) >= 3:
            x0, x1, x2 = seq[:-2, 0], seq[1:-1, 0], seq[2:, 0]
            c = np.column_stack([1.0 / ((x0 - x1) * (x0 - x2)), 1.0 / ((x1 - x0) * (x1 - x2)),
                                 1.0 / ((x2 - x0) * (x2 - x1))])
            c /= np.linalg.norm(c, axis=1, keepdims=True)
            e = np.column_stack([c[:, 0] * seq[:-2, k] + c[:, 1] * seq[1:-1, k] + c[:, 2] * seq[2:, k]
                                 for k in (1, 2)])
            e2 = e * e
            st.e4 += np.sum(e2 * e2, axis=0)
            e_bin = np.floor(x1 / BIN_S).astype(np.int64)
        # per-second sums (the t = 0 sample stays a row of its own)
        tt, tp, tq, ta = t[start:], temp[start:], torque[start:], amb[start:]
        if tt.size:
            stats = np.column_stack([np.ones(tt.size), tt, tp, tq, ta])
            _accumulate(st, np.floor(tt / BIN_S).astype(np.int64), stats, 0)
        if e_bin is not None:
            _accumulate(st, e_bin, np.column_stack([np.ones(len(e2)), e2]), NE)

    # -- the data ------------------------------------------------------------------------
    def finish(self, source: str, files: int = 1, window_s: float | None = None,
               notes: list[str] | None = None) -> Measurements:
        """Reduced (or, for a sparse log or ``window_s == 0``, raw) measurements; *window_s* None: automatic."""
        if not self.tests:
            raise UserError(f"{source}: no data rows after the header; add one row per sample")
        short = [t for t in self.tests.values() if t.n < 3]
        if short:
            _raise([f"{t.where}, column 'test_id': test '{t.name}' has {t.n} sample(s)"
                    + (f" from time 0 on ({t.before_zero} before it, not used)" if t.before_zero else "")
                    + "; give at least 3 per test"
                    for t in short])
        column, header, stated = self.time_column or ("'time_s'", "time_s", False)
        if not stated:
            long = [m for t in self.tests.values() if (m := long_test_message(t.last_where, column, header, t.name,
                                                                              t.last_t))]
            if long:                        # one line: every test says the same
                _raise(long[:1])
        durations = np.array([t.last_t for t in self.tests.values()])
        counts = np.array([t.n for t in self.tests.values()])
        rate = float(np.median((counts - 1) / np.maximum(durations, 1e-300)))      # samples per second
        if window_s is None:
            w = auto_window(rate, float(durations.max()))
            reduce = rate * w >= MIN_PER_WINDOW and float(np.median(durations)) >= MIN_TEST_WINDOWS * w
        else:
            whole = math.isfinite(window_s) and abs(window_s / BIN_S - round(window_s / BIN_S)) <= 1e-9
            if not math.isfinite(window_s) or window_s < 0 or (window_s > 0 and not whole):
                raise UserError(f"--window-s {window_s:g}: give a whole number of seconds ≥ 1 (0: fit every sample)")
            w, reduce = float(window_s), window_s > 0
            per_window = rate * w
            if reduce and per_window < 3:
                raise UserError(f"--window-s {window_s:g}: the log has about {per_window:.1f} samples per window; a "
                                f"window mean needs several (its noise is measured between consecutive samples) — "
                                f"give a longer window, or 0 to fit every sample")
        notes = list(notes or [])
        if self.before_zero:
            notes.append(f"{self.before_zero:,} rows logged before time 0 (before the lever was applied) are not used")
        if self.spikes:
            notes.append(f"{self.spikes:,} isolated sample{'s' if self.spikes > 1 else ''} outside the physical range "
                         f"dropped as spike{'s' if self.spikes > 1 else ''} (first: {self.first_spike})")
        if not reduce:
            if any(not t.raw for t in self.tests.values()) or sum(len(r[0]) for t in self.tests.values()
                                                                   for r in t.raw) != self.kept:
                raise UserError(f"{source}: {self.rows:,} rows are too many to fit sample by sample here; leave "
                                f"--window-s out (automatic window) or give a window in seconds")
            return self._raw(source, files, notes)
        return self._reduced(source, files, w, notes)

    @property
    def kept(self) -> int:
        return self.rows - self.before_zero - self.spikes

    def _raw(self, source: str, files: int, notes: list[str]) -> Measurements:
        ids, dirs, force, cols = [], [], [], [[], [], [], []]
        for st in self.tests.values():
            n = sum(len(r[0]) for r in st.raw)
            ids.append(np.full(n, st.name, dtype=object))
            dirs.append(np.full(n, st.direction, dtype=object))
            force.append(np.full(n, st.force))
            for k in range(4):
                cols[k].append(np.concatenate([r[k] for r in st.raw]))
        t, temp, torque, amb = (np.concatenate(c) for c in cols)
        red = Reduction(self.rows, self.kept, self.kept, None, files, notes=notes)
        return Measurements(np.concatenate(ids).astype(str), np.concatenate(dirs).astype(str), np.concatenate(force),
                            t, temp, torque, amb if self.has_ambient else None,
                            source, None, notes, reduction=red)      # each sample a row: the source is the path

    def _reduced(self, source: str, files: int, w: float, notes: list[str]) -> Measurements:
        k = max(int(round(w / BIN_S)), 1)
        per_test = []
        for st in self.tests.values():
            bins = np.concatenate(st.bins)
            stats = np.concatenate(st.stats)
            win, inv = np.unique(bins // k, return_inverse=True)
            sums = np.zeros((len(win), WIDTH))
            np.add.at(sums, inv, stats)
            per_test.append((st, sums))
        nq, nt = raw_noise([s for _, s in per_test], [st.e4 for st, _ in per_test])
        # noise correlated between samples (a DAQ filter) makes σ/√n too small: the scatter of the window
        # means about a smooth curve says by how much, and the standard errors are widened by that factor
        kq, kt = dispersion([(s[:, ST] / s[:, N], s[:, STEMP] / s[:, N], s[:, SQ] / s[:, N], s[:, N])
                             for s in (sums[sums[:, N] > 0] for _, sums in per_test)], nq, nt)
        nq, nt = replace(nq, mean_factor=kq), replace(nt, mean_factor=kt)
        for ch, kappa in (("torque", kq), ("drum temperature", kt)):
            if kappa > 1.0:
                notes.append(f"{ch} noise is correlated between samples: window standard errors widened "
                             f"×{kappa:.2f} (the scatter of the window means about a smooth curve)")
        rows = {k_: [] for k_ in ("id", "dir", "F", "t", "T", "M", "amb", "n")}
        for st, sums in per_test:
            keep = sums[:, N] > 0
            s = sums[keep]
            n = s[:, N]
            T0, M0, A0 = st.first
            m = len(n) + 1
            rows["id"].append(np.full(m, st.name, dtype=object))
            rows["dir"].append(np.full(m, st.direction, dtype=object))
            rows["F"].append(np.full(m, st.force))
            rows["t"].append(np.concatenate([[0.0], s[:, ST] / n]))
            rows["T"].append(np.concatenate([[T0], s[:, STEMP] / n]))
            rows["M"].append(np.concatenate([[M0], s[:, SQ] / n]))
            rows["amb"].append(np.concatenate([[A0], s[:, SAMB] / n]))
            rows["n"].append(np.concatenate([[1.0], n]))
        cat = {k_: np.concatenate(v) for k_, v in rows.items()}
        red = Reduction(self.rows, self.kept, len(cat["t"]), w, files, nq, nt, notes)
        count = cat["n"]
        data = Measurements(cat["id"].astype(str), cat["dir"].astype(str), cat["F"], cat["t"], cat["T"], cat["M"],
                            cat["amb"] if self.has_ambient else None, f"{source} ({red.summary()})", None,
                            notes + [red.summary()],
                            None, None, count=count, reduction=red)
        data.torque_sigma_Nm = np.maximum(sample_sigma(nq, data, data.torque_Nm), 1e-9)
        data.temp_sigma_C = np.maximum(sample_sigma(nt, data, data.drum_temp_C), 1e-9)
        return data


def auto_window(rate_hz: float, duration_s: float) -> float:
    """The automatic window [s]: w²·√rate ≤ WINDOW_C, at least MIN_ROWS windows in the longest test."""
    w = math.floor(math.sqrt(WINDOW_C / math.sqrt(max(rate_hz, 1e-9))) / BIN_S) * BIN_S
    return float(max(BIN_S, min(w, math.floor(duration_s / MIN_ROWS / BIN_S) * BIN_S)))


def _accumulate(st: _Test, bins: np.ndarray, values: np.ndarray, col: int) -> None:
    """Add *values* (rows in time order) into the per-second sums of *st* starting at column *col*."""
    starts = np.flatnonzero(np.concatenate([[True], bins[1:] != bins[:-1]]))
    sums = np.add.reduceat(values, starts, axis=0)
    out = np.zeros((len(starts), WIDTH))
    out[:, col:col + values.shape[1]] = sums
    st.bins.append(bins[starts])
    st.stats.append(out)


def reduce_measurements(data: Measurements, window_s: float | None = None) -> Measurements:
    """The reduction of measurements already in memory (tests in file order; for tests and comparisons)."""
    from rollaway.bench.batch import Batch, Text
    red = Reducer(keep_raw=len(data))
    ids = list(dict.fromkeys(data.test_id.tolist()))
    dirs = sorted(set(data.direction.tolist()))
    codes = np.array([ids.index(t) for t in data.test_id]) if len(ids) < 64 else \
        np.unique(data.test_id, return_inverse=True)[1]
    names = ids if len(ids) < 64 else list(np.unique(data.test_id))
    red.add(Batch(data.source, 2, "line", Text(codes, names),
                  Text(np.array([dirs.index(d) for d in data.direction]), dirs), data.hand_force_N, data.time_s,
                  data.drum_temp_C, data.torque_Nm, data.ambient_C, {}))
    return red.finish(data.source, 1, window_s)
