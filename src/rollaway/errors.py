"""User-facing errors.

Every mistake a user can make (a bad number, an unknown name, a malformed file)
raises :class:`UserError`.  The CLI turns it into a one-line message on stderr and
exit code 2, never a traceback.  Messages say *what* is wrong, *where* (file, line,
key) and *how to fix it*.
"""
from __future__ import annotations

import difflib
from collections.abc import Iterable


class UserError(ValueError):
    """A mistake in the user's input; the message names the value and the fix."""

    exit_code = 2


def suggest(name: str, choices: Iterable[str]) -> str:
    """Return ``" (did you mean 'x'?)"`` for the closest of *choices*, or ``""``."""
    close = difflib.get_close_matches(str(name), list(choices), n=1, cutoff=0.5)
    return f" (did you mean '{close[0]}'?)" if close else ""


def check_choice(value: str, choices: Iterable[str], what: str) -> str:
    """Validate *value* against *choices*; raise :class:`UserError` with a hint."""
    choices = list(choices)
    if value in choices:
        return value
    raise UserError(
        f"unknown {what} '{value}'{suggest(value, choices)}; choose one of: {', '.join(choices)}"
    )


def read_toml(path, what: str, example: str, referenced_by: str = "") -> dict:
    """Read a TOML file as a user input: a missing file, a folder, bad syntax or bad encoding is a UserError.

    *what* names the kind of file ("scenario file"), *example* where to look for a good one.
    *referenced_by* ("sweep.toml, key 'base'") prefixes the message when another file named this one.
    A UTF-8 byte-order mark is accepted (editors on Windows write one), like the CSV loader does.
    """
    import tomllib
    from pathlib import Path

    path = Path(path)
    pre = f"{referenced_by}: " if referenced_by else ""
    if path.is_dir():
        raise UserError(f"{pre}{what} '{path}' is a folder, not a file; give the path of a .toml file ({example})")
    if not path.is_file():
        raise UserError(f"{pre}{what} '{path}' does not exist; check the path ({example})")
    try:
        text = path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise UserError(f"{pre}{path}: not a UTF-8 text file (byte {exc.start}); save it as UTF-8 TOML") from None
    except OSError as exc:
        raise UserError(f"{pre}{path}: cannot be read ({exc.strerror or exc}); check its permissions") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise UserError(f"{pre}{path}: not valid TOML ({exc}); fix the syntax at that line") from None
    except RecursionError:
        raise UserError(f"{pre}{path}: not valid TOML (nested too deeply); flatten the tables") from None
    return data


def ensure_parent_dir(path, flag: str):
    """Create the folder an output file goes into; UserError if a file stands in the way."""
    from pathlib import Path

    p = Path(path)
    try:
        p.parent.mkdir(parents=True, exist_ok=True)
    except (FileExistsError, NotADirectoryError):
        raise UserError(f"{flag} {path}: '{p.parent}' is a file, not a folder; choose another path") from None
    except PermissionError:
        raise UserError(f"{flag} {path}: no permission to create '{p.parent}'; choose a writable folder") from None
    return p
