"""Column map and units of a lab's bench log: which column holds what, in which unit.

The canonical names are the bench CSV's (``test_id, direction, hand_force_N, time_s,
drum_temp_C, torque_Nm`` and optional ``ambient_C``).  A lab names its columns its own way and
logs in its own units; a map says where each canonical quantity is::

    [columns]                                   # in a TOML file given to --columns
    torque_Nm = "Torque [Nm]"                   # the column; the unit in brackets is read
    drum_temp_C = { column = "T_drum", unit = "degF" }
    time_s = "Time [ms]"

or on the command line ``--columns 'drum_temp_C=T_drum[degF]'`` (repeatable).  A header such
as ``T_drum [°F]`` matches the column ``T_drum`` with its unit.  A map's unit that disagrees with the
header's is an error (one of them is wrong) unless the map says it overrides the header: a trailing
``!`` (``--columns 'drum_temp_C=T_drum[degF]!'``, ``drum_temp_C = "T_drum [degF]!"``) or
``override_units = true`` in the table form; the reader then notes what it did.  Units are parsed with pint
(N·m, lbf·ft, kN·m; °C, °F, K; s, ms, min, h; N, lbf, kgf; and anything else pint knows with
the right dimension) and turned into one affine conversion ``SI = a·x + b`` per column, applied
to whole arrays.
"""
from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from pathlib import Path

from rollaway.errors import UserError, suggest

# canonical name → (pint unit it is stored in, dimension words, examples of accepted units)
QUANTITIES = {
    "hand_force_N": ("N", "force", "N, lbf, kgf"),
    "time_s": ("s", "time", "s, ms, min"),
    "drum_temp_C": ("degC", "temperature", "°C, °F, K"),
    "torque_Nm": ("N*m", "torque", "N·m, lbf·ft, kN·m"),
    "ambient_C": ("degC", "temperature", "°C, °F, K"),
}
TEXT = ("test_id", "direction")
CANONICAL = ("test_id", "direction", "hand_force_N", "time_s", "drum_temp_C", "torque_Nm", "ambient_C")
# the same unit written the ways labs write it → pint's spelling
ALIASES = {"nm": "N*m", "n.m": "N*m", "n-m": "N*m", "knm": "kN*m", "kn.m": "kN*m", "kn-m": "kN*m",
           "lbfft": "lbf*ft", "lbf.ft": "lbf*ft", "lbf-ft": "lbf*ft", "ftlbf": "ft*lbf", "ft-lbf": "ft*lbf",
           "ft.lbf": "ft*lbf", "ftlb": "ft*lbf", "ft-lb": "ft*lbf", "lb-ft": "lbf*ft", "lbft": "lbf*ft",
           "c": "degC", "°c": "degC", "degc": "degC", "celsius": "degC", "f": "degF", "°f": "degF",
           "degf": "degF", "fahrenheit": "degF", "k": "K", "kelvin": "K", "sec": "s", "msec": "ms",
           "kp": "kgf", "lb": "lbf"}
BRACKET = re.compile(r"^(?P<name>.*?)\s*[\[(](?P<unit>[^\[\]()]*)[\])]\s*$")


def split_header(header: str) -> tuple[str, str | None]:
    """``'T_drum [°F]'`` → ``('T_drum', '°F')``; a header without a bracketed unit → ``(header, None)``."""
    m = BRACKET.match(header.strip())
    if m and m.group("name"):
        return m.group("name").strip(), m.group("unit").strip()
    return header.strip(), None


@functools.lru_cache(maxsize=1)
def _registry():
    import pint
    return pint.UnitRegistry()


def _pint_spelling(unit: str) -> str:
    u = unit.strip().replace("·", "*").replace("⋅", "*")
    key = u.lower().replace(" ", "").replace("*", "")
    if key in ALIASES:
        return ALIASES[key]
    if u.lower() in ALIASES:
        return ALIASES[u.lower()]
    return u.replace("°C", "degC").replace("°F", "degF").replace(" ", "*")


@functools.lru_cache(maxsize=256)
def conversion(unit: str | None, quantity: str) -> tuple[float, float]:
    """(a, b) with value_in_canonical_unit = a·x + b for *x* in *unit*; ValueError with the reason."""
    target = QUANTITIES[quantity][0]
    if unit is None or _pint_spelling(unit) == target:
        return 1.0, 0.0
    import pint
    reg = _registry()
    spelled = _pint_spelling(unit)
    try:
        zero = reg.Quantity(0.0, spelled).to(target).magnitude
        one = reg.Quantity(1.0, spelled).to(target).magnitude
    except pint.errors.DimensionalityError:
        raise ValueError(f"'{unit}' is not a unit of {QUANTITIES[quantity][1]}") from None
    except (pint.errors.PintError, AttributeError, TypeError, ValueError, SyntaxError, AssertionError):
        raise ValueError(f"unknown unit '{unit}'") from None
    return float(one - zero), float(zero)


PRETTY = {"N*m": "N·m", "kN*m": "kN·m", "lbf*ft": "lbf·ft", "ft*lbf": "lbf·ft", "degC": "°C", "degF": "°F"}


def unit_label(unit: str | None, quantity: str) -> str:
    """A unit as people write it ('Nm' → 'N·m'); None: the quantity's canonical unit."""
    spelled = _pint_spelling(unit) if unit else QUANTITIES[quantity][0]
    return PRETTY.get(spelled, spelled if not unit else unit)


@dataclass(frozen=True)
class Spec:
    """Where one canonical quantity is: a column name and the unit it is logged in (None: canonical/header)."""

    column: str
    unit: str | None = None
    override: bool = False      # the unit deliberately overrides the header's ('...[degF]!', override_units = true)


@dataclass(frozen=True)
class Resolved:
    """A canonical quantity found in one file's header: the header cell, the unit, the conversion."""

    quantity: str
    header: str
    unit: str | None
    scale: float = 1.0
    offset: float = 0.0
    note: str = ""              # a stated choice taken (the map's unit over the header's), for stderr and JSON

    def describe(self) -> str:
        return f"'{self.header}'" + ("" if self.header == self.quantity else f" ({self.quantity})")


class ColumnMap:
    """Canonical name → :class:`Spec`; unmapped quantities are looked up under their canonical name."""

    def __init__(self, specs: dict[str, Spec] | None = None, origin: str = "--columns"):
        self.specs = dict(specs or {})
        self.origin = origin

    def __bool__(self) -> bool:
        return bool(self.specs)

    def resolve(self, header: list[str], quantity: str, where: str) -> Resolved | None:
        """The column of *quantity* in *header* (None if absent and not mapped); UserError for a mapped
        column that is absent or a unit that is unknown or of the wrong dimension."""
        spec = self.specs.get(quantity)
        name = spec.column if spec else quantity
        found = _find(header, name)
        if found is None:
            if spec is None:
                return None
            bare = split_header(name)[0]
            pool = [split_header(h)[0] for h in header]
            raise UserError(f"{where}, column '{bare}': mapped to {quantity} by {self.origin} but the header has no "
                            f"such column{suggest(bare, pool)}; the header is {', '.join(repr(h) for h in header[:8])}"
                            f"{', ...' if len(header) > 8 else ''} — fix the name in {self.origin}")
        cell, header_unit = found
        # the map's unit (explicit, or in brackets after the mapped name); the header's where the map has none
        spec_unit = (spec.unit or split_header(spec.column)[1]) if spec else None
        unit = spec_unit or header_unit
        if quantity in TEXT:
            return Resolved(quantity, cell, None)
        note = self._disagreement(where, quantity, cell, spec, spec_unit, header_unit)
        try:
            a, b = conversion(unit, quantity)
        except ValueError as exc:
            src = self.origin if spec_unit else "the header"
            good = QUANTITIES[quantity][2].split(", ")[0]
            example = (f"{quantity} = {{ column = \"{split_header(cell)[0]}\", unit = \"{good}\" }} in {self.origin}"
                       if spec_unit and self.origin.endswith(".toml") else
                       f"--columns '{quantity}={split_header(cell)[0]}[{good}]'")
            raise UserError(f"{where}, column '{cell}': {exc} for {quantity} (from {src}); give one of "
                            f"{QUANTITIES[quantity][2]}, e.g. {example}") from None
        return Resolved(quantity, cell, unit, a, b, note)

    def _disagreement(self, where, quantity, cell, spec, spec_unit, header_unit) -> str:
        """'' when the map's and the header's units agree (or one is absent); the note of a stated override;
        UserError for an unstated disagreement."""
        if not (spec_unit and header_unit):
            return ""
        try:
            same = conversion(spec_unit, quantity) == conversion(header_unit, quantity)
        except ValueError:
            return ""                         # an unknown unit: the caller's error names it
        if same:
            return ""
        said, head = unit_label(spec_unit, quantity), unit_label(header_unit, quantity)
        if spec.override:
            return (f"{quantity}: column '{cell}' read in {said} as {self.origin} says, not in {head} as its header "
                    f"says (override stated with '!')")
        bare = split_header(cell)[0]
        raise UserError(f"{where}, column '{cell}': the header says {head} but {self.origin} says {said} for "
                        f"{quantity}; drop the unit from the map to use the header's, or, if the header is wrong, "
                        f"say so with a trailing '!': --columns '{quantity}={bare}[{spec_unit}]!' (in a .toml map: "
                        f"override_units = true)")


def _find(header: list[str], name: str) -> tuple[str, str | None] | None:
    """(header cell, unit from the cell's brackets) of the column called *name*, exactly or by its bare name."""
    stripped = [h.strip() for h in header]
    if name.strip() in stripped:
        cell = header[stripped.index(name.strip())]
        return cell, split_header(cell)[1]     # 'Torque [Nm]' asked by its full name: the bracket is its unit
    bare_name, _ = split_header(name)
    matches = [h for h in header if split_header(h)[0] == bare_name]
    if len(matches) == 1:
        return matches[0], split_header(matches[0])[1]
    if not matches:
        low = [h for h in header if split_header(h)[0].lower() == bare_name.lower()]
        if len(low) == 1:
            return low[0], split_header(low[0])[1]
    return None


def parse_inline(text: str, origin: str = "--columns") -> dict[str, Spec]:
    """``'drum_temp_C=T_drum[degF]'`` or ``'torque_Nm=Torque [Nm]'`` → {quantity: Spec}."""
    if "=" not in text:
        raise UserError(f"{origin} {text!r}: expected NAME=COLUMN (e.g. 'drum_temp_C=T_drum[degF]') or a .toml "
                        f"file with a [columns] table")
    key, col = (s.strip() for s in text.split("=", 1))
    _check_key(key, origin)
    override = col.endswith("!")
    col = col[:-1].strip() if override else col
    if not col:
        raise UserError(f"{origin} {text!r}: no column after '='; e.g. '{key}=My column'")
    if override and not (split_header(col)[1]):
        raise UserError(f"{origin} {text!r}: a trailing '!' overrides the header's unit with the map's, but no unit "
                        f"is given; e.g. '{key}={col}[degF]!'")
    return {key: Spec(col, None, override)}


def parse_table(table, origin: str) -> dict[str, Spec]:
    """A ``[columns]`` table → {quantity: Spec}."""
    if not isinstance(table, dict):
        raise UserError(f"{origin}: [columns] must be a table of NAME = \"column\" or NAME = {{ column = ..., "
                        f"unit = ... }}")
    out = {}
    for key, val in table.items():
        _check_key(key, origin)
        if isinstance(val, str) and val.strip():
            out[key] = parse_inline(f"{key}={val.strip()}", f"{origin}, [columns] {key}:")[key]
        elif isinstance(val, dict) and isinstance(val.get("column"), str) and val["column"].strip():
            extra = set(val) - {"column", "unit", "override_units"}
            if extra:
                raise UserError(f"{origin}, [columns] {key}: unknown key(s) {', '.join(sorted(extra))}; use "
                                f"column, unit and override_units")
            unit = val.get("unit")
            if unit is not None and (not isinstance(unit, str) or not unit.strip()):
                raise UserError(f"{origin}, [columns] {key}: unit must be a text such as \"degF\"")
            override = val.get("override_units", False)
            if not isinstance(override, bool) or (override and not unit):
                raise UserError(f"{origin}, [columns] {key}: override_units must be true or false, and true needs a "
                                f"unit (the one that overrides the header's)")
            out[key] = Spec(val["column"].strip(), unit.strip() if unit else None, override)
        else:
            raise UserError(f"{origin}, [columns] {key}: give the column name as text, e.g. {key} = \"Torque [Nm]\", "
                            f"or {{ column = \"...\", unit = \"...\" }}")
        if key in QUANTITIES and out[key].unit:
            try:
                conversion(out[key].unit, key)
            except ValueError as exc:
                raise UserError(f"{origin}, [columns] {key}: {exc}; give one of {QUANTITIES[key][2]}") from None
    return out


def _check_key(key: str, origin: str) -> None:
    if key not in CANONICAL:
        raise UserError(f"{origin}: unknown quantity '{key}'{suggest(key, CANONICAL)}; map one of "
                        f"{', '.join(CANONICAL)}")


def column_map(values) -> ColumnMap:
    """The map from ``--columns`` values: TOML files with a ``[columns]`` table and/or NAME=COLUMN texts."""
    from rollaway.errors import read_toml
    specs: dict[str, Spec] = {}
    origins = []
    for v in values or ():
        if str(v).lower().endswith(".toml") or ("=" not in str(v) and Path(v).is_file()):
            data = read_toml(v, "column map", "a [columns] table, see docs/how-to/bench-logs.md")
            if "columns" not in data:
                raise UserError(f"{v}: no [columns] table; add one, e.g. [columns] torque_Nm = \"Torque [Nm]\"")
            specs.update(parse_table(data["columns"], str(v)))
            origins.append(str(v))
        else:
            specs.update(parse_inline(str(v)))
            origins.append("--columns")
    return ColumnMap(specs, " and ".join(dict.fromkeys(origins)) or "--columns")


def is_lab_format(path) -> bool:
    """True for inputs only the streaming reader takes (a folder, Parquet, MDF)."""
    p = Path(path)
    return p.is_dir() or p.suffix.lower() in (".parquet", ".pq", ".mf4", ".mdf")
