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


def test_dense_heavy_tailed_logs_raise_no_false_structure():
    """Student-t noise (4 dof) at 10 Hz, diagnosed in-process (no reduction): the trimmed σ of single samples is
    below the noise's standard deviation, and merged rows feel the whole variance — their standard errors carry
    the tail factor (mean_factor ≈ 1.08), so the coarse copy shows no structure where there is none (4 seeds; it
    did in 4 of 4 without the factor), and a lining creep is still named."""
    from rollaway.identify.diagnose import diagnose
    from tests.identify.bench_generator import generate
    for seed in range(2, 6):
        d = diagnose(generate([], sampling="10Hz", seed=seed, n_forces=2, duration_s=1800.0))
        assert d.verdict == "none" and not d.remaining_structure, d.summary()
        assert 1.03 < d.noise_torque.mean_factor < 1.15
    d = diagnose(generate(["creep_exponential"], sampling="10Hz", seed=2, n_forces=2, duration_s=1800.0))
    assert d.verdict == "lining_creep" and not d.remaining_structure
    g = diagnose(generate([], sampling="10Hz", seed=2, n_forces=2, duration_s=1800.0, tail_dof=None))
    assert g.noise_torque.mean_factor < 1.02                 # Gaussian noise: no tail to count
