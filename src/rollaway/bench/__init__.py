"""Bench logs in: lab formats, units, column maps, streamed reduction to window means, noise at the raw rate.

Modules, from the file to the measurements:

* :mod:`rollaway.bench.sources`: one file or a folder of tests (CSV, Parquet, ASAM MDF4) → rows;
* :mod:`rollaway.bench.readers`: the file kinds as record batches (CSV dialects, rows pyarrow cannot take);
* :mod:`rollaway.bench.manifest`: a campaign's manifest (direction and hand force per test);
* :mod:`rollaway.bench.columns`: the lab's column names and units (pint) → rollaway's quantities;
* :mod:`rollaway.bench.asam_mdf`: ASAM MDF4 logs (asammdf, optional);
* :mod:`rollaway.bench.batch`: a block of rows as read;
* :mod:`rollaway.bench.cells`, :mod:`rollaway.bench.time_axis`: the checks of every row, time axes in another unit;
* :mod:`rollaway.bench.reduction`: the checks of each test; high-rate logs streamed and reduced to window means;
* :mod:`rollaway.bench.rawnoise`, :mod:`rollaway.bench.noise`: measurement noise at the raw rate and of window means;
* :mod:`rollaway.bench.measurements`: :class:`Measurements` and :func:`load_measurements`.

Nothing here knows the model: the fits live in :mod:`rollaway.identify`.
"""
from rollaway._moved import lazy_getattr

_NAMES = {"Measurements": "rollaway.bench.measurements", "load_measurements": "rollaway.bench.measurements"}
__all__ = sorted(_NAMES)
__getattr__ = lazy_getattr(__name__, _NAMES)
