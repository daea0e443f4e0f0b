"""Crash-safe storage of a sweep's simulated points.

``journal.jsonl`` in the output folder holds one JSON line per finished simulation,
keyed by the point's stable id (a hash of its inputs, :func:`rollaway.sweep.spec.point_ids`).
Each line is written, flushed and fsync'ed as its point finishes, so a run that is
interrupted — Ctrl-C, SIGTERM or SIGKILL — loses at most the points in flight.  A line
torn by a kill is cut off when the journal is reopened; any other damaged line (not UTF-8,
NUL bytes, not a record) is dropped and its point simulated again.  Running the sweep again reads
the journal and simulates only the ids it does not hold: no point lost, none done twice.

The analytic columns are not journalled: they are recomputed for every point in
milliseconds.  ``results.parquet`` and ``results.csv`` are the consolidated table, replaced
atomically (write to a temporary file, then rename).
"""
from __future__ import annotations

import json
import math
import os
import uuid
from pathlib import Path

import pandas as pd

JOURNAL = "journal.jsonl"


def _clean(value):
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    return value


class Journal:
    """Append-only JSON-lines record of finished simulations (one per point id)."""

    def __init__(self, folder: str | Path):
        self.path = Path(folder) / JOURNAL
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.duplicates = 0
        self.damaged = 0
        self._file = None

    def _repair(self) -> None:
        """Cut a last line torn by a kill (no trailing newline) so appends start on a fresh line."""
        if not self.path.exists():
            return
        data = self.path.read_bytes()
        if data and not data.endswith(b"\n"):
            keep = data.rfind(b"\n") + 1
            with open(self.path, "r+b") as fh:
                fh.truncate(keep)

    def load(self) -> dict[str, dict]:
        """Every record by point id (first one wins; later duplicates are counted, not used).

        A damaged line — torn, not UTF-8, with NUL bytes (a crash on some file systems), not a
        JSON object with a text ``point_id`` — is dropped: the journal is rewritten without it
        (atomically) and its point, absent from the records, is simulated again.
        """
        self._repair()
        records: dict[str, dict] = {}
        self.duplicates = self.damaged = 0
        if not self.path.exists():
            return records
        good: list[bytes] = []
        for raw in self.path.read_bytes().split(b"\n"):
            if not raw.strip():
                continue
            rec = _parse_line(raw)
            if rec is None:
                self.damaged += 1
                continue
            good.append(raw)
            pid = rec["point_id"]
            if pid in records:
                self.duplicates += 1
                continue
            records[pid] = rec
        if self.damaged:
            _rewrite(self.path, b"".join(line + b"\n" for line in good))
        return records

    def append(self, record: dict) -> None:
        if self._file is None:
            self._repair()
            self._file = open(self.path, "a", encoding="utf-8")
        self._file.write(json.dumps({k: _clean(v) for k, v in record.items()}) + "\n")
        self._file.flush()
        os.fsync(self._file.fileno())

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None


def _parse_line(raw: bytes) -> dict | None:
    """A journal line as a record, or None when it is damaged."""
    if b"\x00" in raw:
        return None
    try:
        rec = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError):
        return None
    if not isinstance(rec, dict) or not isinstance(rec.get("point_id"), str):
        return None
    return rec


def _rewrite(path: Path, data: bytes) -> None:
    tmp = _temporary(path)
    with open(tmp, "wb") as fh:
        fh.write(data)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


def drop_records(folder: str | Path, point_ids: set[str]) -> None:
    """Rewrite the journal without *point_ids* (used to retry failed points)."""
    path = Path(folder) / JOURNAL
    if not path.exists() or not point_ids:
        return
    keep = []
    for raw in path.read_bytes().split(b"\n"):
        rec = _parse_line(raw) if raw.strip() else None
        if rec is not None and rec["point_id"] not in point_ids:
            keep.append(raw + b"\n")
    _rewrite(path, b"".join(keep))


TABLE_CHUNK_ROWS = 200_000


def _temporary(path: Path) -> Path:
    """A temporary name next to *path*, unique per process and call (never shared by two writers)."""
    return path.with_name(f".{path.name}.{os.getpid()}.{uuid.uuid4().hex[:8]}.tmp")


def write_table(df: pd.DataFrame, folder: str | Path, stem: str = "results") -> tuple[Path, Path]:
    """Write *df* as ``stem.parquet`` and ``stem.csv`` atomically; return both paths.

    Written in slices of :data:`TABLE_CHUNK_ROWS` rows (one Parquet row group each), so the
    memory for a 2 000 000-row table stays a fraction of the table itself.
    """
    import pyarrow as pa
    import pyarrow.csv as pa_csv
    import pyarrow.parquet as pq

    folder = Path(folder)
    paths = folder / f"{stem}.parquet", folder / f"{stem}.csv"
    tmp_pq, tmp_csv = (_temporary(p) for p in paths)
    try:
        schema = pa.Schema.from_pandas(df.iloc[:TABLE_CHUNK_ROWS], preserve_index=False)
        with pq.ParquetWriter(tmp_pq, schema) as pw, \
                pa_csv.CSVWriter(tmp_csv, schema, write_options=pa_csv.WriteOptions(quoting_style="needed")) as cw:
            for i in range(0, max(len(df), 1), TABLE_CHUNK_ROWS):
                chunk = pa.Table.from_pandas(df.iloc[i:i + TABLE_CHUNK_ROWS], schema=schema, preserve_index=False)
                pw.write_table(chunk)
                cw.write_table(chunk)
        os.replace(tmp_pq, paths[0])
        os.replace(tmp_csv, paths[1])
    finally:
        for t in (tmp_pq, tmp_csv):
            t.unlink(missing_ok=True)
    return paths
