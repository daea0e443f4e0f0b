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


DATA_HELP = ("bench log: a CSV or Parquet file, or a folder with one file per test (canonical columns "
             "test_id,direction,hand_force_N,time_s,drum_temp_C,torque_Nm[,ambient_C] or mapped with --columns)")
SMALL_CSV_BYTES = 1 << 20      # a canonical CSV up to this size is tokenized by the strict CSV loader (same rules)


def columns_option():
    import typer
    return typer.Option([], "--columns", metavar="MAP",
                        help="where the quantities are and in which unit: NAME=COLUMN[unit] (e.g. "
                             "'drum_temp_C=T_drum[degF]', repeatable) or a .toml file with a [columns] table "
                             "(default: the folder's columns.toml, if any); a unit that differs from the header's "
                             "needs a trailing '!' (the header is wrong: 'drum_temp_C=T_drum[degF]!')")


def manifest_option():
    import typer
    return typer.Option(None, "--manifest", metavar="FILE",
                        help="CSV with test_id,direction,hand_force_N per test, for a folder or a single log with "
                             "a test_id column (a folder's manifest.csv is found by itself)")


def window_option():
    import typer
    return typer.Option(None, "--window-s", min=0.0, metavar="S",
                        help="reduce the log to means over windows of S seconds (default: automatic for logs of "
                             "8+ samples per window; 0: fit every sample)")


def load_data(path, columns=(), manifest=None, window_s=None):
    """Load bench data (validated) and print its notes on stderr: a small canonical CSV sample by sample,
    anything else (Parquet, a folder, mapped columns, a long log) through the streaming reader."""
    from pathlib import Path

    import typer

    from rollaway.bench.columns import column_map, is_lab_format
    from rollaway.bench.measurements import load_measurements
    p = Path(path)
    own = p / "columns.toml"
    notes = []
    if not columns and p.is_dir() and own.is_file():          # a folder that carries its own column map
        columns = [own]
        notes.append(f"column map {own}")
    elif columns and p.is_dir() and own.is_file():
        notes.append(f"--columns is used, not the folder's {own.name}")
    colmap = column_map(columns)
    streaming = bool(colmap) or manifest or is_lab_format(p) or not p.is_file() or \
        p.stat().st_size > SMALL_CSV_BYTES or _units_in_header(p)
    if streaming:
        from rollaway.bench.sources import read_log
        data = read_log(p, colmap, manifest, window_s, notes)
    else:                       # the same rules and rows as the streaming reader (bench.measurements)
        data = load_measurements(path, window_s)
        data.notes[:0] = notes
    for note in data.notes:
        typer.echo(f"note: {note}", err=True)
    return data


def _units_in_header(path) -> bool:
    """True when a header cell carries a unit ('torque_Nm [kN·m]'): the column map reads it (the streaming reader)."""
    from rollaway.bench.columns import split_header
    from rollaway.bench.readers import read_header
    from rollaway.errors import UserError
    try:
        header = read_header(path, "csv")[0]
    except UserError:
        return False                    # the strict loader names what is wrong with it
    return any(split_header(h)[1] for h in header)


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
        text = json.dumps(to_jsonable(result.as_dict()), indent=2)     # whole before the file is opened
        with open(json_out, "w", encoding="utf-8") as fh:
            fh.write(text + "\n")
        say(f"json: {json_out}")
