"""Text columns of large sweep tables built from small integer codes.

A table of 2 000 000 points holds a few distinct labels per text column ("held", "roll", …).
Converting such a column through one Python string per row costs seconds and hundreds of MB;
these helpers go through Arrow dictionary arrays instead (codes + the few labels).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pandas as pd
import pyarrow as pa


def label_column(codes: np.ndarray, labels: Sequence[str]):
    """A pandas string array with ``labels[codes[i]]`` in row *i*."""
    codes = np.asarray(codes, dtype=np.int32)
    arr = pa.DictionaryArray.from_arrays(pa.array(codes), pa.array([str(v) for v in labels], type=pa.string()))
    return pd.array(arr.cast(pa.string()), dtype="str")


def label_codes(column, labels: list[str]) -> np.ndarray:
    """Codes of a text column in *labels*; labels not yet in the list are appended to it."""
    codes, uniques = pd.factorize(pd.Series(column), use_na_sentinel=False)
    lut = np.empty(len(uniques), dtype=np.int32)
    for i, u in enumerate(uniques):
        u = "" if u is None or (isinstance(u, float) and u != u) else str(u)
        if u not in labels:
            labels.append(u)
        lut[i] = labels.index(u)
    return lut[codes] if len(codes) else np.zeros(0, dtype=np.int32)
