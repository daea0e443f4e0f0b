"""Writing tables of numbers as csv, json or an aligned text table."""
from __future__ import annotations

import json
import math
import sys
from collections.abc import Mapping, Sequence

from rollaway.errors import check_choice
from rollaway.jsonsafe import to_jsonable

FORMATS = ("csv", "json", "table")
REPORT_FORMATS = ("text", "json")     # commands whose result is a decision plus evidence


def echo_json(obj, out=None) -> None:
    """Print *obj* as strict JSON (NaN/inf → null) on *out* (stdout)."""
    out = sys.stdout if out is None else out
    json.dump(to_jsonable(obj), out, indent=1)
    out.write("\n")


def _fmt(v) -> str:
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f"{v:.12g}"
    return str(v)


def write_table(columns: Mapping[str, Sequence], fmt: str = "table", out=None, precision: int = 6) -> None:
    """Write equal-length *columns* to *out* (stdout) as csv, json (list of records) or a text table."""
    fmt = check_choice(fmt, FORMATS, "format")
    out = sys.stdout if out is None else out
    names = list(columns)
    rows = list(zip(*[list(columns[n]) for n in names]))
    if fmt == "csv":
        out.write(",".join(names) + "\n")
        for r in rows:
            out.write(",".join(_fmt(float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v)
                               for v in r) + "\n")
    elif fmt == "json":
        json.dump(to_jsonable([dict(zip(names, r)) for r in rows]), out, indent=1)
        out.write("\n")
    else:
        def cell(v):
            if isinstance(v, float):
                return "-" if math.isnan(v) else f"{v:.{precision}g}"
            return str(v)
        text = [[cell(v) for v in r] for r in rows]
        widths = [max([len(n)] + [len(t[i]) for t in text]) for i, n in enumerate(names)]
        out.write("  ".join(n.rjust(w) for n, w in zip(names, widths)) + "\n")
        for t in text:
            out.write("  ".join(c.rjust(w) for c, w in zip(t, widths)) + "\n")
