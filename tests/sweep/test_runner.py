"""Running sweeps with real MuJoCo: band selection, verdicts, failures, Dask = local."""
import pandas as pd
import pytest

from rollaway.hold.scenario import preset_scenarios
from rollaway.sweep import grid_spec, run_sweep
from rollaway.sweep.spec import expand, SweepSpec

BASE = preset_scenarios("fmvss135")[0]
GRID = {"grade_pct": [15, 25, 30, 35, 40, 45], "direction": ["uphill", "downhill"], "occupants": [1, 5],
        "hand_force_N": [250, 400], "tyre_road_mu": [0.5, 0.8], "duration_s": [60]}
TIMING = ("wall_time_s",)


def explode_on_steep(scenario, mode="fast"):
    """A simulator that fails on one kind of point (to prove a failing point is recorded)."""
    if scenario.grade_pct >= 40:
        raise FloatingPointError("simulation diverged (test)")
    from rollaway.sim import simulate
    return simulate(scenario, mode=mode)


@pytest.fixture(scope="module")
def band_run(tmp_path_factory):
    spec = grid_spec(BASE, GRID, simulate="band")
    return spec, run_sweep(spec, tmp_path_factory.mktemp("band"), workers=2, progress=False)


def test_table_has_a_row_per_point_with_inputs_and_results(band_run):
    spec, res = band_run
    t = res.table
    assert len(t) == len(spec.points) == 6 * 2 * 2 * 2 * 2
    assert t["point_id"].is_unique
    assert (t["error"] == "").all()
    for col in ("grade_pct", "brake_margin_min", "tyre_margin", "sim_outcome", "rollaway_time_s", "wall_time_s",
                "disagreement", "verdict"):
        assert col in t
    pq = pd.read_parquet(res.out_dir / "results.parquet")
    csv = pd.read_csv(res.out_dir / "results.csv", keep_default_na=False, na_values=[""])
    assert len(pq) == len(csv) == len(t)
    pd.testing.assert_series_equal(pq["brake_margin_min"], t["brake_margin_min"])
    assert list(csv["point_id"]) == list(t["point_id"])


def test_exactly_the_band_is_simulated(band_run):
    spec, res = band_run
    t = res.table
    lo, hi = spec.band
    near = (t["brake_margin_min"].between(lo, hi)) | (t["tyre_margin"].between(lo, hi))
    assert near.any() and not near.all()
    assert (t["simulated"] == near).all()
    assert (t.loc[t["simulated"], "sim_outcome"].isin(["held", "brake_slip", "tyre_skid"])).all()
    assert (t.loc[~t["simulated"], "outcome"] == t.loc[~t["simulated"], "analytic_outcome"]).all()


def test_simulated_verdicts_match_analytic_away_from_the_threshold(band_run):
    _, res = band_run
    s = res.table[res.table["simulated"]]
    clear = (s["margin"] - 1.0).abs() > 0.02
    assert clear.sum() >= 5
    assert (s.loc[clear, "outcome"] == s.loc[clear, "analytic_outcome"]).all()


def test_disagreements_are_explained(band_run):
    _, res = band_run
    t = res.table
    bad = t[t["agree"] == False]  # noqa: E712
    assert len(bad), "this grid has tyre-limited points the paper's check calls holding"
    assert (bad["disagreement"] != "").all()
    assert (t.loc[t["agree"] == True, "disagreement"] == "").all()  # noqa: E712
    skid = bad[bad["outcome"] == "tyre_skid"]
    assert len(skid) and skid["disagreement"].str.contains("ignores tyres").all()
    assert (skid["paper_verdict"] == "hold").all()


def test_plots_written(band_run):
    _, res = band_run
    names = {p.name for p in res.files}
    assert {"map-grade-occupants.png", "map-grade-hand-force.png", "design-chart.png"} <= names
    for p in res.files:
        if p.suffix == ".png":
            assert p.stat().st_size > 20_000


def test_failing_points_are_recorded_and_the_others_continue(tmp_path):
    points = [{"grade_pct": g, "direction": "uphill", "hand_force_N": 250} for g in (10, 20, 40, 45)]
    points += [{"occupants": 7}, {"grade_pct": 150}, {"occupants": 2.5}]     # bad input
    spec = SweepSpec(source="t", base=BASE, points=expand(BASE, None, points), simulate="all")
    for workers in (1, 2):
        res = run_sweep(spec, tmp_path / f"w{workers}", workers=workers, progress=False, plots=False,
                        simulate_fn=explode_on_steep)
        t = res.table.set_index("grade_pct", drop=False)
        assert len(t) == 7
        err = res.table["error"]
        assert err.str.contains("simulation diverged").sum() == 2
        assert err.str.contains("bad input").sum() == 3
        assert err.str.contains("2.5 is not a whole number").sum() == 1
        assert res.table.loc[err.str.contains("occupants"), "error"].str.contains("0 to 5").all()
        good = res.table[err == ""]
        assert len(good) == 2 and good["simulated"].all() and (good["sim_outcome"] != "").all()


def test_local_cluster_gives_the_same_table_as_local_processes(tmp_path, band_run):
    from distributed import LocalCluster
    spec, local = band_run
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        res = run_sweep(spec, tmp_path / "dask", dask_address=cluster.scheduler_address, progress=False, plots=False)
    assert res.n_run == local.n_to_simulate > 0
    pd.testing.assert_frame_equal(res.table.drop(columns=list(TIMING)), local.table.drop(columns=list(TIMING)))


def test_retry_failed_reruns_only_the_failed_points(tmp_path):
    points = [{"grade_pct": g, "direction": "uphill", "hand_force_N": 250, "duration_s": 30} for g in (10, 20, 40)]
    spec = SweepSpec(source="t", base=BASE, points=expand(BASE, None, points), simulate="all")
    first = run_sweep(spec, tmp_path, workers=1, progress=False, plots=False, simulate_fn=explode_on_steep)
    assert first.n_failed == 1 and first.n_run == 3
    again = run_sweep(spec, tmp_path, workers=1, progress=False, plots=False)
    assert again.n_run == 0 and again.n_failed == 1            # a recorded failure is a finished point
    retry = run_sweep(spec, tmp_path, workers=1, progress=False, plots=False, retry_failed=True)
    assert retry.n_run == 1 and retry.n_failed == 0 and retry.table["simulated"].all()
    ids = [line for line in (tmp_path / "journal.jsonl").read_text().splitlines()]
    assert len(ids) == 3


def test_simulate_none_is_analytic_only(tmp_path):
    spec = grid_spec(BASE, {"grade_pct": [10, 30, 45]}, simulate="none")
    res = run_sweep(spec, tmp_path, progress=False, plots=False)
    assert res.n_to_simulate == 0 and not res.table["simulated"].any()
    assert (res.table["outcome"] == res.table["analytic_outcome"]).all()
