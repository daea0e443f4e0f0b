"""Where the Monte Carlo chunks of a rate estimate run: in this process, or on a Dask cluster.

A chunk is (population, size, seed sequence) → (failures, brake slips, tyre skids)
(:func:`rollaway.risk.estimators.count_chunk`); chunks are independent, so the counts add up to the
same estimate wherever they run (the seed of each chunk is spawned from the study's seed).  Dask: an
existing scheduler (``--dask-address tcp://host:8786``, as ``rollaway sweep --dask``) or, without an
address, a ``distributed.LocalCluster`` of worker processes on this machine.
"""
from __future__ import annotations

import os

import numpy as np

from rollaway.errors import UserError, check_choice

EXECUTORS = ("local", "dask")


class DaskChunks:
    """Monte Carlo chunks sent to a ``dask.distributed`` cluster; the population is scattered once."""

    def __init__(self, address: str | None = None):
        from distributed import Client, LocalCluster
        self.cluster = None
        try:
            if address:
                self.client = Client(address, timeout=f"{os.environ.get('ROLLAWAY_DASK_TIMEOUT_S', '15')}s")
            else:
                self.cluster = LocalCluster(n_workers=max(1, min(os.cpu_count() or 1, 4)), threads_per_worker=1,
                                            processes=True, dashboard_address=None)
                self.client = Client(self.cluster)
        except (OSError, TimeoutError, ValueError) as exc:
            raise UserError(f"cannot reach the Dask scheduler at '{address}' ({exc}); start one with "
                            f"'dask scheduler' and workers with 'dask worker ADDRESS', or use --executor local") \
                from None

    def __call__(self, population, sizes, seeds) -> np.ndarray:
        from rollaway.risk.estimators import count_chunk
        pop = self.client.scatter(population, broadcast=True)
        futures = self.client.map(count_chunk, [pop] * len(sizes), sizes, seeds, pure=False)
        return np.sum(self.client.gather(futures), axis=0)

    def close(self) -> None:
        self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def executor_for(name: str, address: str | None = None):
    """None for in-process chunks, a :class:`DaskChunks` for ``dask``."""
    check_choice(name, EXECUTORS, "--executor")
    if name == "local":
        if address:
            raise UserError("--dask-address needs --executor dask")
        return None
    return DaskChunks(address)
