"""Options shared by the bench commands (compare, diagnose, fit, synth)."""
from __future__ import annotations


def load_plugins(files) -> list[str]:
    from rollaway.effects import load_effect_file
    names = []
    for f in files or ():
        names += load_effect_file(f)
    return names


def parse_effects(specs) -> dict[str, dict[str, float]]:
    """``NAME`` / ``NAME=param=value,...`` options → {name: values}; names validated, repeats refused."""
    from rollaway.identify.synth import parse_effect_spec
    from rollaway.errors import UserError
    out: dict[str, dict[str, float]] = {}
    for s in specs or ():
        name, values = parse_effect_spec(s)
        if name in out:
            raise UserError(f"--effect {name} is given twice; give each effect once")
        out[name] = values
    return out


FORMAT_HELP = "text | json (the result, decision first, on stdout)"


def load_data(path):
    """Load a measurement CSV (validated) and print its notes on stderr."""
    from pathlib import Path

    import typer

    from rollaway.errors import UserError
    from rollaway.identify.measurements import load_measurements
    if Path(path).is_dir():
        csvs = sorted(p.name for p in Path(path).glob("*.csv"))
        hint = f" (it holds {', '.join(csvs[:3])}{', ...' if len(csvs) > 3 else ''})" if csvs else ""
        raise UserError(f"'{path}' is a folder; give one measurement CSV file{hint}, e.g. "
                        f"'rollaway compare bench.csv' (make one with 'rollaway synth --out bench.csv')")
    data = load_measurements(path)
    for note in data.notes:
        typer.echo(f"note: {note}", err=True)
    return data


def prepare_outputs(**paths) -> None:
    """Create the folders of the output files the user asked for, before any work (flag name → path)."""
    from rollaway.errors import ensure_parent_dir
    for flag, path in paths.items():
        if path:
            ensure_parent_dir(path, "--" + flag.replace("_out", "").replace("_", "-"))


def write_outputs(result, *, report=None, json_out=None, plot=None, fmt: str = "text") -> None:
    """Print *result*'s summary (text) or its data (json, decision included) on stdout, then write the
    HTML report, JSON file and plot the user asked for (their paths on stderr with --format json)."""
    import json

    import typer

    from rollaway.cli.output import echo_json
    from rollaway.jsonsafe import to_jsonable
    if fmt == "json":
        echo_json(result.as_dict())
    else:
        typer.echo(result.summary())
    say = (lambda m: typer.echo(m, err=True)) if fmt == "json" else typer.echo
    if plot:
        result.plot(plot)
        say(f"plot: {plot}")
    if report:
        result.report(report)
        say(f"report: {report}")
    if json_out:
        with open(json_out, "w", encoding="utf-8") as fh:
            json.dump(to_jsonable(result.as_dict()), fh, indent=2)
        say(f"json: {json_out}")
