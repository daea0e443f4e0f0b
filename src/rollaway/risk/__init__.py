"""Fleet risk: the roll-away rate of a production population, what drives it, the design that meets a target.

A reliability study as OpenTURNS builds one — three objects, read in this order:

* :mod:`rollaway.risk.distributions`, :mod:`rollaway.risk.population`: the input distribution, a
  POPULATION.toml (a scenario's fixed values + ``[vary]`` marginals + a Gaussian copula);
* :mod:`rollaway.risk.limit_state`: the model — least brake margin and tyre margin of N cars at once;
* the algorithms: :mod:`rollaway.risk.estimators` (Monte Carlo, FORM, importance sampling, subset
  simulation; every estimate with its 95 % interval and its method), :mod:`rollaway.risk.sensitivity`
  (Sobol indices by SALib), :mod:`rollaway.risk.design` (the least value meeting a target rate);
* :mod:`rollaway.risk.study` puts them together (:func:`run_study`, :class:`RiskResult`);
  :mod:`rollaway.risk.executors` runs Monte Carlo chunks on a Dask cluster.

The package is also callable: ``rollaway.risk("POPULATION.toml", ...)`` is :func:`rollaway.api.risk`.
"""
from rollaway.callable_module import make_callable
from rollaway.risk.population import Population, load_population, population_from_mapping
from rollaway.risk.study import RiskResult, run_study

__all__ = ["Population", "RiskResult", "load_population", "population_from_mapping", "run_study"]

make_callable(__name__, "rollaway.api:risk")
