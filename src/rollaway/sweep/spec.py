"""SWEEP.toml: a grid (or list) of cases on top of a base scenario, validated.

Example (``scenarios/sweeps/grade-load.toml``)::

    description = "Where does the FMVSS 135 car hold?"
    base = "../fmvss135-uphill.toml"   # a scenario file, relative to this file
    # base_preset = "fmvss135"         # ... or a regulation preset (both directions)
    simulate = "band"                  # band | all | none
    band = [0.95, 1.08]                # analytic margin band simulated in MuJoCo (the default)

    [grid]                             # every combination of the listed values
    grade_pct = { start = 0, stop = 40, num = 41 }     # inclusive range (or step = 1)
    occupants = [1, 3, 5]
    direction = ["uphill", "downhill"]

    [[points]]                         # ... and/or single cases; unset axes come from the base
    grade_pct = 30
    hand_force_N = 445

Structural mistakes (unknown keys, wrong types, bad ranges) are :class:`UserError`
naming the file and key.  A *value* the model cannot take (a 120 % grade, 7
occupants) is not: that point is recorded with its error and the others run.
"""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from rollaway.errors import UserError, check_choice, read_toml, suggest
from rollaway.physics.drum import DIRECTIONS
from rollaway.regulations import PRESETS
from rollaway.scenario import Scenario, load_scenario, preset_scenarios

# the axes a sweep may vary; the last varies fastest in a grid
AXES = ("direction", "occupants", "grade_pct", "hand_force_N", "mu_drum", "initial_drum_temp_C",
        "tyre_road_mu", "duration_s")
NUMERIC_AXES = AXES[1:]
SIMULATE_MODES = ("band", "all", "none")
DEFAULT_BAND = (0.95, 1.08)   # see rollaway.sweep.analytic.in_band for why
MAX_POINTS = 2_000_000
_TOP_KEYS = ("description", "base", "base_preset", "simulate", "band", "grid", "points")


@dataclass(frozen=True)
class SweepSpec:
    """A validated sweep: the base scenario and one row per point (columns :data:`AXES` + ``point_id``)."""

    source: str
    base: Scenario
    points: pd.DataFrame
    simulate: str = "band"
    band: tuple[float, float] = DEFAULT_BAND
    description: str = ""

    @property
    def name(self) -> str:
        return Path(self.source).stem

    def with_model(self, model) -> "SweepSpec":
        """The same sweep on another drum model (its parameter set and effects; the base keeps its T_0)."""
        import dataclasses
        p = model.params.replace(initial_drum_temp_C=self.base.initial_drum_temp_C)
        base = dataclasses.replace(self.base, params=p, model=model.with_params(p))
        points = self.points.copy()
        points["point_id"] = point_ids(base, points)
        return dataclasses.replace(self, base=base, points=points)


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _axis_values(axis: str, value, where: str) -> list:
    """A grid entry: a list of values or a {start, stop, num|step} range."""
    if isinstance(value, dict):
        if axis == "direction":
            raise UserError(f"{where}: 'direction' takes a list of names, e.g. [\"uphill\", \"downhill\"]")
        return _range_values(value, where)
    if not isinstance(value, list):
        value = [value]
    if not value:
        raise UserError(f"{where}: empty list; give at least one value")
    for v in value:
        _check_value(axis, v, where)
    return list(value)


def _range_values(r: dict, where: str) -> list[float]:
    allowed = ("start", "stop", "num", "step")
    for k in r:
        if k not in allowed:
            raise UserError(f"{where}: unknown range key '{k}'{suggest(k, allowed)}; "
                            f"a range is {{start = 0, stop = 40, num = 41}} or {{start = 0, stop = 40, step = 1}}")
    for k in ("start", "stop"):
        if k not in r:
            raise UserError(f"{where}: range needs '{k}', e.g. {{start = 0, stop = 40, num = 41}}")
        if not _is_number(r[k]) or not math.isfinite(r[k]):
            raise UserError(f"{where}: range '{k}' must be a number, got {r[k]!r}")
    if ("num" in r) == ("step" in r):
        raise UserError(f"{where}: give exactly one of 'num' (how many values) or 'step' (spacing)")
    start, stop = float(r["start"]), float(r["stop"])
    if "num" in r:
        num = r["num"]
        if not isinstance(num, int) or isinstance(num, bool) or num < 1:
            raise UserError(f"{where}: range 'num' must be a whole number ≥ 1, got {num!r}")
        if num > MAX_POINTS:
            raise UserError(f"{where}: range 'num' = {num} is too many values (max {MAX_POINTS})")
        return [float(v) for v in np.linspace(start, stop, num)]
    step = r["step"]
    if not _is_number(step) or not step > 0 or not math.isfinite(step):
        raise UserError(f"{where}: range 'step' must be a number > 0, got {step!r}")
    count = int(math.floor(abs(stop - start) / step + 1e-9)) + 1
    if count > MAX_POINTS:
        raise UserError(f"{where}: range gives {count} values (max {MAX_POINTS}); use a larger step")
    sign = 1.0 if stop >= start else -1.0
    return [float(start + sign * i * step) for i in range(count)]


def _check_value(axis: str, v, where: str) -> None:
    if axis == "direction":
        if not isinstance(v, str):
            raise UserError(f"{where}: direction must be a quoted name ({', '.join(DIRECTIONS)}), got {v!r}")
        check_choice(v, DIRECTIONS, f"direction in {where}")
    elif not _is_number(v):
        raise UserError(f"{where}: '{axis}' must be a number, got {v!r}")


def _check_keys(table: dict, allowed, where: str) -> None:
    for key in table:
        if key not in allowed:
            raise UserError(f"{where}: unknown key '{key}'{suggest(key, allowed)}; valid keys: {', '.join(allowed)}")


def _base_scenario(data: dict, where: str, base_dir: Path) -> tuple[Scenario, list[str] | None]:
    """The base scenario, and the preset's directions when the base is a preset."""
    if ("base" in data) == ("base_preset" in data):
        raise UserError(f"{where}: give exactly one of 'base' (a scenario TOML file, relative to the sweep file) "
                        f"or 'base_preset' ({', '.join(PRESETS)})")
    if "base" in data:
        if not isinstance(data["base"], str):
            raise UserError(f"{where}: key 'base' must be a quoted file path, got {data['base']!r}")
        path = Path(data["base"])
        path = path if path.is_absolute() else base_dir / path
        if not path.is_file():
            raise UserError(f"{where}: key 'base': scenario file '{path}' does not exist; "
                            f"give a path relative to the sweep file")
        return load_scenario(path), None
    name = data["base_preset"]
    if not isinstance(name, str):
        raise UserError(f"{where}: key 'base_preset' must be a quoted preset name, got {name!r}")
    check_choice(name, PRESETS, f"base_preset in {where}")
    scenarios = preset_scenarios(name)
    return scenarios[0], [s.direction for s in scenarios]


def _settings(data: dict, where: str) -> tuple[str, tuple[float, float], str]:
    mode = data.get("simulate", "band")
    if not isinstance(mode, str):
        raise UserError(f"{where}: key 'simulate' must be one of {', '.join(SIMULATE_MODES)}, got {mode!r}")
    check_choice(mode, SIMULATE_MODES, f"simulate mode in {where} (key 'simulate')")
    band = data.get("band", list(DEFAULT_BAND))
    if (not isinstance(band, list) or len(band) != 2 or not all(_is_number(b) for b in band)
            or not 0 <= band[0] < band[1] or not all(math.isfinite(b) for b in band)):
        raise UserError(f"{where}: key 'band' must be two margins [low, high] with 0 ≤ low < high, "
                        f"e.g. [0.95, 1.08]; got {band!r}")
    desc = data.get("description", "")
    if not isinstance(desc, str):
        raise UserError(f"{where}: key 'description' must be a quoted string")
    return mode, (float(band[0]), float(band[1])), desc


def _base_values(base: Scenario) -> dict:
    return {a: getattr(base, a) for a in AXES}


def expand(base: Scenario, grid: dict[str, list] | None = None, points: list[dict] | None = None,
           default_directions: list[str] | None = None) -> pd.DataFrame:
    """Rows of AXES: the product of *grid* (unset axes from *base*) followed by the single *points*."""
    defaults = _base_values(base)
    frames = []
    if grid is not None or not points:
        axes_values = []
        for a in AXES:
            if grid and a in grid:
                axes_values.append(list(grid[a]))
            elif a == "direction" and default_directions:
                axes_values.append(list(default_directions))
            else:
                axes_values.append([defaults[a]])
        total = math.prod(len(v) for v in axes_values)
        if total > MAX_POINTS:
            raise UserError(f"the grid has {total} points (max {MAX_POINTS}); use fewer values per axis")
        idx = np.stack(np.meshgrid(*[np.arange(len(v)) for v in axes_values], indexing="ij"), -1).reshape(-1, len(AXES))
        frames.append(pd.DataFrame({a: np.asarray(vals, dtype=object if a == "direction" else float)[idx[:, i]]
                                    for i, (a, vals) in enumerate(zip(AXES, axes_values))}))
    if points:
        frames.append(pd.DataFrame([{a: p.get(a, defaults[a]) for a in AXES} for p in points]))
    df = pd.concat(frames, ignore_index=True)
    for a in NUMERIC_AXES:
        df[a] = df[a].astype(float)
    df["direction"] = df["direction"].astype(str)
    df.insert(0, "point_id", point_ids(base, df))
    df = df.drop_duplicates("point_id", keep="first").reset_index(drop=True)
    df.insert(0, "point_index", np.arange(len(df)))
    return df


def base_key(base: Scenario) -> str:
    """Hash of what a point inherits from its base: every parameter of the set."""
    payload = json.dumps(base.params.as_dict(), sort_keys=True)
    if base.model.has_effects:            # a model with effects is another base: other point ids
        payload += json.dumps({k: float(v) for k, v in base.model.values.items()}, sort_keys=True)
    return hashlib.sha1(payload.encode()).hexdigest()


def point_ids(base: Scenario, df: pd.DataFrame) -> list[str]:
    """A stable id per point: hash of the base's parameters and the point's AXES values."""
    key = base_key(base)
    cols = [df[a].tolist() for a in AXES]
    out = []
    for row in zip(*cols):
        text = key + "|" + "|".join(v if isinstance(v, str) else repr(float(v)) for v in row)
        out.append(hashlib.sha1(text.encode()).hexdigest()[:16])
    return out


def spec_from_mapping(data: dict, where: str, base_dir: Path) -> SweepSpec:
    _check_keys(data, _TOP_KEYS, where)
    base, preset_dirs = _base_scenario(data, where, base_dir)
    mode, band, desc = _settings(data, where)
    grid = data.get("grid")
    if grid is not None:
        if not isinstance(grid, dict):
            raise UserError(f"{where}: 'grid' must be a [grid] table of axis = values")
        _check_keys(grid, AXES, f"{where} [grid]")
        grid = {a: _axis_values(a, v, f"{where} [grid] key '{a}'") for a, v in grid.items()}
    pts = data.get("points")
    if pts is not None:
        if not isinstance(pts, list) or not all(isinstance(p, dict) for p in pts):
            raise UserError(f"{where}: 'points' must be an array of tables: [[points]] blocks of axis = value")
        for i, p in enumerate(pts):
            _check_keys(p, AXES, f"{where} [[points]] #{i + 1}")
            for a, v in p.items():
                _check_value(a, v, f"{where} [[points]] #{i + 1} key '{a}'")
    if grid is None and pts is None:
        raise UserError(f"{where}: nothing to sweep; add a [grid] table or [[points]] blocks")
    df = expand(base, grid, pts, preset_dirs)
    return SweepSpec(source=where, base=base, points=df, simulate=mode, band=band, description=desc)


def load_sweep(path: str | Path) -> SweepSpec:
    """Read and validate a SWEEP.toml file."""
    path = Path(path)
    data = read_toml(path, "sweep file", "see scenarios/sweeps/ for examples")
    return spec_from_mapping(data, str(path), path.parent)


def grid_spec(base: Scenario, grid: dict[str, list], *, simulate: str = "band",
              band: tuple[float, float] = DEFAULT_BAND, source: str = "sweep") -> SweepSpec:
    """Build a spec in code (benchmarks, tests), validated like a file's [grid]."""
    _check_keys(grid, AXES, f"{source} grid")
    values = {a: _axis_values(a, v, f"{source} grid axis '{a}'") for a, v in grid.items()}
    return SweepSpec(source=source, base=base, points=expand(base, values), band=band,
                     simulate=check_choice(simulate, SIMULATE_MODES, "simulate mode"))
