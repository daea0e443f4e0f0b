"""Reading bench logs as labs write them: CSV or Parquet, one file or a folder with one file per test.

A *source* yields :class:`Batch` es — up to a few hundred thousand rows each, already in the
canonical quantities and SI units (:mod:`rollaway.bench.columns`) — so a log of any length
is read in bounded memory (:mod:`rollaway.bench.readers`: pyarrow's streaming CSV reader, Parquet
row groups).

* One file: a ``test_id`` column says which test each row belongs to; without one the whole file
  is one test named after the file.
* A folder: every ``*.csv`` / ``*.parquet`` file is one test, its ``test_id`` the file name
  (without the suffix).  Direction and hand force come from columns of the file or from a
  manifest (:mod:`rollaway.bench.manifest`: ``manifest.csv`` in the folder, or ``--manifest FILE``
  for a folder or a single log).  Every file must log each quantity in one unit: a folder whose
  files disagree is refused (an export mistake, not something to guess).

Nothing is dropped or reused without a word: a file with a header and no rows, a column read as two
quantities, a column listed twice, a manifest row without its test are errors; a map's unit that
overrides the header's is taken only when marked with ``!`` and is then noted.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from rollaway.bench.batch import Batch, Text  # noqa: F401  (re-exported: the readers' unit of work)
from rollaway.bench.columns import CANONICAL, TEXT, ColumnMap, Resolved, Spec, _find, unit_label
from rollaway.bench.manifest import NAMES as MANIFEST_NAMES
from rollaway.bench.manifest import Manifest, read_manifest
from rollaway.bench.readers import DIALECT, check_names, csv_batches, mdf_batches, parquet_batches, read_header
from rollaway.errors import UserError

SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet", ".mf4": "mdf", ".mdf": "mdf"}


@dataclass
class FilePlan:
    """One file to read: its kind, the columns found, and the per-file constants (folder mode)."""

    path: Path
    kind: str
    header: list[str]
    header_line: int
    columns: dict[str, Resolved]
    constants: dict[str, object]
    channels: tuple | None = None       # MDF: (cell → channel name, master cell)
    dialect: tuple[str, str] = DIALECT  # CSV: delimiter, decimal mark
    manifest: Manifest | None = None    # the campaign's manifest, if any (direction, force per test)
    notes: list[str] = field(default_factory=list)   # stated choices taken (a map's unit over the header's)


def plan(path, colmap: ColumnMap | None = None, manifest: str | None = None) -> list[FilePlan]:
    """The files of *path* (a file or a folder) with their columns resolved; every header problem raised."""
    colmap = colmap or ColumnMap()
    p = Path(path)
    if p.is_dir():
        files = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in SUFFIXES
                       and f.name.lower() not in MANIFEST_NAMES and not f.name.startswith("."))
        if manifest and Path(manifest).resolve() in {f.resolve() for f in files}:
            files = [f for f in files if f.resolve() != Path(manifest).resolve()]
        stems: dict[str, Path] = {}
        for f in files:
            if f.stem in stems:
                raise UserError(f"{f}: a second file for test '{f.stem}' (also {stems[f.stem].name}); one file per "
                                f"test — remove or rename one")
            stems[f.stem] = f
        if not files:
            raise UserError(f"'{p}' is a folder with no .csv or .parquet file; give a measurement CSV file, or a "
                            f"folder with one CSV/Parquet file per test (named after the test)")
        per_test = True
    elif p.is_file():
        if p.suffix.lower() not in SUFFIXES:
            raise UserError(f"{p}: unknown file type '{p.suffix}'; give a .csv, .parquet or .mf4 file (or a "
                            f"folder of them, one per test)")
        files, per_test = [p], False
    else:
        raise UserError(f"measurement file '{p}' does not exist; check the path")
    tests = read_manifest(p, manifest, colmap)
    plans = _check_units([_plan_file(f, colmap, tests, per_test) for f in files], p)
    if per_test:
        other = sorted(f.name + ("/" if f.is_dir() else "") for f in p.iterdir() if not f.name.startswith(".")
                       and (f.is_dir() or f.suffix.lower() not in SUFFIXES)
                       and f.name.lower() not in (*MANIFEST_NAMES, "columns.toml"))
        if other:
            plans[0].notes.append(f"{p}: {len(other)} file(s) or folder(s) not read (one .csv, .parquet or .mf4 "
                                  f"file per test): {', '.join(other[:5])}{', ...' if len(other) > 5 else ''}")
        own = [p / n for n in MANIFEST_NAMES if (p / n).is_file()]
        if manifest and own and own[0].resolve() != Path(manifest).resolve():
            plans[0].notes.append(f"--manifest {manifest} is used, not the folder's {own[0].name}")
    return plans


def _plan_file(f: Path, colmap: ColumnMap, tests: Manifest | None, per_test: bool) -> FilePlan:
    kind = SUFFIXES[f.suffix.lower()]
    channels, dialect = None, DIALECT
    if kind == "mdf":
        from rollaway.bench import asam_mdf
        header, names, master = asam_mdf.header(f)
        hline, channels = 0, (names, master)
        if "time_s" not in colmap.specs and master is not None and "time_s" not in header:
            colmap = ColumnMap({**colmap.specs, "time_s": Spec(master)}, colmap.origin)
    else:
        header, hline, dialect = read_header(f, kind)
    where = f"{f}, line {hline}" if kind == "csv" else str(f)
    check_names(header, where)
    cols = {}
    for q in CANONICAL:
        spec = colmap.specs.get(q)
        if (tests is not None and q in ("direction", "hand_force_N") and spec is not None
                and _find(header, spec.column) is None):
            continue                          # the manifest gives it for this file
        if (r := colmap.resolve(header, q, where)) is not None:
            cols[q] = r
    _check_columns(header, cols, colmap, where)
    constants = {}
    if per_test or "test_id" not in cols:
        constants["test_id"] = f.stem    # a folder's file is named after its test (a test_id column must agree)
    for q in ("hand_force_N", "direction"):
        if q in cols or (tests is not None and "test_id" in cols and not per_test):
            continue                     # logged, or given per test_id by the manifest (see _batch)
        info = tests.rows.get(str(constants["test_id"])) if tests is not None else None
        if info is None:
            what = "hand force" if q == "hand_force_N" else "direction"
            if tests is None:
                fix = (f"add a column '{q}' (or map yours with --columns '{q}=...'), or put a manifest.csv "
                       f"with test_id,direction,hand_force_N next to the files")
            else:
                fix = f"add a row for test '{constants['test_id']}' to the manifest {tests.path}"
            raise UserError(f"{where}, column '{q}': no {what} for this file (no such column, no manifest "
                            f"entry); {fix}")
        constants[q] = info[q]
    for q in ("time_s", "drum_temp_C", "torque_Nm"):
        if q not in cols:
            spec = colmap.specs.get(q)
            raise UserError(f"{where}, column '{q}': missing; the header is "
                            f"{', '.join(repr(h) for h in header[:8])}{', ...' if len(header) > 8 else ''} — "
                            f"map the column that holds {q} with --columns '{q}=<column>[unit]'"
                            + (f" ({spec.column!r} is not there)" if spec else ""))
    notes = [r.note for r in cols.values() if r.note]
    return FilePlan(f, kind, header, hline, cols, constants, channels, dialect, tests, notes)


def _check_columns(header: list[str], cols: dict[str, Resolved], colmap: ColumnMap, where: str) -> None:
    """A column the header lists twice, or one column read as two quantities: an error naming both."""
    stripped = [h.strip() for h in header]
    seen: dict[str, str] = {}
    for q, r in cols.items():
        if stripped.count(r.header.strip()) > 1:
            raise UserError(f"{where}, column '{r.header}': duplicate column (the header has it "
                            f"{stripped.count(r.header.strip())} times); keep one, or rename the other")
        if r.header in seen:
            q0 = seen[r.header]
            mapped = [x for x in (q0, q) if x in colmap.specs]
            by = f" ({' and '.join(mapped)} mapped to it by {colmap.origin})" if mapped else ""
            raise UserError(f"{where}, column '{r.header}': read as both {q0} and {q}{by}; one column holds one "
                            f"quantity — map each to its own column with --columns")
        seen[r.header] = q


def _check_units(plans: list[FilePlan], folder: Path) -> list[FilePlan]:
    """One unit per quantity across the files of a folder."""
    first: dict[str, tuple[FilePlan, Resolved]] = {}
    for fp in plans:
        for q, r in fp.columns.items():
            if q in TEXT:
                continue
            if q not in first:
                first[q] = (fp, r)
                continue
            f0, r0 = first[q]
            if (r0.scale, r0.offset) != (r.scale, r.offset):
                raise UserError(f"{fp.path}, column '{r.header}': {q} in {unit_label(r.unit, q)} here but in "
                                f"{unit_label(r0.unit, q)} in {f0.path.name} (column '{r0.header}'); mixed units in "
                                f"folder '{folder}' — export every file with one unit")
    return plans


# -- reading -----------------------------------------------------------------------------------
def batches(fp: FilePlan):
    """The rows of one planned file as :class:`Batch` es (SI units)."""
    read = {"mdf": mdf_batches, "parquet": parquet_batches}.get(fp.kind, csv_batches)
    for rb, first, word in read(fp):
        yield _batch(fp, rb, first, word)


def _text(arr, n: int) -> Text:
    """A text column as codes into its distinct names (stripped; an empty cell: code −1)."""
    import pyarrow as pa
    import pyarrow.compute as pc
    if isinstance(arr, pa.ChunkedArray):
        arr = arr.combine_chunks()
    if not pa.types.is_dictionary(arr.type):
        arr = pc.cast(arr, pa.string()).dictionary_encode()
    codes = np.asarray(arr.indices.to_numpy(zero_copy_only=False), np.int64)
    if arr.null_count:
        codes = np.where(arr.is_valid().to_numpy(zero_copy_only=False), codes, -1)
    raw = [str(v).strip() for v in arr.dictionary.to_pylist()]
    names = [v for v in dict.fromkeys(raw) if v]
    index = {v: i for i, v in enumerate(names)}
    remap = np.array([index.get(v, -1) for v in raw] + [-1], np.int64)    # ' A' and 'A' are one test; '' none
    return Text(remap[codes], names)


def _number(fp: FilePlan, arr, q: str) -> np.ndarray:
    import pyarrow as pa
    import pyarrow.compute as pc
    r = fp.columns[q]
    if not pa.types.is_floating(arr.type):
        try:
            arr = pc.cast(arr, pa.float64())
        except (pa.ArrowInvalid, pa.ArrowNotImplementedError):
            raise UserError(f"{fp.path}, column '{r.header}': holds {arr.type} values, not numbers; give {q} as "
                            f"numbers") from None
    x = np.asarray(arr.to_numpy(zero_copy_only=False), float)
    if r.scale != 1.0 or r.offset != 0.0:
        x = x * r.scale + r.offset
    return x


def _batch(fp: FilePlan, rb, first: int, word: str) -> Batch:
    n = rb.num_rows
    col = {q: rb.column(r.header) for q, r in fp.columns.items()}
    by_row = "test_id" in col and "test_id" not in fp.constants
    if "test_id" in col and not by_row:
        _same_id(fp, _text(col["test_id"], n), first, word)
    tid = _text(col["test_id"], n) if by_row else Text.constant(str(fp.constants["test_id"]), n)
    direction = _text(col["direction"], n) if "direction" in col else None
    force = _number(fp, col["hand_force_N"], "hand_force_N") if "hand_force_N" in col else None
    if (direction is None or force is None) and by_row:
        per_dir, per_force = _from_manifest(fp, tid, first, word)
        direction = per_dir if direction is None else direction
        force = per_force if force is None else force
    if direction is None:
        direction = Text.constant(str(fp.constants["direction"]), n)
    force = np.full(n, float(fp.constants["hand_force_N"])) if force is None else force
    amb = _number(fp, col["ambient_C"], "ambient_C") if "ambient_C" in col else None
    b = Batch(str(fp.path), first, word, tid, direction, force, _number(fp, col["time_s"], "time_s"),
              _number(fp, col["drum_temp_C"], "drum_temp_C"), _number(fp, col["torque_Nm"], "torque_Nm"), amb,
              fp.columns)
    if fp.manifest is not None:
        fp.manifest.check_agrees(b, tid.names, tid.codes)
    return b


def _same_id(fp: FilePlan, tid: Text, first: int, word: str) -> None:
    """UserError where a folder file's test_id column names another test than the file's name."""
    for k, name in enumerate(tid.names):
        hit = np.flatnonzero(tid.codes == k)
        if hit.size and name != fp.constants["test_id"]:
            raise UserError(f"{fp.path}, {word} {first + int(hit[0])}, column {fp.columns['test_id'].describe()}: "
                            f"test '{name}', but a folder's file is the test it is named after "
                            f"('{fp.constants['test_id']}'); rename the file or correct the column")


def _from_manifest(fp: FilePlan, tid: Text, first: int, word: str) -> tuple[Text, np.ndarray]:
    """Each row's direction and hand force from the manifest row of its test_id (a single log with test ids)."""
    rows = fp.manifest.rows
    for k, name in enumerate(tid.names):
        hit = np.flatnonzero(tid.codes == k)
        if name not in rows and hit.size:
            at = f"{fp.path}, {word} {first + int(hit[0])}"
            raise UserError(f"{at}, column {fp.columns['test_id'].describe()}: test '{name}' has no row in the "
                            f"manifest {fp.manifest.path}; add one (test_id,direction,hand_force_N)")
    dirs = [rows[t]["direction"] if t in rows else "" for t in tid.names]
    forces = np.array([rows[t]["hand_force_N"] if t in rows else np.nan for t in tid.names] + [np.nan])
    return Text(tid.codes.copy(), dirs), forces[tid.codes]          # code −1 (no test id) → the last: NaN


def read_log(path, colmap: ColumnMap | None = None, manifest: str | None = None,
             window_s: float | None = None, notes: list[str] | None = None):
    """Measurements from a bench log (file or folder, CSV or Parquet), reduced when it is dense
    (:mod:`rollaway.bench.reduction`; *window_s* None: automatic, 0: every sample a row)."""
    from rollaway.bench.reduction import Reducer
    plans = plan(path, colmap, manifest)
    reducer = Reducer(keep_raw=2 ** 62 if window_s == 0 else None)
    notes = list(notes or [])
    ignored: dict[tuple, list[str]] = {}
    for fp in plans:
        cols = tuple(h for h in fp.header if h not in {r.header for r in fp.columns.values()})
        if cols:
            ignored.setdefault(cols, []).append(fp.path.name)
    for cols, names in ignored.items():
        where = str(plans[0].path) if len(plans) == 1 else f"{Path(path)} ({len(names)} of {len(plans)} files)"
        notes.append(f"{where}: ignoring column(s) {', '.join(repr(h) for h in cols[:6])}"
                     f"{', ...' if len(cols) > 6 else ''} (not used)")
    for fp in plans:
        notes += [n for n in fp.notes if n not in notes]
        before = reducer.rows
        for b in batches(fp):
            reducer.add(b)
        if reducer.rows == before:
            at = f"{fp.path}, line {fp.header_line + 1}" if fp.kind == "csv" else str(fp.path)
            raise UserError(f"{at}: no data rows after the header — a test with no samples; add its samples or "
                            f"remove the file" +
                            (" and its manifest row" if fp.manifest and fp.path.stem in fp.manifest.rows else ""))
    m = plans[0].manifest
    if m is not None:
        p = Path(path)
        m.check_all_used(reducer.tests, f"folder '{p}' (no file named after it)" if p.is_dir() else
                         f"{p.name} (no row has this test_id)" if "test_id" in plans[0].columns else
                         f"{p.name} (this file is test '{p.stem}')")
    return reducer.finish(str(path), len(plans), window_s, notes)
