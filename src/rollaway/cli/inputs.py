"""Telling the kinds of input file apart, so that a file given to the wrong command says so.

A scenario TOML describes one parked car (``grade_pct``, ``hand_force_N``, ...); a sweep TOML
has a ``[grid]`` table; a parameter set has parameter names such as ``mu_drum``.  Each kind
goes to its own command; these checks run before the full validation so that the message
names the kind of file and the command that takes it.
"""
from __future__ import annotations

from pathlib import Path

from rollaway.errors import UserError

SWEEP_KEYS = ("grid", "cases", "base", "base_preset", "band")
SCENARIO_KEYS = ("grade_pct", "hand_force_N", "direction", "occupants", "duration_s")


def toml_kind(path) -> str | None:
    """'sweep', 'scenario' or None (not a readable TOML, or a kind not recognised here)."""
    from rollaway.errors import read_toml
    p = Path(path)
    if p.suffix.lower() != ".toml" or not p.is_file():
        return None
    try:
        data = read_toml(p, "TOML file", "")     # BOM, bad bytes, deep nesting: the loader's own errors later
    except UserError:
        return None
    if any(k in data for k in SWEEP_KEYS):
        return "sweep"
    if any(k in data for k in SCENARIO_KEYS):
        return "scenario"
    return None


def expect_scenario(path, command: str) -> None:
    """UserError when *path* is a sweep file given to a command that takes one scenario."""
    if toml_kind(path) == "sweep":
        raise UserError(f"{path} is a sweep file (it has sweep keys such as [grid] or base), not a scenario; "
                        f"'rollaway {command}' takes one scenario (see scenarios/*.toml) — "
                        f"run a sweep with 'rollaway sweep {path}'")


def expect_sweep(path) -> None:
    """UserError when *path* is a scenario file given to ``rollaway sweep``."""
    if toml_kind(path) == "scenario":
        raise UserError(f"{path} is a scenario file (one parked car), not a sweep; simulate it with "
                        f"'rollaway simulate {path}' — a sweep file has a [grid] table (see scenarios/sweeps/)")
