"""Coarser copies of dense measurements for model selection (rollaway.identify.coarse)."""
from __future__ import annotations

import numpy as np

from rollaway.identify.coarse import MAX_WINDOW_S, coarsen
from tests.identify.bench_generator import generate


def test_small_data_are_left_alone():
    d = generate(seed=1)                      # 8 tests × 13 samples
    assert coarsen(d) is d


def test_rows_merge_within_tests_with_counts_and_weighted_means():
    d = generate(seed=2, sampling="1min")     # 8 tests × 61 samples = 488 rows
    c = coarsen(d, max_rows=200)
    assert len(c) < len(d) and c.n_tests == d.n_tests and c.tests == d.tests
    assert c.count.sum() == len(d)                                        # every sample in exactly one row
    for k in range(d.n_tests):
        rows, raw = c.test_index == k, d.test_index == k
        assert c.time_s[rows][0] == 0.0 and c.count[rows][0] == 1        # T_0 kept alone
        assert np.all(np.diff(c.time_s[rows]) > 0)
        assert np.isclose((c.torque_Nm[rows] * c.count[rows]).sum(), d.torque_Nm[raw].sum())
        assert np.isclose((c.time_s[rows] * c.count[rows]).sum(), d.time_s[raw].sum())
    assert c.count.max() <= MAX_WINDOW_S / 60.0 + 1                     # never wider than the window limit


def test_sparse_rows_are_not_merged():
    d = generate(seed=3, sampling="5min", n_forces=40)                    # 80 tests × 13 = 1040 rows, 300 s apart
    assert coarsen(d, max_rows=100) is d
