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


def read_toml(path, what: str, example: str) -> dict:
    """Read a TOML file as a user input: a missing file, bad syntax or bad encoding is a UserError.

    *what* names the kind of file ("scenario file"), *example* where to look for a good one.
    """
    import tomllib
    from pathlib import Path

    path = Path(path)
    if not path.is_file():
        raise UserError(f"{what} '{path}' does not exist; check the path ({example})")
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise UserError(f"{path}: not valid TOML ({exc}); fix the syntax at that line") from None
    except UnicodeDecodeError:
        raise UserError(f"{path}: not a UTF-8 text file; save it as UTF-8 TOML") from None


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
