"""Drum-model files: a parameter set plus effects, fitted values, covariance and provenance, as TOML.

A model file is a parameter file (``extends`` + values that differ, see
:mod:`rollaway.model.parameters`) with three optional tables::

    extends = "paper"                 # the named set it extends
    mu_drum = 0.381                   # values that differ from it

    [effects.lining_creep]            # one table per effect: its parameter values
    relaxed_fraction = 0.118
    relaxation_time_s = 845.0
    # plugin = "my_effect.py"         # an effect from a plugin file (path relative to this file)

    [effects.lining_creep_shape]      # an effect's shape-free form (rollaway.effects.shape_free):
    knots = [0.0, 300.0, 3600.0]      # its spline's knots in the effect's covariate, then one value
    c0 = -0.05                        # per knot segment
    c1 = -0.04
    # scale = 1e-05                   # an absolute change's unit (cable_relaxation_shape: u_6 + scale·g);
                                      # absent: a factor, q·(1 + g)

    [covariance]                      # of the fitted parameters (names + matrix, SI units)
    names = ["mu_drum", "lining_creep.relaxed_fraction", ...]
    matrix = [[...], ...]

    [provenance]                      # where the values came from (free-form scalars)
    data_file = "bench.csv"

    [calibration]                     # per brake parameter: fitted, fixed (and why) or not tested
    mu_drum = "fitted: 0.381 ± 0.004"
    shoe_arm_ratio = "not tested: 0.857 — only downhill tests"

Every name is validated (unknown effect, parameter or table: an error naming the file and
key, with the closest match); ``--params FILE.toml`` accepts a model file in every command.
``shoe_arm_ratio`` (l_fr/l_f) in ``[covariance]`` and ``[calibration]`` is the set's
``shoe_arm_friction_m / shoe_arm_normal_m``.

This module is the file format only: :func:`read_model` returns the parts of a model (the keyword
arguments of :class:`~rollaway.model.drum_model.DrumModel`), which builds the model from them
(``DrumModel("fitted.toml")`` or :func:`rollaway.model.load_model`); :func:`save_model` writes one.
"""
from __future__ import annotations

import hashlib
import math
from datetime import date
from pathlib import Path

import numpy as np

from rollaway.errors import UserError, read_toml, suggest
from rollaway.model.covariance import BASELINE_FREE, Covariance
from rollaway.model.parameters import PARAMETER_SETS, SPEC_BY_NAME, BrakeParameters, load_parameters, parameters_from_mapping

TABLES = ("effects", "covariance", "provenance", "calibration", "predictive")


def read_model(source: str | Path | None = None) -> dict:
    """The parts of a named set (``"paper"``), a parameter file or a model file, as keyword arguments of
    :class:`~rollaway.model.drum_model.DrumModel`: ``params``, ``effects``, ``values``, ``covariance``, ``provenance``,
    ``name``, ``base``, ``effect_files``, ``calibration``."""
    if source is None or str(source) in PARAMETER_SETS:
        return dict(params=load_parameters(source), effects=(), values={}, covariance=None, provenance={},
                    name=None, base=None, effect_files={}, calibration={}, predictive={})
    path = Path(str(source))
    if path.suffix != ".toml" and not path.exists():
        load_parameters(source)          # raises the "unknown parameter set" error with its hint
    data = read_toml(path, "parameter or model file", "see 'rollaway params' for the keys")
    return model_parts(data, where=str(path), base_dir=path.parent)


def model_parts(data: dict, where: str = "model", base_dir: Path | None = None) -> dict:
    """Validate a parsed model file (see the module docstring) into the keyword arguments of a DrumModel."""
    data = dict(data)
    tables = {k: data.pop(k) for k in TABLES if k in data}
    for key, value in data.items():
        if isinstance(value, dict):
            raise UserError(f"{where}: key '{key}' is a table{suggest(key, TABLES)}; parameters are top-level "
                            f"'name = value' lines, and a model file's only tables are [effects.NAME], [covariance], "
                            f"[provenance], [calibration] and [predictive]")
    params = parameters_from_mapping(data, where=where)
    base = data.get("extends") if isinstance(data.get("extends"), str) else None
    effects, values, files = _effects(tables.get("effects", {}), where, base_dir)
    name = Path(where).stem if where.endswith(".toml") else None
    fitted = [*BASELINE_FREE, *(f"{e.name}.{p.name}" for e in effects for p in e.parameters)]
    covariance = _covariance(tables["covariance"], fitted, where) if "covariance" in tables else None
    provenance = _provenance(tables["provenance"], where) if "provenance" in tables else {}
    calibration = _calibration(tables["calibration"], where) if "calibration" in tables else {}
    from rollaway.model.predictive_record import validate
    predictive = validate(tables["predictive"], where, base_dir) if "predictive" in tables else {}
    for i, alt in enumerate(predictive.get("alternatives", [])):
        _alternative(Path(alt["file"]), f"{where}, key 'predictive.alternatives[{i}].file'")
    return dict(params=params, effects=tuple(effects), values=values, covariance=covariance, provenance=provenance,
                name=name, base=base, effect_files=files, calibration=calibration, predictive=predictive)


def _alternative(path: Path, named_by: str) -> None:
    """An alternative model file read and validated now, its errors prefixed by the key that names it; it is one
    effect set (no alternatives of its own, so that no file is read twice)."""
    data = read_toml(path, "alternative model file", "diagnose --save-model writes them", referenced_by=named_by)
    pred = data.get("predictive")
    if isinstance(pred, dict) and pred.get("alternatives"):
        raise UserError(f"{named_by}: {path} has alternatives of its own; an alternative is one effect set — "
                        f"delete its 'predictive.alternatives'")
    try:
        model_parts(data, where=str(path), base_dir=path.parent)
    except UserError as exc:
        raise UserError(f"{named_by}: {exc}") from None


def _calibration(table, where: str) -> dict:
    from rollaway.model.drum_parameters import BASELINE_FREE
    table = _table(table, where, "calibration")
    for key, value in table.items():
        if key not in BASELINE_FREE:
            raise UserError(f"{where}: unknown key 'calibration.{key}'{suggest(key, BASELINE_FREE)}; [calibration] "
                            f"has one line per brake parameter: {', '.join(BASELINE_FREE)}")
        if not isinstance(value, str):
            raise UserError(f"{where}: key 'calibration.{key}' must be text, e.g. \"fitted: 0.38 ± 0.01\"")
    return dict(table)


def _table(value, where: str, key: str) -> dict:
    if not isinstance(value, dict):
        raise UserError(f"{where}: '{key}' must be a table ([{key}] with 'name = value' lines), got {value!r}")
    return value


def _effects(table, where: str, base_dir: Path | None):
    from rollaway.effects import available_effects, load_effect_file
    from rollaway.effects.shape_free import SUFFIX as SHAPE_SUFFIX, from_model_file

    table = _table(table, where, "effects")
    effects, values, files = [], {}, {}
    for name, entries in table.items():
        entries = dict(_table(entries, where, f"effects.{name}"))
        plugin = entries.pop("plugin", None)
        if plugin is not None:
            if not isinstance(plugin, str):
                raise UserError(f"{where}: key 'effects.{name}.plugin' must be a quoted file path, got {plugin!r}")
            path = Path(plugin) if base_dir is None or Path(plugin).is_absolute() else base_dir / plugin
            try:
                load_effect_file(path)
            except UserError as exc:
                raise UserError(f"{where}: key 'effects.{name}.plugin': {exc}") from None
            files[name] = plugin
        known = available_effects()
        if name not in known and name.endswith(SHAPE_SUFFIX):     # a shape-free form: its knots give the class
            known = {name: from_model_file(name, entries.pop("knots", None), where, entries.pop("scale", 0.0))}
        if name not in known:
            raise UserError(f"{where}: unknown effect [effects.{name}]{suggest(name, known)}; run 'rollaway diagnose "
                            f"--list-effects' for the catalogue, or add plugin = \"file.py\" to the table")
        cls = known[name]
        for key, value in entries.items():
            spec = cls.parameter(key) if key in {p.name for p in cls.parameters} else None
            if spec is None:
                raise UserError(f"{where}: unknown key 'effects.{name}.{key}'"
                                f"{suggest(key, [p.name for p in cls.parameters])}; the parameters of '{name}' are: "
                                + ", ".join(p.name for p in cls.parameters))
            v = _number(value, where, f"effects.{name}.{key}", spec.unit)
            if not spec.lower <= v <= spec.upper:
                raise UserError(f"{where}: key 'effects.{name}.{key}' = {value!r} is outside [{spec.lower:g}, "
                                f"{spec.upper:g}] {spec.unit}; give a value within the effect's bounds")
            values[f"{name}.{key}"] = v
        effects.append(cls)
    return effects, values, files


def _number(value, where: str, key: str, unit: str = "") -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)):
        shown = f" in {unit}" if unit and unit not in ("-", "–") else ""
        raise UserError(f"{where}: key '{key}' must be a finite number{shown}, got {value!r}")
    return float(value)


def _covariance(table, fitted: list[str], where: str) -> Covariance:
    table = _table(table, where, "covariance")
    for key in table:
        if key not in ("names", "matrix"):
            raise UserError(f"{where}: unknown key 'covariance.{key}'{suggest(key, ['names', 'matrix'])}; "
                            f"[covariance] has 'names' and 'matrix'")
    names, matrix = table.get("names"), table.get("matrix")
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names) or not names:
        raise UserError(f"{where}: key 'covariance.names' must be a list of parameter names, e.g. "
                        f"[\"mu_drum\", \"lining_creep.relaxed_fraction\"]")
    for n in names:
        if n not in fitted:
            raise UserError(f"{where}: key 'covariance.names' names '{n}'{suggest(n, fitted)}, which is not a value "
                            f"of this model; use mu_drum, heat_transfer_W_m2K or EFFECT.PARAMETER of its effects")
    if len(set(names)) != len(names):
        raise UserError(f"{where}: key 'covariance.names' lists a name twice; name each parameter once")
    ok = isinstance(matrix, list) and len(matrix) == len(names) and all(
        isinstance(r, list) and len(r) == len(names) for r in matrix)
    if not ok:
        raise UserError(f"{where}: key 'covariance.matrix' must be a {len(names)}×{len(names)} list of rows, one per "
                        f"name")
    m = np.array([[_number(x, where, f"covariance.matrix[{i}][{j}]") for j, x in enumerate(r)]
                  for i, r in enumerate(matrix)])
    if not np.allclose(m, m.T, rtol=1e-6, atol=0.0):
        raise UserError(f"{where}: key 'covariance.matrix' is not symmetric; a covariance matrix equals its "
                        f"transpose")
    _check_semidefinite(m, names, where)
    return Covariance(tuple(names), m)


def _check_semidefinite(m: np.ndarray, names: list[str], where: str) -> None:
    """UserError naming the entry unless *m* is a covariance: variances ≥ 0, a zero variance (a parameter held
    fixed: its draws keep the fitted value) with zero covariances, correlations that form a positive
    semi-definite matrix."""
    var = np.diag(m)
    for i, v in enumerate(var):
        if v < 0:
            raise UserError(f"{where}: key 'covariance.matrix[{i}][{i}]' = {v:g} is a negative variance (of "
                            f"'{names[i]}'); a variance is ≥ 0 (0: the parameter is held fixed)")
    for i, j in zip(*np.nonzero(m)):
        if var[i] == 0 and i != j:
            raise UserError(f"{where}: key 'covariance.matrix[{i}][{j}]' = {m[i, j]:g} but the variance of "
                            f"'{names[i]}' is 0 (held fixed); a fixed parameter has no covariance — set its row and "
                            f"column to 0")
    pos = np.flatnonzero(var > 0)
    sd = np.sqrt(var[pos])
    corr = m[np.ix_(pos, pos)] / sd[:, None] / sd[None, :]
    if not np.all(np.isfinite(corr)):
        raise UserError(f"{where}: key 'covariance.matrix' has values too large or too small to use; give it in the "
                        f"parameters' units (as 'rollaway fit --save-model' writes it)")
    bad = np.argwhere(np.abs(corr) > 1 + 1e-8)
    if bad.size:
        i, j = (int(pos[k]) for k in bad[0])
        raise UserError(f"{where}: key 'covariance.matrix[{i}][{j}]': not positive semi-definite — the correlation "
                        f"of '{names[i]}' and '{names[j]}' is {corr[bad[0][0], bad[0][1]]:.3g}, beyond ±1; check "
                        f"the values")
    try:
        low = float(np.min(np.linalg.eigvalsh(corr))) if pos.size else 0.0
    except np.linalg.LinAlgError:
        low = -np.inf
    if low < -1e-8:
        raise UserError(f"{where}: key 'covariance.matrix' is not positive semi-definite (its correlations are "
                        f"inconsistent: smallest eigenvalue {low:.3g}); check the values, or save the model again")


def _provenance(table, where: str) -> dict:
    table = _table(table, where, "provenance")
    for key, value in table.items():
        if isinstance(value, (dict, list)):
            raise UserError(f"{where}: key 'provenance.{key}' must be a single value (text, number or date)")
    return dict(table)


# -- writing -----------------------------------------------------------------------------------
def file_sha256(path: str | Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def provenance_for(data_path: str | Path, *, rows: int, tests: int, rmse: dict, command: str) -> dict:
    """The provenance table of a model fitted on a data file."""
    from rollaway import __version__
    return {"data_file": Path(data_path).name, "data_sha256": file_sha256(data_path), "rows": int(rows),
            "tests": int(tests), **{k: float(v) for k, v in rmse.items()}, "command": command,
            "date": date.today().isoformat(), "rollaway_version": __version__}


def _value(v) -> str:
    """One TOML value on one line (lists inline); strings escaped by tomli-w."""
    import tomli_w
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return tomli_w.dumps({"x": v}).split("=", 1)[1].strip()


def _plugin_path(model, effect, base_dir: Path | None) -> str | None:
    """The plugin file *effect* came from, as a model file in *base_dir* names it (relative where it can be)."""
    import os
    where = model.effect_files.get(effect.name)
    if where is not None:
        return where
    source = getattr(type(effect), "__rollaway_source__", None)
    if source is None:
        return None
    source = Path(source).resolve()
    if base_dir is None:
        return str(source)
    try:
        return Path(os.path.relpath(source, Path(base_dir).resolve())).as_posix()
    except ValueError:        # another drive (Windows)
        return str(source)


def model_to_toml(model, comment: str = "", base_dir: Path | None = None) -> str:
    """A :class:`~rollaway.model.drum_model.DrumModel` as a model file a person can read and edit (round-trips through
    :func:`read_model`).  An effect from a plugin file is written with ``plugin =`` that file (relative to
    *base_dir*, the model file's folder, where given)."""
    base_name = model.base if model.base in PARAMETER_SETS else "paper"
    base = BrakeParameters(**PARAMETER_SETS[base_name], name=base_name)
    se = model.covariance.stderr if model.covariance is not None else {}
    lines = ["# rollaway drum model: parameter set + effects + fitted values (+ covariance, provenance).",
             "# Load it anywhere with --params THIS_FILE.toml; edit values freely (they are validated on load).",
             *(f"# {c}" for c in comment.splitlines() if c.strip()), "",
             f"extends = {_value(base_name)}"]
    for key, v in model.params.as_dict().items():
        if v != getattr(base, key):
            unc = f" ± {se[key]:.3g}" if key in se else ""
            lines.append(f"{key} = {_value(v):<24} # [{SPEC_BY_NAME[key].unit}]{unc}")
    for e in model.effects:
        lines += ["", f"[effects.{e.name}]", f"# {e.summary}"]
        plugin = _plugin_path(model, e, base_dir)
        if plugin is not None:
            lines.append(f"plugin = {_value(plugin)}")
        if getattr(e, "knots", None) is not None:          # a shape-free form (rollaway.effects.shape_free)
            lines.append(f"knots = {_value([float(k) for k in e.knots])}  # [{e.covariate}]")
            if e.scale:                                     # an absolute change: its unit (absent: a factor)
                lines.append(f"scale = {_value(float(e.scale))}  # the spline's unit of an absolute change")
        for p in e.parameters:
            key = f"{e.name}.{p.name}"
            unc = f" ± {se[key]:.3g}" if key in se else ""
            lines.append(f"{p.name} = {_value(float(model.values[key])):<24} # [{p.unit}]{unc}")
    if model.covariance is not None:
        c = model.covariance
        lines += ["", "[covariance]", "# of the fitted parameters, in their units; row/column order = names",
                  f"names = {_value(list(c.names))}", "matrix = ["]
        lines += [f"  {_value([float(x) for x in row])}," for row in c.matrix]
        lines.append("]")
    if model.provenance:
        lines += ["", "[provenance]"]
        lines += [f"{k} = {_value(v)}" for k, v in model.provenance.items()]
    if getattr(model, "predictive", None):
        lines += ["", "[predictive]", "# model error, tested range and competing effect sets (rollaway.uncertainty.predictive)"]
        for k, v in model.predictive.items():
            if k == "alternatives":
                lines.append("alternatives = [" + ", ".join("{ weight = %s, file = %s }" % (
                    _value(round(a["weight"], 4)), _value(Path(a["file"]).name)) for a in v) + "]")
            else:
                lines.append(f"{k} = {_value(v)}")
    if getattr(model, "calibration", None):
        lines += ["", "[calibration]", "# what the bench data determined, per brake parameter (rollaway.model.drum_parameters)"]
        lines += [f"{k} = {_value(v)}" for k, v in model.calibration.items()]
    return "\n".join(lines) + "\n"


def save_model(model, path: str | Path, comment: str = "") -> Path:
    """Write :func:`model_to_toml` to *path* (its folder is created); competing effect sets
    (``model.alternatives``) go beside it as ``NAME.altK.toml``."""
    from rollaway.errors import ensure_parent_dir
    p = ensure_parent_dir(path, "--save-model")
    if getattr(model, "_alternatives", None):
        alts = []
        for k, (w, alt) in enumerate(model._alternatives, 1):
            f = p.with_name(f"{p.stem}.alt{k}.toml")
            f.write_text(model_to_toml(alt, f"Competing effect set {k} of {p.name} (weight {w:.3g}).", p.parent),
                         encoding="utf-8")
            alts.append({"weight": float(w), "file": f.name})
        model.predictive = {**model.predictive, "alternatives": alts}
    p.write_text(model_to_toml(model, comment, p.parent), encoding="utf-8")
    return p


__all__ = ["BASELINE_FREE", "model_parts", "model_to_toml", "provenance_for", "read_model", "save_model"]
