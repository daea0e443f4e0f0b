"""ASAM MDF4 bench logs (``.mf4``/``.mdf``) through asammdf, an optional extra (``pip install 'rollaway[mdf]'``).

Each channel becomes a column named ``"<channel> [<unit>]"`` (the unit MDF stores with it), so the column map
and the unit conversion of :mod:`rollaway.bench.columns` apply as for CSV; the master channel (time, in s)
stands for ``time_s`` unless the map names another.  Channels of different groups are aligned on one time base
by asammdf (:meth:`asammdf.MDF.to_dataframe`).  An MDF file is read whole (asammdf decodes by group).
"""
from __future__ import annotations

from pathlib import Path

from rollaway.errors import UserError

ROWS = 262_144


def _open(path: Path):
    try:
        from asammdf import MDF
    except ImportError:
        raise UserError(f"{path}: reading MDF4 needs the optional extra asammdf: pip install 'rollaway[mdf]' "
                        f"(or export the log as CSV or Parquet)") from None
    try:
        return MDF(str(path))
    except Exception as exc:            # asammdf raises many kinds for a file that is not MDF
        raise UserError(f"{path}: not a readable MDF file ({exc}); export it again") from None


def header(path: Path) -> tuple[list[str], dict[str, str], str | None]:
    """(column cells, cell → channel name, the master channel's cell)."""
    mdf = _open(path)
    cells, names, master = [], {}, None
    for gi, group in enumerate(mdf.groups):
        mi = mdf.masters_db.get(gi)
        for ci, ch in enumerate(group.channels):
            cell = f"{ch.name} [{ch.unit}]" if ch.unit else ch.name
            if cell in names:
                continue
            cells.append(cell)
            names[cell] = ch.name
            if ci == mi and master is None:
                master = cell
    mdf.close()
    return cells, names, master


def record_batches(path: Path, cells: list[str], names: dict[str, str], master: str | None):
    """The wanted *cells* as pyarrow record batches (master channel cells from the time base)."""
    import pyarrow as pa
    mdf = _open(path)
    wanted = [names[c] for c in cells if c != master]
    try:
        df = mdf.to_dataframe(channels=wanted, time_from_zero=False)
    except Exception as exc:
        raise UserError(f"{path}: channels {', '.join(wanted)} cannot be read together ({exc})") from None
    finally:
        mdf.close()
    cols = {c: (df.index.to_numpy() if c == master else df[names[c]].to_numpy()) for c in cells}
    table = pa.table(cols)
    for rb in table.to_batches(max_chunksize=ROWS):
        yield rb
