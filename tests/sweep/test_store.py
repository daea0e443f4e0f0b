"""The journal survives torn lines and never counts a point twice; the analytic pass is the scalar check."""
import json

import numpy as np
import pytest

from rollaway.hold import analytic_verdict
from rollaway.hold.scenario import preset_scenarios
from rollaway.sweep.analytic import analytic_pass, in_band
from rollaway.sweep.spec import expand
from rollaway.sweep.store import Journal, drop_records


def test_torn_last_line_is_cut_and_appends_start_clean(tmp_path):
    j = Journal(tmp_path)
    j.append({"point_id": "a", "x": 1.0})
    j.append({"point_id": "b", "x": float("nan")})
    j.close()
    with open(j.path, "a") as fh:
        fh.write('{"point_id": "c", "x"')          # killed mid-write
    j2 = Journal(tmp_path)
    assert set(j2.load()) == {"a", "b"}
    assert j2.load()["b"]["x"] is None
    j2.append({"point_id": "c", "x": 3.0})
    j2.close()
    lines = j.path.read_text().splitlines()
    assert [json.loads(line)["point_id"] for line in lines] == ["a", "b", "c"]


def test_duplicates_are_counted_and_first_wins(tmp_path):
    j = Journal(tmp_path)
    for v in (1, 2):
        j.append({"point_id": "a", "v": v})
    j.close()
    recs = j.load()
    assert recs["a"]["v"] == 1 and j.duplicates == 1


def test_drop_records(tmp_path):
    j = Journal(tmp_path)
    for pid in "abc":
        j.append({"point_id": pid})
    j.close()
    drop_records(tmp_path, {"b"})
    assert set(Journal(tmp_path).load()) == {"a", "c"}


def test_vectorised_pass_equals_the_scalar_check():
    base = preset_scenarios("paper30")[0]
    rng = np.random.default_rng(4)
    pts = [{"grade_pct": float(g), "direction": d, "occupants": int(n), "hand_force_N": float(f),
            "mu_drum": float(mu), "initial_drum_temp_C": float(t0), "tyre_road_mu": float(mr), "duration_s": float(du)}
           for g, d, n, f, mu, t0, mr, du in zip(rng.uniform(-40, 50, 60), rng.choice(["uphill", "downhill"], 60),
                                                 rng.integers(0, 6, 60), rng.uniform(100, 600, 60),
                                                 rng.uniform(0.25, 0.6, 60), rng.uniform(27, 300, 60),
                                                 rng.uniform(0.3, 1.0, 60), rng.uniform(10, 7200, 60))]
    res = analytic_pass(base, expand(base, None, pts), (0.9, 1.15))
    for p, (_, row) in zip(pts, res.iterrows()):
        s = base.replace(**p)
        v = analytic_verdict(s.params, hand_force_N=p["hand_force_N"], grade_pct=p["grade_pct"],
                             direction=p["direction"], occupants=p["occupants"], duration_s=p["duration_s"])
        assert row["brake_margin_min"] == pytest.approx(v.brake_margin_min, rel=1e-9)
        assert row["tyre_margin"] == pytest.approx(v.tyre_margin, rel=1e-12)
        assert (row["paper_verdict"] == "hold") == (v.brake_margin_min >= 1)
        assert (row["analytic_outcome"] == "held") == v.holds
        if np.isfinite(v.time_to_slip_s):
            assert row["analytic_time_to_slip_s"] == pytest.approx(v.time_to_slip_s, rel=1e-9)


def test_band_selects_either_margin():
    b = in_band([0.5, 0.95, 1.2, 2.0, 2.0], [2.0, 2.0, 2.0, 1.1, 0.85], (0.9, 1.15))
    assert b.tolist() == [False, True, False, True, False]


def test_concurrent_table_writes_use_their_own_temporary_files(tmp_path):
    from concurrent.futures import ThreadPoolExecutor

    import pandas as pd

    from rollaway.sweep.store import write_table
    frames = [pd.DataFrame({"a": [float(i)] * 1000, "b": ["x"] * 1000}) for i in range(8)]
    with ThreadPoolExecutor(4) as pool:
        list(pool.map(lambda df: write_table(df, tmp_path), frames))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["results.csv", "results.parquet"]   # no .tmp left
    back = pd.read_parquet(tmp_path / "results.parquet")
    assert len(back) == 1000 and back["a"].nunique() == 1
