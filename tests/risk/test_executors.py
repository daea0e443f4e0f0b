"""Monte Carlo chunks on a Dask cluster give the same rate as in process."""
from rollaway.risk import load_population, run_study

POP = "[vary]\nmu_drum = { uniform = [0.3, 0.6] }\n"


def test_dask_chunks_give_the_same_rate_as_local_ones(write_population):
    pop = load_population(write_population(POP)).with_fixed("hand_force_N", 250.0)
    local = run_study(pop, samples=300_000, method="mc", seed=5)
    dask = run_study(pop, samples=300_000, method="mc", seed=5, executor="dask")
    assert local.probability == dask.probability and local.ci95 == dask.ci95
