"""Export: the calibrated drum model for other tools, as an FMI 2.0 co-simulation FMU.

:func:`export_fmu` writes the chain and every catalogue effect as C code (:mod:`rollaway.export.c_source`)
with the model's values baked in, compiles it, and zips it with ``modelDescription.xml``
(:mod:`rollaway.export.model_description`); :mod:`rollaway.export.variables` is the one list of
the FMU's variables both are written from.
"""
from rollaway.export.fmu import export_fmu

__all__ = ["export_fmu"]
