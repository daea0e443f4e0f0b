"""One sweep per output folder, and only the sweep that made it: a lock and a spec fingerprint.

* **Lock** (``sweep.lock``): an exclusive ``flock`` held while a sweep writes into the folder.
  A second sweep into the same folder is refused with the holder's pid and host.  The kernel
  drops the lock when its process dies (even by ``kill -9``), so a lock left by a dead sweep is
  simply taken over; the pid written in the file is only for the message.
* **Fingerprint** (``fingerprint.json``): a hash of the sweep's points (their ids, which hash
  the base parameters and every axis value).  Rerunning the same spec resumes; a spec with
  other points in an existing folder is refused, with the way out (``--fresh`` or another
  ``--out``).  The simulate mode and band are not part of it: widening the simulated band in
  the same folder reuses every simulation already journalled.
"""
from __future__ import annotations

import fcntl
import hashlib
import json
import os
import socket
import time
from pathlib import Path

import numpy as np

from rollaway.errors import UserError

LOCK = "sweep.lock"
FINGERPRINT = "fingerprint.json"
OUTPUTS = ("journal.jsonl", "results.parquet", "results.csv", "manifest.json", FINGERPRINT)


class FolderLock:
    """Exclusive lock of a sweep output folder (a context manager); UserError if another sweep holds it."""

    def __init__(self, folder: str | Path, flag: str = "--out"):
        self.folder, self.flag = Path(folder), flag
        self._fd: int | None = None

    def acquire(self) -> "FolderLock":
        path = self.folder / LOCK
        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            holder = os.pread(fd, 200, 0).decode("utf-8", "replace").strip() or "another process"
            os.close(fd)
            raise UserError(f"{self.flag} {self.folder}: another sweep is writing into this folder ({holder}); "
                            f"wait for it to finish, or give another {self.flag}") from None
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"pid {os.getpid()} on {socket.gethostname()}, since "
                      f"{time.strftime('%Y-%m-%d %H:%M:%S')}\n".encode(), 0)
        self._fd = fd
        return self

    def release(self) -> None:
        if self._fd is not None:
            os.ftruncate(self._fd, 0)
            fcntl.flock(self._fd, fcntl.LOCK_UN)
            os.close(self._fd)
            self._fd = None

    def __enter__(self) -> "FolderLock":
        return self.acquire()

    def __exit__(self, *exc) -> None:
        self.release()


def fingerprint(point_hashes: np.ndarray) -> str:
    """Hash of a sweep's set of points (order-independent)."""
    return hashlib.sha1(np.sort(np.asarray(point_hashes, dtype=np.uint64)).tobytes()).hexdigest()


def check_fingerprint(folder: str | Path, fp: str, source: str, n_points: int, flag: str = "--out") -> None:
    """Record *fp* in a new folder; refuse a folder that holds another sweep's results (UserError)."""
    folder = Path(folder)
    path = folder / FINGERPRINT
    if path.exists():
        try:
            old = json.loads(path.read_text(encoding="utf-8"))
            same = old.get("fingerprint") == fp
        except (OSError, ValueError, AttributeError):
            old, same = {}, False
        if not same:
            was = old.get("sweep", "another sweep") if isinstance(old, dict) else "another sweep"
            raise UserError(f"{flag} {folder} holds the results of a different sweep ({was}, "
                            f"{old.get('n_points', '?') if isinstance(old, dict) else '?'} points); "
                            f"give another {flag}, or add --fresh to delete them and start over")
        return
    payload = {"fingerprint": fp, "sweep": str(source), "n_points": int(n_points),
               "created": time.strftime("%Y-%m-%d %H:%M:%S")}
    tmp = path.with_name(f".{FINGERPRINT}.{os.getpid()}.tmp")
    tmp.write_text(json.dumps(payload, indent=1) + "\n", encoding="utf-8")
    os.replace(tmp, path)


def clear_outputs(folder: str | Path) -> None:
    """Delete a previous sweep's files (``--fresh``); the lock must be held."""
    folder = Path(folder)
    for name in OUTPUTS:
        (folder / name).unlink(missing_ok=True)
    plots = folder / "plots"
    if plots.is_dir():
        for f in plots.glob("*.png"):
            f.unlink()
