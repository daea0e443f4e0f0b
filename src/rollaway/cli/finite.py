"""Every float option of every command refuses ``nan`` and ``inf``.

No option of rollaway means anything at a non-finite value (a window, a duration, a force, a
frame rate, a noise level); click's float type takes ``nan`` and ``inf`` as numbers, so each
command's float options are given :class:`Finite` when the command is built
(:func:`rollaway.cli.app.load_command`): a one-line error naming the option, exit 2.
"""
from __future__ import annotations

import math

try:  # typer >= 0.22 carries its own copy of click
    from typer._click.types import FloatParamType, ParamType
except ImportError:  # pragma: no cover - older typer on real click
    from click.types import FloatParamType, ParamType


class Finite(ParamType):
    """A float type (plain or ranged) that also refuses nan and ±inf."""

    def __init__(self, inner: ParamType):
        self.inner = inner
        self.name = inner.name

    def convert(self, value, param, ctx):
        try:
            v = float(value)
        except (TypeError, ValueError):
            v = None                      # not a number: the inner type says so
        if v is not None and not math.isfinite(v):
            from rollaway.errors import UserError
            flag = max(getattr(param, "opts", None) or [param.human_readable_name], key=len)
            raise UserError(f"{flag} {value}: not a finite number; give a number (see --help for its range)")
        return self.inner.convert(value, param, ctx)

    def get_metavar(self, *args, **kwargs):
        return self.inner.get_metavar(*args, **kwargs)

    def __repr__(self) -> str:
        return f"Finite({self.inner!r})"


def refuse_non_finite(command) -> None:
    """Give every float option and argument of *command* (and its subcommands) the :class:`Finite` type."""
    for p in getattr(command, "params", ()):
        if isinstance(p.type, FloatParamType):
            p.type = Finite(p.type)
    for sub in getattr(command, "commands", {}).values():
        refuse_non_finite(sub)
