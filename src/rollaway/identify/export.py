"""A fit as a drum-model file: the calibrated :class:`~rollaway.model.drum_model.DrumModel` with covariance and provenance.

What ``fit --save-model`` and ``diagnose --save-model`` write, and what ``--params`` of every
other command reads back (:mod:`rollaway.model.model_file`).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rollaway.model.drum_model import Covariance, DrumModel


def fit_covariance(fit) -> Covariance | None:
    """The covariance of the fitted parameters (the fit's own matrix, else its standard errors on a diagonal)."""
    cov = getattr(fit, "covariance", None)
    if isinstance(cov, Covariance):
        return cov
    if isinstance(cov, tuple) and len(cov) == 2:
        return Covariance(tuple(cov[0]), np.asarray(cov[1], float))
    corr, names = getattr(fit, "correlation", None), list(getattr(fit, "names", []) or [])
    if corr is not None and len(names) == np.shape(corr)[0]:     # the joint fit's full covariance
        se = np.array([fit.estimates[n].stderr for n in names])
        keep = np.isfinite(se)
        c = np.nan_to_num(np.asarray(corr, float)[np.ix_(keep, keep)]) * np.outer(se[keep], se[keep])
        np.fill_diagonal(c, se[keep] ** 2)
        if keep.any():
            return Covariance(tuple(n for n, k in zip(names, keep) if k), c)
    names = [n for n, e in fit.estimates.items() if np.isfinite(e.stderr)]
    if not names:
        return None
    return Covariance(tuple(names), np.diag([fit.estimates[n].stderr ** 2 for n in names]))


def calibrated_model(fit, data_path: str | Path | None = None, command: str = "fit") -> DrumModel:
    """The drum model a fit found: its parameter set with μ_d and h, its effects and values, covariance."""
    from rollaway.model.model_file import provenance_for

    held = {f"{e.name}.{p.name}": p.initial for e in fit.model.effects for p in e.parameters if p.held}
    model = fit.model.drum_model({**held, **fit.values}, covariance=fit_covariance(fit))   # held: at their centre
    model.calibration = dict(fit.fit_info.get("calibration", {}))
    model.predictive = dict(fit.fit_info.get("predictive", {}))
    alts = fit.fit_info.get("alternatives") or []
    model._alternatives = [(w, calibrated_model(f)) for w, f in alts]
    if data_path is not None:
        folder = Path(data_path).is_dir()
        files = sorted(f for f in Path(data_path).iterdir() if f.is_file()) if folder else [Path(data_path)]
        model.provenance = provenance_for(files[0], rows=fit.data.rows_info()["rows_read"], tests=fit.data.n_tests,
                                          command=command, rmse={"rmse_torque_Nm": fit.rmse_torque_Nm,
                                                                 "rmse_temp_C": fit.rmse_temp_C})
        if folder:          # a folder of files per test: its name, and one hash over its files (names and contents)
            import hashlib

            from rollaway.model.model_file import file_sha256
            h = hashlib.sha256("".join(f"{f.name}:{file_sha256(f)}\n" for f in files).encode())
            model.provenance.update(data_file=Path(data_path).name + "/", data_sha256=h.hexdigest())
    return model


def save_fit(fit, path: str | Path, data_path: str | Path | None, command: str) -> Path:
    """Write the calibrated model of *fit* as a model file (*data_path*: the CSV it was fitted on, or None)."""
    from rollaway.model.model_file import save_model

    model = calibrated_model(fit, data_path, command)
    effects = ", ".join(e.name for e in model.effects) or "no effect (paper chain, calibrated)"
    on = f" on {Path(data_path).name}" if data_path is not None else ""
    return save_model(model, path, comment=f"Calibrated by 'rollaway {command}'{on}: {effects}.")


def data_file(data) -> Path | None:
    """The file or folder *data* (:class:`~rollaway.bench.measurements.Measurements`) was read from, if it still exists."""
    p = Path(str(getattr(data, "source", "")))
    return p if p.exists() else None


class CalibratedModelMixin:
    """``.model`` and ``.save_model(path)`` of a result whose :meth:`_calibrated_fit` is the fit to keep."""

    _command = "fit"

    def _calibrated_fit(self):
        raise NotImplementedError

    @property
    def model(self) -> DrumModel:
        """The calibrated drum model: parameter set with the fitted μ_d and h, effects, values, covariance and
        provenance (the data file's name and SHA-256 when the data were read from a file)."""
        fit = self._calibrated_fit()
        return calibrated_model(fit, data_file(fit.data), self._command)

    def save_model(self, path: str | Path, data_path: str | Path | None = None) -> Path:
        """Write :attr:`model` as a model file (TOML) for ``DrumModel(path)`` or ``--params path``; returns the path.
        *data_path*: the file or folder the data came from (default: the data's source, if it exists)."""
        fit = self._calibrated_fit()
        return save_fit(fit, path, data_path if data_path is not None else data_file(fit.data), self._command)
