"""``rollaway params``: list a parameter set with units, sources and what is assumed."""
from __future__ import annotations

from typing import Optional

import typer

from rollaway.cli.output import write_table
from rollaway.model.drum_model import load_model
from rollaway.model.parameters import SPEC_BY_NAME


def params(
    source: Optional[str] = typer.Argument(None, metavar="SET", help="set name (paper) or TOML file"),
    fmt: str = typer.Option("table", "--format", metavar="FORMAT", help="csv | json | table"),
) -> None:
    """List every parameter of a set: value, unit, source; 'assumed' marks values not in the paper's Table 1."""
    model = load_model(source)
    d = model.params.as_dict()
    cols = {
        "name": list(d),
        "symbol": [SPEC_BY_NAME[k].symbol for k in d],
        "value": [float(v) for v in d.values()],
        "unit": [SPEC_BY_NAME[k].unit for k in d],
        "assumed": [bool(SPEC_BY_NAME[k].assumed) if fmt == "json" else ("yes" if SPEC_BY_NAME[k].assumed else "")
                    for k in d],
        "source": [SPEC_BY_NAME[k].source for k in d],
    }
    if model.calibration:            # a calibrated model: what the bench data said of each brake parameter
        where = {"shoe_arm_ratio": "shoe_arm_friction_m"}
        cols["calibration"] = [model.calibration.get(k, "") for k in d]
        for k, text in model.calibration.items():
            if where.get(k, k) in d:
                cols["calibration"][list(d).index(where.get(k, k))] = f"{k} {text}" if k in where else text
    for e in model.effects:          # a model file's effects: their values, after the set's
        for par in e.parameters:
            key = f"{e.name}.{par.name}"
            for col, val in (("name", key), ("symbol", ""), ("value", float(model.values[key])), ("unit", par.unit),
                             ("assumed", ""), ("source", f"effect '{e.name}' ({model.name})")):
                cols[col].append(val)
            if "calibration" in cols:
                cols["calibration"].append("")
    write_table(cols, fmt)


def register(app: typer.Typer) -> None:
    app.command("params")(params)
