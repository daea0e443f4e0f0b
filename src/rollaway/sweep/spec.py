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
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa

from rollaway.errors import UserError, check_choice, read_toml, suggest
from rollaway.physics.drum import DIRECTIONS
from rollaway.hold.regulations import PRESETS
from rollaway.hold.scenario import Scenario, load_scenario, preset_scenarios

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
    layout: tuple | None = field(default=None, repr=False, compare=False)   # expand()'s arguments after the base

    @property
    def name(self) -> str:
        return Path(self.source).stem

    def with_model(self, model) -> "SweepSpec":
        """The same sweep on another drum model (its parameter set and effects; the base keeps its T_0): the axes
        the sweep does not set (μ_d, μ_r, …) take the model's values, as they took the base's."""
        import dataclasses
        p = model.params.replace(initial_drum_temp_C=self.base.initial_drum_temp_C)
        base = dataclasses.replace(self.base, params=p, model=model.with_params(p))
        if self.layout is not None:
            points = expand(base, *self.layout)
        else:
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
    if not math.isfinite(stop - start):
        raise UserError(f"{where}: range from {start:g} to {stop:g} spans more than a float can hold; "
                        f"give physical values (e.g. grade_pct from -50 to 50)")
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
    count_f = abs(stop - start) / step + 1e-9          # inf for a denormal step: still refused below
    if not count_f < MAX_POINTS:
        raise UserError(f"{where}: range with step {step:g} gives "
                        f"{'more than ' + str(MAX_POINTS) if not math.isfinite(count_f) else int(count_f) + 1} "
                        f"values (max {MAX_POINTS}); use a larger step")
    count = int(math.floor(count_f)) + 1
    sign = 1.0 if stop >= start else -1.0
    return [float(v) for v in start + sign * np.arange(count) * step]


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
            raise UserError(f"{where}: key 'base': scenario file '{path}' "
                            f"{'is a folder' if path.is_dir() else 'does not exist'}; "
                            f"give a path relative to the sweep file")
        try:
            return load_scenario(path), None
        except UserError as exc:
            raise UserError(f"{where}, key 'base': {exc}") from None
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


def _grid_frame(axes_values: list[list]) -> pd.DataFrame:
    """Every combination of *axes_values* (one list per AXES entry, the last varying fastest)."""
    total = math.prod(len(v) for v in axes_values)
    cols, stride = {}, total
    for a, vals in zip(AXES, axes_values):
        stride //= len(vals)
        k = (np.arange(total, dtype=np.int64) // stride) % len(vals)
        if a == "direction":      # an Arrow string column built from codes: no Python string per row
            arr = pa.DictionaryArray.from_arrays(pa.array(k.astype(np.int32)), pa.array([str(v) for v in vals]))
            cols[a] = pd.array(arr.cast(pa.string()), dtype="str")
        else:
            cols[a] = np.asarray(vals, dtype=float)[k]
    return pd.DataFrame(cols)


def expand(base: Scenario, grid: dict[str, list] | None = None, points: list[dict] | None = None,
           default_directions: list[str] | None = None, where: str = "sweep") -> pd.DataFrame:
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
        total = math.prod(len(v) for v in axes_values) + len(points or ())
        if total > MAX_POINTS:
            sizes = " × ".join(f"{a} {len(v)}" for a, v in zip(AXES, axes_values) if len(v) > 1)
            raise UserError(f"{where} [grid]: the grid has {total} points ({sizes}; max {MAX_POINTS}); "
                            f"use fewer values per axis or split the sweep")
        frames.append(_grid_frame(axes_values))
    if points:
        frames.append(pd.DataFrame([{a: p.get(a, defaults[a]) for a in AXES} for p in points]))
    df = pd.concat(frames, ignore_index=True) if len(frames) > 1 else frames[0]
    for a in NUMERIC_AXES:
        df[a] = df[a].astype(float)
    df["direction"] = df["direction"].astype(str)
    h = point_hashes(base, df)
    dup = pd.Series(h).duplicated(keep="first").to_numpy()
    if dup.any():
        df, h = df[~dup].reset_index(drop=True), h[~dup]
    df.insert(0, "point_id", hex_ids(h))
    df.insert(0, "point_index", np.arange(len(df)))
    return df


def base_key(base: Scenario) -> str:
    """Hash of what a point inherits from its base: every parameter of the set."""
    payload = json.dumps(base.params.as_dict(), sort_keys=True)
    if base.model.has_effects:            # a model with effects is another base: other point ids
        payload += json.dumps({k: float(v) for k, v in base.model.values.items()}, sort_keys=True)
    return hashlib.sha1(payload.encode()).hexdigest()


_M1, _M2 = np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB)


def _mix64(z: np.ndarray) -> np.ndarray:
    """The splitmix64 finaliser (a bijection of uint64 that spreads every input bit), vectorised."""
    with np.errstate(over="ignore"):
        z = (z ^ (z >> np.uint64(30))) * _M1
        z = (z ^ (z >> np.uint64(27))) * _M2
    return z ^ (z >> np.uint64(31))


def _sha64(text: str) -> int:
    return int(hashlib.sha1(text.encode()).hexdigest()[:16], 16)


def _column_bits(col: pd.Series) -> np.ndarray:
    """One uint64 per row that identifies the value: a float's bits (−0 → 0, one NaN), a string's hash."""
    if col.dtype.kind == "f":
        v = col.to_numpy(float) + 0.0
        v[np.isnan(v)] = np.nan
        return v.view(np.uint64)
    codes, uniques = pd.factorize(col, use_na_sentinel=False)
    return np.array([_sha64(str(u)) for u in uniques], dtype=np.uint64)[codes]


def point_hashes(base: Scenario, df: pd.DataFrame) -> np.ndarray:
    """A stable 64-bit hash per point of the base's parameters and the point's AXES values (vectorised)."""
    h = np.full(len(df), _sha64(base_key(base)), dtype=np.uint64)
    for a in AXES:
        h = _mix64(h ^ _column_bits(df[a]))
    return h


def hex_ids(h: np.ndarray):
    """16 hex digits per hash, as a pandas string array built without a Python string per row."""
    data = np.ascontiguousarray(h, dtype=">u8").tobytes().hex().encode("ascii")
    offsets = (np.arange(len(h) + 1, dtype=np.int32) * 16)
    arr = pa.StringArray.from_buffers(len(h), pa.py_buffer(offsets), pa.py_buffer(data))
    return pd.array(arr, dtype="str")


def point_ids(base: Scenario, df: pd.DataFrame):
    """A stable id per point (16 hex digits): :func:`point_hashes` as text; the same values give the
    same id in every run and process, so a rerun finds its points in the journal."""
    return hex_ids(point_hashes(base, df))


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
    if pts is not None and len(pts) > MAX_POINTS:
        raise UserError(f"{where}: {len(pts)} [[points]] blocks (max {MAX_POINTS}); split the sweep")
    df = expand(base, grid, pts, preset_dirs, where)
    return SweepSpec(source=where, base=base, points=df, simulate=mode, band=band, description=desc,
                     layout=(grid, pts, preset_dirs, where))


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
    return SweepSpec(source=source, base=base, points=expand(base, values, where=source), band=band,
                     layout=(values, None, None, source),
                     simulate=check_choice(simulate, SIMULATE_MODES, "simulate mode"))
