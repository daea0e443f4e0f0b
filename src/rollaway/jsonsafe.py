"""Turning results into strict JSON: numpy scalars to Python, NaN and ±inf to null."""
from __future__ import annotations

import math

import numpy as np


def to_jsonable(o):
    """Recursively convert dicts/lists of numpy and float values into strict-JSON values."""
    if isinstance(o, dict):
        return {k: to_jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [to_jsonable(v) for v in o]
    if isinstance(o, np.ndarray):
        return to_jsonable(o.tolist())
    if isinstance(o, np.bool_):
        return bool(o)
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, (float, np.floating)):
        return float(o) if math.isfinite(o) else None
    return o
