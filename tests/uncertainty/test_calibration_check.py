"""The calibration self-check on the user's own design (rollaway.uncertainty.calibration_check)."""
from __future__ import annotations

import pytest

from rollaway.errors import UserError
from rollaway.uncertainty.calibration_check import check_calibration, words
from rollaway.identify.diagnose import diagnose
from tests.identify.bench_generator import generate


def test_campaigns_of_the_users_design_report_coverage():
    d = diagnose(generate(["creep_exponential"], seed=61))
    out = check_calibration(d, 3, draws=100)
    assert out["campaigns"] == 3 and len(out["results"]) == 3
    assert 0.0 <= out["coverage"] <= 1.0 and out["median_half_width"] > 0
    for r in out["results"]:
        assert r["p5"] <= r["p95"] and r["covered"] == (r["p5"] <= r["truth"] <= r["p95"])
    assert "synthetic campaigns of your test design" in words(out)
    with pytest.raises(UserError, match="--check-calibration"):
        check_calibration(d, 0)
