"""What a run keeps: one record per brake update while anything moves, fewer while at rest."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

DECIMATE_UPDATES = 25     # at rest, keep one record in this many updates (0.5 s) [assumed]


@dataclass
class Trace:
    """What happened: records at brake updates (every 20 ms while moving, every 0.5 s at rest) plus one per skip."""

    time_s: np.ndarray                # (n,)
    qpos: np.ndarray                  # (n, nq)
    qvel: np.ndarray                  # (n, nv)
    capacity_Nm: np.ndarray           # (n, 2) per-wheel capacity in effect until the next record
    sense: np.ndarray                 # (n, 2) driven sense per rear wheel (+1 forward, eq. 18; −1 eq. 19)
    displacement_m: np.ndarray        # (n,) along the slope, + downhill, from the settled t = 0 position
    speed_m_s: np.ndarray             # (n,) along the slope, + downhill
    wheel_angle_rad: np.ndarray       # (n,) mean rear hinge angle, + forward rotation
    skips: list                       # [(from_s, to_s)] spans jumped over at rest (fast mode)


class Recorder:
    """Growable record buffers (sized to what is kept, not to the horizon)."""

    def __init__(self, nq: int, nv: int, capacity: int = 1024):
        self.n = 0
        self._buf = {"t": np.zeros(capacity), "qpos": np.zeros((capacity, nq)), "qvel": np.zeros((capacity, nv)),
                     "cap": np.zeros((capacity, 2)), "sense": np.zeros((capacity, 2), dtype=int)}

    def append(self, t, qpos, qvel, cap, sense) -> None:
        if self.n == len(self._buf["t"]):
            self._buf = {k: np.concatenate([v, np.zeros_like(v)]) for k, v in self._buf.items()}
        r = self.n
        b = self._buf
        b["t"][r], b["qpos"][r], b["qvel"][r], b["cap"][r], b["sense"][r] = t, qpos, qvel, cap, sense
        self.n += 1

    def view(self, key: str) -> np.ndarray:
        return self._buf[key][:self.n]
