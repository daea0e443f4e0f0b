"""Importing a user's effect file in a child process first, so that it cannot end or hang the tool.

:func:`rollaway.effects.load_effect_file` catches what a plugin raises at import (``sys.exit``
included), but ``os._exit()``, a crash of native code or an endless loop would take the tool down
with it, or hang it, before any error could be printed.  :func:`preflight_import` runs the same
import in a fresh interpreter (same Python, same ``rollaway``) with a time limit and turns an
abnormal end into a one-line :class:`~rollaway.errors.UserError`; errors the import *raises* are
left to the real import, which names the line.  The file is therefore executed twice: a plugin
must only define classes (what it does at import is done twice).  Installed plugins (entry
points) are trusted code and are not checked this way; ``ROLLAWAY_TRUST_PLUGINS=1`` skips the
check for files too (about 0.2 s a file).
"""
from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

from rollaway.errors import UserError

TIMEOUT_S = 60.0          # [assumed] generous for a file that only defines classes
_DONE = "rollaway-preflight-done"
_CHILD = f"""
import importlib.util, sys
try:
    spec = importlib.util.spec_from_file_location("rollaway_preflight_plugin", sys.argv[1])
    spec.loader.exec_module(importlib.util.module_from_spec(spec))
except BaseException:
    pass                      # raised errors are reported by the real import, with their line
sys.stdout.write("\\n{_DONE}\\n")
sys.stdout.flush()
"""


def preflight_import(path: Path, timeout_s: float | None = None) -> None:
    """Import *path* in a child interpreter; UserError if that process ends abnormally or runs out of time."""
    if os.environ.get("ROLLAWAY_TRUST_PLUGINS", "").strip() in ("1", "true", "yes"):
        return
    limit = TIMEOUT_S if timeout_s is None else timeout_s
    package_root = str(Path(__file__).resolve().parents[2])         # the folder holding 'rollaway'
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(p for p in (package_root, os.environ.get("PYTHONPATH"))
                                                       if p)}
    try:
        proc = subprocess.run([sys.executable, "-c", _CHILD, str(path)], stdin=subprocess.DEVNULL,
                              capture_output=True, text=True, errors="replace", env=env, timeout=limit)
    except subprocess.TimeoutExpired:
        raise UserError(f"{path}: importing the effect file did not finish within {limit:g} s; a plugin must only "
                        f"define Effect classes (no long work, no waiting at import)") from None
    if proc.stdout.rstrip().endswith(_DONE):
        return
    if proc.returncode < 0:
        try:
            how = f"was killed by signal {signal.Signals(-proc.returncode).name}"
        except ValueError:
            how = f"was killed by signal {-proc.returncode}"
    else:
        how = f"ended the Python process with exit code {proc.returncode} (os._exit() or a crash)"
    raise UserError(f"{path}: importing the effect file {how}; a plugin must only define Effect classes")
