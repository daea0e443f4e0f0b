"""Command-line entry point: ``rollaway COMMAND ...``.

Every command lives in its own module ``rollaway.cli.<name>`` with a ``register(app)``
function, imported only when the command is used (:class:`rollaway.cli.app.LazyGroup`).  User mistakes (:class:`rollaway.errors.UserError`, click usage errors) print
one line on stderr and exit with code 2; no traceback.
"""
from __future__ import annotations

import sys

import typer

from rollaway.cli.app import COMMANDS, app  # noqa: F401  (COMMANDS: the command list, re-exported)
from rollaway.errors import UserError

try:  # typer >= 0.22 carries its own copy of click
    from typer._click.exceptions import NoArgsIsHelpError, UsageError
except ImportError:  # pragma: no cover - older typer on real click
    from click.exceptions import NoArgsIsHelpError, UsageError



def _command_path(args: list[str]) -> str:
    sub = next((a for a in args if not a.startswith("-")), "")
    return f"rollaway {sub}".strip()


def main(argv: list[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    command = typer.main.get_command(app)
    try:
        rv = command.main(args=args, prog_name="rollaway", standalone_mode=False)
    except NoArgsIsHelpError as exc:  # bare 'rollaway': show help, usage error
        print(exc.ctx.get_help() if exc.ctx else str(exc))
        return 2
    except UsageError as exc:
        path = exc.ctx.command_path if exc.ctx else _command_path(args)
        print(f"{path}: error: {exc.format_message()} (see '{path} --help')", file=sys.stderr)
        return 2
    except UserError as exc:
        print(f"{_command_path(args)}: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:  # a path the user gave cannot be read or written
        where = f": {exc.filename}" if getattr(exc, "filename", None) else ""
        print(f"{_command_path(args)}: error: {exc.strerror or exc}{where}; check the path and its permissions",
              file=sys.stderr)
        return 2
    except (typer.Abort, KeyboardInterrupt):
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    if isinstance(rv, int):
        return rv
    return 0


def run() -> None:  # pragma: no cover - console script shim
    _leave(main())


def _leave(code: int) -> None:
    """End the process with *code* once the command is done, skipping the interpreter's teardown where that is safe.

    Freeing every module and array one by one takes 0.2–0.3 s after a diagnosis (SciPy, the fits kept for the
    report), longer than many commands themselves.  With the main thread alone (no scheduler or writer thread
    still running), the streams are flushed and the ``atexit`` handlers run (process pools, temporary folders,
    logging), then :func:`os._exit` ends the process; otherwise the ordinary :func:`sys.exit`.
    """
    import atexit
    import os
    import threading
    if threading.active_count() > 1:
        sys.exit(code)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):          # a closed pipe (``| head``) or stream: nothing more to write
            pass
    atexit._run_exitfuncs()
    os._exit(code)
