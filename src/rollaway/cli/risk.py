"""``rollaway risk POPULATION.toml``: the roll-away rate of a production fleet (:func:`rollaway.risk`)."""
from __future__ import annotations

from typing import Optional

import typer

from rollaway.cli import options as opt
from rollaway.cli.output import echo_json


def risk(
    population: str = typer.Argument(..., metavar="POPULATION_TOML",
                                     help="population file: a scenario's fixed values + [vary] (scenarios/populations/)"),
    json_out: bool = typer.Option(False, "--json", help="print the result as JSON"),
    samples: int = typer.Option(1_000_000, "--samples", metavar="N", help="cars the estimate may evaluate at most (importance sampling "
                                 "takes its design-point search and one chunk of 10 000 beyond that; the number "
                                 "evaluated is reported)"),
    method: str = typer.Option("auto", "--method", metavar="METHOD",
                               help="auto | mc | is | subset | form (auto: a pilot Monte Carlo run decides)"),
    design: Optional[str] = typer.Option(None, "--design", metavar="NAME",
                                         help="solve for the least (or greatest) value of this fixed input, or "
                                              "NAME.lower / NAME.upper of a varied one, that keeps the rate ≤ --target"),
    target: Optional[float] = typer.Option(None, "--target", metavar="P", help="target rate, e.g. 1e-5 (10 ppm)"),
    sensitivity: bool = typer.Option(False, "--sensitivity", help="Sobol indices of the least brake margin"),
    chart: Optional[str] = typer.Option(None, "--chart", metavar="PNG", help="sensitivity bars (and/or the design curve)"),
    simulate: int = typer.Option(0, "--simulate", metavar="N", help="run the N cars nearest the boundary in MuJoCo"),
    executor: str = typer.Option("local", "--executor", metavar="NAME", help="local | dask (Monte Carlo chunks)"),
    dask_address: Optional[str] = typer.Option(None, "--dask-address", metavar="ADDRESS",
                                               help="dask.distributed scheduler (default with --executor dask: a "
                                                    "local cluster)"),
    params: Optional[str] = opt.params_option("drum model of the population: a set name, parameter file or "
                                              "model file (.toml); replaces the file's 'params'"),
    seed: int = typer.Option(0, "--seed", metavar="S", help="seed of every random draw"),
    quiet: bool = typer.Option(False, "--quiet", help="no progress bar"),
) -> int:
    """Roll-away rate of a production fleet (ppm, 95 % interval), drivers and design.

    The probability that a car of the population rolls away (brake slip or tyre skid within
    duration_s), with its 95 % interval, the method and the cars evaluated; per failure mode;
    with --sensitivity the Sobol indices of the least brake margin; with --design/--target the
    value of one input that meets the target.  Exit 0 on success, 2 on bad input.
    """
    import sys

    from rollaway.api import risk as run

    res = run(population, samples=samples, method=method, seed=seed, sensitivity=sensitivity, design=design,
              target=target, chart=chart, simulate=simulate, executor=executor, dask_address=dask_address,
              params=params, progress=not quiet and not json_out and sys.stderr.isatty())
    if json_out:
        echo_json(res.as_dict())
    else:
        typer.echo(res.summary())
    return 0


def register(app: typer.Typer) -> None:
    app.command("risk")(risk)
