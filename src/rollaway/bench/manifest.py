"""A bench campaign's manifest: one row per test with its direction and hand force.

``manifest.csv`` (or ``tests.csv``) in a folder of test files, or ``--manifest FILE`` for a folder
or a single log::

    test_id,direction,hand_force_N
    D250,downhill,250
    U340,uphill,340

Columns are mapped like the logs' (``--columns``), else taken by their canonical names.  The
rules, so that nothing is dropped, overridden or reused without a word:

* written like the logs: ``,`` or, as European exports write it, ``;`` with decimal commas;
* a test is listed once (two rows for one test: an error naming both lines);
* every row has its test (a folder: a file ``TEST.csv``; a single log: rows with that ``test_id``),
  and every test has its row, unless the log itself logs the direction and the force;
* where the log logs them too, the two agree (an error naming the log's line and the manifest's).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rollaway.bench.columns import ColumnMap, _find
from rollaway.bench.readers import sniff_dialect
from rollaway.errors import UserError, suggest
from rollaway.physics.drum import DIRECTIONS

NAMES = ("manifest.csv", "tests.csv")
QUANTITIES = ("test_id", "direction", "hand_force_N")


@dataclass
class Manifest:
    """The rows of a manifest: {test_id: {"direction", "hand_force_N", "line"}} and the file they came from."""

    path: Path
    rows: dict[str, dict]

    def where(self, test: str) -> str:
        return f"{self.path}, line {self.rows[test]['line']}"

    def check_agrees(self, batch, test_names: list[str], codes: np.ndarray) -> None:
        """UserError where a log's own direction or hand force of a test differs from its manifest row."""
        for k, name in enumerate(test_names):
            row = self.rows.get(name)
            hit = np.flatnonzero(codes == k)
            if row is None or not hit.size:
                continue
            i = int(hit[0])
            if batch.direction is not None and batch.direction.codes[i] >= 0:
                d = batch.direction.names[int(batch.direction.codes[i])]
                if d != row["direction"]:
                    raise UserError(f"{batch.at(i)}, column {batch.column('direction')}: test '{name}' is {d} here "
                                    f"but {row['direction']} in {self.where(name)}; correct the one that is wrong "
                                    f"(or drop the column or the manifest row)")
            f = batch.hand_force_N[i] if batch.hand_force_N is not None else None
            if f is not None and np.isfinite(f) and not np.isclose(f, row["hand_force_N"], rtol=1e-9, atol=1e-9):
                raise UserError(f"{batch.at(i)}, column {batch.column('hand_force_N')}: test '{name}' has a hand force "
                                f"of {f:g} N here but {row['hand_force_N']:g} N in {self.where(name)}; correct the "
                                f"one that is wrong (or drop the column or the manifest row)")

    def check_all_used(self, seen, what: str) -> None:
        """UserError for a manifest row whose test the log does not have (*what*: where the tests were looked for)."""
        missing = [t for t in self.rows if t not in seen]
        if missing:
            t = missing[0]
            more = f" (and {len(missing) - 1} more: {', '.join(missing[1:4])}{', ...' if len(missing) > 4 else ''})" \
                if len(missing) > 1 else ""
            raise UserError(f"{self.where(t)}, column 'test_id': test '{t}' has no data in {what}{more}"
                            f"; add its log or delete the row")


def read_manifest(path: Path, manifest: str | None, colmap: ColumnMap) -> Manifest | None:
    """The manifest given by ``--manifest`` or found in the folder *path*; None if there is none."""
    if manifest:
        m = Path(manifest)
        if not m.is_file():
            raise UserError(f"--manifest {manifest}: no such file; give a CSV with test_id,direction,hand_force_N")
    else:
        found = [path / n for n in NAMES if path.is_dir() and (path / n).is_file()]
        if not found:
            return None
        if len(found) > 1:
            raise UserError(f"{found[1]}: the folder has two manifests ({', '.join(f.name for f in found)}); keep "
                            f"one, or name the one to use with --manifest")
        m = found[0]
    header, line, rows = _read_small_csv(m)
    cols = {}
    for q in QUANTITIES:
        # the map's column if the manifest has it, else the canonical name (a manifest is often written by hand)
        spec = colmap.specs.get(q)
        use = colmap if spec is not None and _find(header, spec.column) else ColumnMap()
        r = use.resolve(header, q, f"{m}, line {line}")
        if r is None:
            raise UserError(f"{m}, line {line}, column '{q}': missing; a manifest has the columns "
                            f"test_id,direction,hand_force_N (one row per test file)")
        cols[q] = r
    out: dict[str, dict] = {}
    for n, row in rows:
        if len(row) != len(header):
            raise UserError(f"{m}, line {n}: {len(row)} fields but the header has {len(header)}; fix the commas")
        cell = {q: row[header.index(r.header)].strip() for q, r in cols.items()}
        tid = cell["test_id"]
        if not tid:
            raise UserError(f"{m}, line {n}, column {cols['test_id'].describe()}: empty; give the test's id (its "
                            f"file name without .csv, or its test_id in the log)")
        if tid in out:
            raise UserError(f"{m}, line {n}, column {cols['test_id'].describe()}: test '{tid}' is listed twice (also "
                            f"on line {out[tid]['line']}); keep one row per test — a second lever application is "
                            f"a new test with its own id")
        try:
            force = float(cell["hand_force_N"]) * cols["hand_force_N"].scale + cols["hand_force_N"].offset
        except ValueError:
            force = float("nan")
        if not np.isfinite(force) or not 0.0 <= force <= 5000.0:
            raise UserError(f"{m}, line {n}, column {cols['hand_force_N'].describe()}: {cell['hand_force_N']!r} is "
                            f"not a hand force in [0, 5000] N; give the hand force of test '{tid}'")
        if cell["direction"] not in DIRECTIONS:
            raise UserError(f"{m}, line {n}, column {cols['direction'].describe()}: unknown direction "
                            f"{cell['direction']!r}{suggest(cell['direction'].lower(), DIRECTIONS)}; use 'downhill' "
                            f"or 'uphill'")
        out[tid] = {"direction": cell["direction"], "hand_force_N": force, "line": n}
    if not out:
        raise UserError(f"{m}, line {line + 1}: the manifest has a header but no rows; add one row per test")
    return Manifest(m, out)


def _read_small_csv(path: Path):
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise UserError(f"{path}, line 1: not a UTF-8 text file; save it as UTF-8 CSV") from None
    lines = text.splitlines()
    filled = [x for x in lines if x.strip()]
    delim, decimal = sniff_dialect(filled[0], filled[1] if len(filled) > 1 else "") if filled else (",", ".")
    try:
        reader = csv.reader(lines, delimiter=delim)
        numbered = [(reader.line_num, [c.replace(decimal, ".") if decimal != "." else c for c in r])
                    for r in reader if any(c.strip() for c in r)]
    except csv.Error as exc:
        raise UserError(f"{path}, line {reader.line_num}: {exc}; check the quotes on this line") from None
    if not numbered:
        raise UserError(f"{path}, line 1: the file is empty; expected a header row test_id,direction,hand_force_N")
    (line, header), body = numbered[0], numbered[1:]
    return [h.strip() for h in header], line, body
