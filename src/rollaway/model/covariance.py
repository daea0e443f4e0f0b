"""What a calibration moves and how sure it is: the free baseline values and :class:`Covariance`.

A calibrated :class:`~rollaway.model.drum_model.DrumModel` carries the covariance of its fitted values
(the brake parameters of :mod:`rollaway.model.drum_parameters` and ``EFFECT.PARAMETER`` of its
effects).  This module holds that small record, so that both the model (:mod:`rollaway.model.drum_model`)
and its file format (:mod:`rollaway.model.model_file`) can use it without importing each other.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rollaway.errors import UserError

# Brake parameters a calibration may free, their bounds and units: rollaway.model.drum_parameters
from rollaway.model.drum_parameters import BASELINE_BOUNDS, BASELINE_FREE, BASELINE_UNITS  # noqa: E402,F401


@dataclass(frozen=True)
class Covariance:
    """Covariance of fitted parameters: names (``"mu_drum"``, ``"lining_creep.relaxed_fraction"``) and matrix."""

    names: tuple[str, ...]
    matrix: np.ndarray

    def __post_init__(self):
        m = np.asarray(self.matrix, float)
        object.__setattr__(self, "matrix", m)
        object.__setattr__(self, "names", tuple(self.names))
        if m.shape != (len(self.names), len(self.names)):
            raise UserError(f"covariance: matrix is {m.shape[0]}×{m.shape[1] if m.ndim > 1 else 1} but "
                            f"{len(self.names)} names are given; give one row and column per name")

    def conditional(self, given: tuple[str, ...] | list[str]) -> "Covariance":
        """The covariance of the other names with *given* held at their values (Gaussian conditioning: the Schur
        complement Σ_aa − Σ_ag·Σ_gg⁻¹·Σ_ga); names of *given* not in the record are ignored."""
        g = [i for i, n in enumerate(self.names) if n in given]
        if not g:
            return self
        a = [i for i in range(len(self.names)) if i not in g]
        s = self.matrix
        sgg = s[np.ix_(g, g)]
        cond = s[np.ix_(a, a)] - s[np.ix_(a, g)] @ np.linalg.pinv(sgg) @ s[np.ix_(g, a)]
        return Covariance(tuple(self.names[i] for i in a), 0.5 * (cond + cond.T))

    @property
    def stderr(self) -> dict[str, float]:
        return {n: float(np.sqrt(max(self.matrix[i, i], 0.0))) for i, n in enumerate(self.names)}


__all__ = ["BASELINE_BOUNDS", "BASELINE_FREE", "BASELINE_UNITS", "Covariance"]
