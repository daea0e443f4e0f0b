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


def load_data(path):
    """Load a measurement CSV (validated) and print its notes on stderr."""
    import typer

    from rollaway.identify.measurements import load_measurements
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


def write_outputs(result, *, report=None, json_out=None, plot=None) -> None:
    """Print *result*'s summary, then write the HTML report, JSON and plot the user asked for."""
    import json

    import typer

    from rollaway.jsonsafe import to_jsonable
    typer.echo(result.summary())
    if plot:
        result.plot(plot)
        typer.echo(f"plot: {plot}")
    if report:
        result.report(report)
        typer.echo(f"report: {report}")
    if json_out:
        with open(json_out, "w", encoding="utf-8") as fh:
            json.dump(to_jsonable(result.as_dict()), fh, indent=2)
        typer.echo(f"json: {json_out}")
