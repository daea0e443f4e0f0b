"""Reading bench logs as labs write them: CSV or Parquet, one file or a folder with one file per test.

A *source* yields :class:`Batch` es — up to a few hundred thousand rows each, already in the
canonical quantities and SI units (:mod:`rollaway.bench.columns`) — so a log of any length
is read in bounded memory (pyarrow's streaming CSV reader, Parquet row groups).

* One file: a ``test_id`` column says which test each row belongs to; without one the whole file
  is one test named after the file.
* A folder: every ``*.csv`` / ``*.parquet`` file is one test, its ``test_id`` the file name
  (without the suffix).  Direction and hand force come from columns of the file or from a small
  manifest (``manifest.csv`` in the folder, or ``--manifest FILE``: ``test_id,direction,
  hand_force_N``, columns mapped like the logs').  Every file must log each quantity in one
  unit: a folder whose files disagree is refused (an export mistake, not something to guess).
"""
from __future__ import annotations

import csv
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rollaway.physics.drum import DIRECTIONS
from rollaway.errors import UserError, suggest
from rollaway.bench.batch import Batch, Text  # noqa: F401  (re-exported: the readers' unit of work)
from rollaway.bench.columns import CANONICAL, TEXT, ColumnMap, Resolved, Spec, _find, unit_label

SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet", ".mf4": "mdf", ".mdf": "mdf"}
MANIFEST_NAMES = ("manifest.csv", "tests.csv")
BLOCK_BYTES = 1 << 20         # CSV block (≈ 25 000 rows): pyarrow keeps ~30 blocks in flight, so 1 MB blocks hold
#                                 the reader to ~40 MB (16 MB blocks: ~500 MB); larger blocks are not faster here
BATCH_ROWS = 262_144            # Parquet rows per batch
DIALECT = (",", ".")            # CSV delimiter and decimal mark


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


def manifest_for(path: Path, manifest: str | None, colmap: ColumnMap) -> dict[str, dict] | None:
    """{test_id: {"direction", "hand_force_N"}} from the manifest, or None if there is none."""
    if manifest:
        m = Path(manifest)
        if not m.is_file():
            raise UserError(f"--manifest {manifest}: no such file; give a CSV with test_id,direction,hand_force_N")
    else:
        found = [path / n for n in MANIFEST_NAMES if path.is_dir() and (path / n).is_file()]
        if not found:
            return None
        m = found[0]
    header, line, rows = _read_small_csv(m)
    cols = {}
    for q in ("test_id", "direction", "hand_force_N"):
        # the map's column if the manifest has it, else the canonical name (a manifest is often written by hand)
        spec = colmap.specs.get(q)
        use = colmap if spec is not None and _find(header, spec.column) else ColumnMap()
        r = use.resolve(header, q, f"{m}, line {line}")
        if r is None:
            raise UserError(f"{m}, line {line}, column '{q}': missing; a manifest has the columns "
                            f"test_id,direction,hand_force_N (one row per test file)")
        cols[q] = r
    out = {}
    for n, row in rows:
        if len(row) != len(header):
            raise UserError(f"{m}, line {n}: {len(row)} fields but the header has {len(header)}; fix the commas")
        cell = {q: row[header.index(r.header)].strip() for q, r in cols.items()}
        try:
            force = float(cell["hand_force_N"]) * cols["hand_force_N"].scale + cols["hand_force_N"].offset
        except ValueError:
            raise UserError(f"{m}, line {n}, column {cols['hand_force_N'].describe()}: {cell['hand_force_N']!r} is "
                            f"not a number; give the hand force of test '{cell['test_id']}'") from None
        if cell["direction"] not in DIRECTIONS:
            raise UserError(f"{m}, line {n}, column {cols['direction'].describe()}: unknown direction "
                            f"{cell['direction']!r}{suggest(cell['direction'].lower(), DIRECTIONS)}; use 'downhill' "
                            f"or 'uphill'")
        out[cell["test_id"]] = {"direction": cell["direction"], "hand_force_N": force, "where": f"{m}, line {n}"}
    return out


def _read_small_csv(path: Path):
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise UserError(f"{path}, line 1: not a UTF-8 text file; save it as UTF-8 CSV") from None
    numbered = [(i + 1, r) for i, r in enumerate(csv.reader(text.splitlines())) if any(c.strip() for c in r)]
    if not numbered:
        raise UserError(f"{path}, line 1: the file is empty; expected a header row")
    (line, header), body = numbered[0], numbered[1:]
    return [h.strip() for h in header], line, body


def read_header(path: Path, kind: str) -> tuple[list[str], int, tuple[str, str]]:
    """The column names of a file, the line they are on (Parquet: the schema, line 0) and the CSV dialect
    (delimiter, decimal mark): ',' and '.', or as European exports write them, ';' (or tab) and ','."""
    if kind == "parquet":
        import pyarrow.parquet as pq
        try:
            return list(pq.ParquetFile(path).schema_arrow.names), 0, DIALECT
        except Exception as exc:      # pyarrow raises several kinds for a file that is not Parquet
            raise UserError(f"{path}: not a readable Parquet file ({exc}); export it again") from None
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:
            for line_no, line in enumerate(fh, 1):
                if line.strip():
                    if "\x00" in line:
                        raise UserError(f"{path}, line {line_no}: a NUL byte; this is not a text CSV file — "
                                        f"export the data again")
                    delim = max((",", ";", "\t"), key=line.count)
                    delim = delim if line.count(delim) else ","
                    data = fh.readline()
                    decimal = "," if delim != "," and re.search(r"\d,\d", data) else "."
                    return [h.strip() for h in next(csv.reader([line], delimiter=delim))], line_no, (delim, decimal)
    except UnicodeDecodeError:
        raise UserError(f"{path}, line 1: not a UTF-8 text file; save the measurements as UTF-8 CSV") from None
    raise UserError(f"{path}, line 1: the file is empty; expected a header row")


def plan(path, colmap: ColumnMap | None = None, manifest: str | None = None) -> list[FilePlan]:
    """The files of *path* (a file or a folder) with their columns resolved; every header problem raised."""
    colmap = colmap or ColumnMap()
    p = Path(path)
    if p.is_dir():
        files = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in SUFFIXES
                       and f.name.lower() not in MANIFEST_NAMES and not f.name.startswith("."))
        if not files:
            raise UserError(f"'{p}' is a folder with no .csv or .parquet file; give a measurement CSV file, or a "
                            f"folder with one CSV/Parquet file per test (named after the test)")
        if manifest and Path(manifest).resolve() in {f.resolve() for f in files}:
            files = [f for f in files if f.resolve() != Path(manifest).resolve()]
        per_test = True
    elif p.is_file():
        if p.suffix.lower() not in SUFFIXES:
            raise UserError(f"{p}: unknown file type '{p.suffix}'; give a .csv, .parquet or .mf4 file (or a "
                            f"folder of them, one per test)")
        files, per_test = [p], False
    else:
        raise UserError(f"measurement file '{p}' does not exist; check the path")
    tests = manifest_for(p, manifest, colmap)
    plans = []
    for f in files:
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
        cols = {}
        for q in CANONICAL:
            spec = colmap.specs.get(q)
            if (tests is not None and q in ("direction", "hand_force_N") and spec is not None
                    and _find(header, spec.column) is None):
                continue                          # the manifest gives it for this file
            if (r := colmap.resolve(header, q, where)) is not None:
                cols[q] = r
        constants = {}
        if per_test or "test_id" not in cols:
            constants["test_id"] = f.stem
            if "test_id" in cols and per_test:
                cols.pop("test_id")          # the file name is the test's id
        for q in ("hand_force_N", "direction"):
            if q in cols:
                continue
            info = (tests or {}).get(str(constants.get("test_id", "")))
            if info is None:
                what = "hand force" if q == "hand_force_N" else "direction"
                if tests is None:
                    fix = (f"add a column '{q}' (or map yours with --columns '{q}=...'), or put a manifest.csv "
                           f"with test_id,direction,hand_force_N next to the files")
                else:
                    fix = f"add a row for test '{constants.get('test_id', f.stem)}' to the manifest"
                if "test_id" not in constants:
                    fix = f"add a column '{q}' (or map yours with --columns '{q}=...')"
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
        plans.append(FilePlan(f, kind, header, hline, cols, constants, channels, dialect))
    _check_units(plans, p)
    return plans


def _check_units(plans: list[FilePlan], folder: Path) -> None:
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


# -- reading -----------------------------------------------------------------------------------
def batches(fp: FilePlan):
    """The rows of one planned file as :class:`Batch` es (SI units)."""
    if fp.kind == "mdf":
        from rollaway.bench.asam_mdf import record_batches
        first = 1
        for rb in record_batches(fp.path, [r.header for r in fp.columns.values()], *fp.channels):
            yield _batch(fp, rb, first, "row")
            first += rb.num_rows
    elif fp.kind == "parquet":
        yield from _parquet_batches(fp)
    else:
        yield from _csv_batches(fp)


def _csv_batches(fp: FilePlan):
    import pyarrow as pa
    import pyarrow.csv as pcsv
    types = {r.header: (pa.dictionary(pa.int32(), pa.string()) if q in TEXT else pa.float64())
             for q, r in fp.columns.items()}
    ro = pcsv.ReadOptions(block_size=BLOCK_BYTES, skip_rows=fp.header_line - 1, use_threads=True)
    co = pcsv.ConvertOptions(include_columns=list(types), column_types=types, strings_can_be_null=True,
                             decimal_point=fp.dialect[1])
    first = fp.header_line + 1
    try:
        reader = pcsv.open_csv(fp.path, read_options=ro, convert_options=co,
                               parse_options=pcsv.ParseOptions(delimiter=fp.dialect[0]))
        for rb in reader:
            yield _batch(fp, rb, first, "line")
            first += rb.num_rows
    except pa.ArrowInvalid as exc:
        raise UserError(_bad_cell(fp) or _arrow_message(fp, exc, first)) from None


def _bad_cell(fp: FilePlan) -> str | None:
    """The first cell of a numeric column that is not a number, as 'file, line N, column C: ...' (a rescan)."""
    import pyarrow as pa
    import pyarrow.csv as pcsv
    numeric = [r.header for q, r in fp.columns.items() if q not in TEXT]
    ro = pcsv.ReadOptions(block_size=BLOCK_BYTES, skip_rows=fp.header_line - 1)
    co = pcsv.ConvertOptions(include_columns=numeric, column_types={h: pa.string() for h in numeric})
    line = fp.header_line + 1
    try:
        for rb in pcsv.open_csv(fp.path, read_options=ro, convert_options=co,
                                parse_options=pcsv.ParseOptions(delimiter=fp.dialect[0])):
            for h in numeric:
                cells = rb.column(h).to_pylist()
                for i, c in enumerate(cells):
                    if c is None or not c.strip():
                        continue
                    try:
                        float(c.replace(fp.dialect[1], "."))
                    except ValueError:
                        return (f"{fp.path}, line {line + i}, column '{h}': {c!r} is not a number; give a value "
                                f"or delete the row")
            line += rb.num_rows
    except pa.ArrowInvalid:
        return None
    return None


def _parquet_batches(fp: FilePlan):
    import pyarrow as pa
    import pyarrow.parquet as pq
    first = 1
    try:
        for rb in pq.ParquetFile(fp.path).iter_batches(batch_size=BATCH_ROWS,
                                                       columns=[r.header for r in fp.columns.values()]):
            yield _batch(fp, rb, first, "row")
            first += rb.num_rows
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError) as exc:
        raise UserError(_arrow_message(fp, exc, first)) from None


def _arrow_message(fp: FilePlan, exc, first: int) -> str:
    text = str(exc).splitlines()[0]
    m = re.search(r"column #(\d+).*invalid value '([^']*)'", text)
    if m:
        idx = int(m.group(1))
        names = [h for h in fp.header if h in {r.header for r in fp.columns.values()}]
        col = names[idx] if idx < len(names) else "?"
        return (f"{fp.path}, column '{col}': {m.group(2)!r} is not a number (in the rows from line {first} on); "
                f"give every cell of '{col}' as a number, or delete the row")
    return f"{fp.path}: cannot be read ({text}); export it again as CSV or Parquet"


def _text(arr, n: int) -> Text:
    import pyarrow as pa
    import pyarrow.compute as pc
    if isinstance(arr, pa.ChunkedArray):
        arr = arr.combine_chunks()
    if not pa.types.is_dictionary(arr.type):
        arr = pc.cast(arr, pa.string()).dictionary_encode()
    codes = arr.indices.to_numpy(zero_copy_only=False)
    if arr.null_count:
        codes = np.where(arr.is_valid().to_numpy(zero_copy_only=False), codes, -1)
    names = [str(v).strip() for v in arr.dictionary.to_pylist()]
    return Text(np.asarray(codes, np.int64), names)


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
    tid = _text(col["test_id"], n) if "test_id" in col else Text.constant(str(fp.constants["test_id"]), n)
    if "direction" in col:
        direction = _text(col["direction"], n)
    else:
        direction = Text.constant(str(fp.constants["direction"]), n)
    force = _number(fp, col["hand_force_N"], "hand_force_N") if "hand_force_N" in col else \
        np.full(n, float(fp.constants["hand_force_N"]))
    amb = _number(fp, col["ambient_C"], "ambient_C") if "ambient_C" in col else None
    return Batch(str(fp.path), first, word, tid, direction, force, _number(fp, col["time_s"], "time_s"),
                 _number(fp, col["drum_temp_C"], "drum_temp_C"), _number(fp, col["torque_Nm"], "torque_Nm"), amb,
                 fp.columns)


def read_log(path, colmap: ColumnMap | None = None, manifest: str | None = None,
             window_s: float | None = None, notes: list[str] | None = None):
    """Measurements from a bench log (file or folder, CSV or Parquet), reduced when it is dense
    (:mod:`rollaway.bench.reduction`; *window_s* None: automatic, 0: every sample a row)."""
    from rollaway.bench.reduction import Reducer
    plans = plan(path, colmap, manifest)
    reducer = Reducer(keep_raw=2 ** 62 if window_s == 0 else None)
    notes = list(notes or [])
    for fp in plans:
        ignored = [h for h in fp.header if h not in {r.header for r in fp.columns.values()}]
        if ignored and len(plans) == 1:
            notes.append(f"{fp.path}: ignoring column(s) {', '.join(repr(h) for h in ignored[:6])}"
                         f"{', ...' if len(ignored) > 6 else ''} (not mapped)")
        for b in batches(fp):
            reducer.add(b)
    return reducer.finish(str(path), len(plans), window_s, notes)
