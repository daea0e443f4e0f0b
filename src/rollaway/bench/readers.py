"""The file kinds a bench log comes in, read as pyarrow record batches in bounded memory.

* CSV: pyarrow's streaming reader (``,`` and ``.``, or as European exports write them, ``;`` (or tab)
  and ``,``), 1 MB blocks; a row pyarrow cannot take (a ragged row, a cell that is not a number) is
  then found by a second pass with Python's csv module, so its line is named whatever the file's size;
* Parquet: row groups in batches;
* ASAM MDF4: :mod:`rollaway.bench.asam_mdf`.

Each yields ``(record batch, number of its first line or row, "line" | "row")``.
"""
from __future__ import annotations

import csv
import re
from pathlib import Path

from rollaway.bench.columns import TEXT
from rollaway.errors import UserError

BLOCK_BYTES = 1 << 20         # CSV block (≈ 25 000 rows): pyarrow keeps ~30 blocks in flight, so 1 MB blocks hold
#                                 the reader to ~40 MB (16 MB blocks: ~500 MB); larger blocks are not faster here
BATCH_ROWS = 262_144            # Parquet rows per batch
DIALECT = (",", ".")            # CSV delimiter and decimal mark
# cells pyarrow reads as missing in a numeric column (its default null_values): NaN for every reader
NULLS = frozenset(("", "#N/A", "#N/A N/A", "#NA", "-1.#IND", "-1.#QNAN", "-NaN", "-nan", "1.#IND", "1.#QNAN", "N/A",
                   "NA", "NULL", "NaN", "n/a", "nan", "null"))
NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(inf|infinity|nan)", re.IGNORECASE)


def parse_number(cell: str, decimal: str = ".") -> float | None:
    """A numeric cell as pyarrow reads it: a missing-value mark (the cell exactly) → NaN, a number (spaces around
    it allowed) → float, anything else (a blank cell of spaces too) → None."""
    if cell in NULLS:
        return float("nan")
    c = cell.strip()
    c = c.replace(decimal, ".") if decimal != "." else c
    return float(c) if NUMBER.fullmatch(c) else None


def sniff_dialect(header_line: str, data_line: str) -> tuple[str, str]:
    """(delimiter, decimal mark) of a CSV from its header and first data line: the most frequent of ``, ; tab``
    in the header; a decimal comma where the delimiter is not a comma and the data has ``digit,digit``."""
    delim = max((",", ";", "\t"), key=header_line.count)
    delim = delim if header_line.count(delim) else ","
    decimal = "," if delim != "," and re.search(r"\d,\d", data_line) else "."
    return delim, decimal


def check_names(header: list[str], where: str) -> None:
    """UserError for a header of units only ('[s],[degC],[Nm]'): the names are on another line or missing."""
    if header and header[0].strip().lower().startswith("sep=") and not any(h.strip() for h in header[1:]):
        raise UserError(f"{where}: '{header[0].strip()}' is a spreadsheet's separator hint, not the header; delete "
                        f"this line so that the header is the first line")
    if header and all(re.fullmatch(r"\s*[\[(][^\[\]()]*[\])]\s*", h) for h in header):
        raise UserError(f"{where}: the header has units but no column names ({', '.join(repr(h) for h in header[:4])}"
                        f"{', ...' if len(header) > 4 else ''}); write each name with its unit on one header line, "
                        f"e.g. 'time_s [s]', or map the columns with --columns")


def read_header(path: Path, kind: str) -> tuple[list[str], int, tuple[str, str]]:
    """The column names of a file, the line they are on (Parquet: the schema, line 0) and the CSV dialect."""
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
                    dialect = sniff_dialect(line, fh.readline())
                    return [h.strip() for h in next(csv.reader([line], delimiter=dialect[0]))], line_no, dialect
    except UnicodeDecodeError:
        raise UserError(f"{path}, line 1: not a UTF-8 text file; save the measurements as UTF-8 CSV") from None
    raise UserError(f"{path}, line 1: the file is empty; expected a header row")


def csv_batches(fp):
    """Record batches of the planned columns of a CSV file (numbers as float64, text dictionary-encoded)."""
    import pyarrow as pa
    import pyarrow.csv as pcsv
    types = {r.header: (pa.dictionary(pa.int32(), pa.string()) if q in TEXT else pa.float64())
             for q, r in fp.columns.items()}
    ro = pcsv.ReadOptions(block_size=BLOCK_BYTES, skip_rows=fp.header_line, use_threads=True,
                          column_names=arrow_names(fp.header))     # the header's names, stripped, as the plan has them
    co = pcsv.ConvertOptions(include_columns=list(types), column_types=types, strings_can_be_null=False,
                             decimal_point=fp.dialect[1])
    first = fp.header_line + 1
    try:
        reader = pcsv.open_csv(fp.path, read_options=ro, convert_options=co,
                               parse_options=pcsv.ParseOptions(delimiter=fp.dialect[0]))
        for rb in reader:
            yield rb, first, "line"
            first += rb.num_rows
    except pa.ArrowException as exc:
        raise UserError(first_bad_row(fp) or arrow_message(fp, exc, first)) from None


def arrow_names(header: list[str]) -> list[str]:
    """Column names for pyarrow: the stripped header cells, a repeated one made unique ('x', 'x#2')."""
    out, seen = [], {}
    for h in header:
        seen[h] = seen.get(h, 0) + 1
        out.append(h if seen[h] == 1 else f"{h}#{seen[h]}")
    return out


def first_bad_row(fp) -> str | None:
    """The first row pyarrow cannot take — a row with another number of fields than the header, or a cell of
    a numeric column that is not a number — as 'file, line N: ...' (a second pass, line by line)."""
    numeric = {fp.header.index(r.header): r.header for q, r in fp.columns.items() if q not in TEXT}
    delim, decimal = fp.dialect
    with open(fp.path, encoding="utf-8-sig", newline="") as fh:
        reader = csv.reader(fh, delimiter=delim)
        try:
            for row in reader:
                n = reader.line_num
                if n <= fp.header_line or not row:      # pyarrow skips empty lines only
                    continue
                if len(row) != len(fp.header):
                    return ragged_message(fp.path, n, len(row), len(fp.header), delim)
                for j, h in numeric.items():
                    if parse_number(row[j], decimal) is None:
                        return (f"{fp.path}, line {n}, column '{h}': {row[j].strip()!r} is not a number; give a "
                                f"value or delete the row")
        except csv.Error as exc:
            return (f"{fp.path}, line {reader.line_num}: {exc}; a cell that long or broken quoting is not bench "
                    f"data — check the quotes on this line")
    return None


def ragged_message(path, line: int, fields: int, header: int, delim: str = ",") -> str:
    return (f"{path}, line {line}: {fields} fields but the header has {header}; fix the separators ('{delim}') "
            f"on this line")


def parquet_batches(fp):
    """Record batches of the planned columns of a Parquet file."""
    import pyarrow as pa
    import pyarrow.parquet as pq
    first = 1
    try:
        for rb in pq.ParquetFile(fp.path).iter_batches(batch_size=BATCH_ROWS,
                                                       columns=[r.header for r in fp.columns.values()]):
            yield rb, first, "row"
            first += rb.num_rows
    except pa.ArrowException as exc:
        raise UserError(arrow_message(fp, exc, first)) from None


def mdf_batches(fp):
    """Record batches of the planned channels of an ASAM MDF4 file."""
    from rollaway.bench.asam_mdf import record_batches
    first = 1
    for rb in record_batches(fp.path, [r.header for r in fp.columns.values()], *fp.channels):
        yield rb, first, "row"
        first += rb.num_rows


def arrow_message(fp, exc, first: int) -> str:
    text = str(exc).splitlines()[0]
    m = re.search(r"column #(\d+).*invalid value '([^']*)'", text)
    if m:
        idx = int(m.group(1))
        names = [h for h in fp.header if h in {r.header for r in fp.columns.values()}]
        col = names[idx] if idx < len(names) else "?"
        return (f"{fp.path}, column '{col}': {m.group(2)!r} is not a number (in the rows from line {first} on); "
                f"give every cell of '{col}' as a number, or delete the row")
    return f"{fp.path}: cannot be read ({text}); export it again as CSV or Parquet"
