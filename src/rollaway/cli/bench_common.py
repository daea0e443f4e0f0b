"""Options shared by the bench commands (compare, diagnose, fit, synth)."""
from __future__ import annotations


def load_plugins(files) -> list[str]:
    from rollaway.bench.effects import load_effect_file
    names = []
    for f in files or ():
        names += load_effect_file(f)
    return names


def parse_effects(specs) -> dict[str, dict[str, float]]:
    """``NAME`` / ``NAME=param=value,...`` options → {name: values}; names validated, repeats refused."""
    from rollaway.bench.synth import parse_effect_spec
    from rollaway.errors import UserError
    out: dict[str, dict[str, float]] = {}
    for s in specs or ():
        name, values = parse_effect_spec(s)
        if name in out:
            raise UserError(f"--effect {name} is given twice; give each effect once")
        out[name] = values
    return out
