"""A fit as a drum-model file: the calibrated :class:`~rollaway.model.DrumModel` with covariance and provenance.

What ``fit --save-model`` and ``diagnose --save-model`` write, and what ``--params`` of every
other command reads back (:mod:`rollaway.model_file`).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rollaway.model import Covariance, DrumModel


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
    from rollaway.model_file import provenance_for

    model = fit.model.drum_model(fit.values, covariance=fit_covariance(fit))
    if data_path is not None:
        folder = Path(data_path).is_dir()
        files = sorted(f for f in Path(data_path).iterdir() if f.is_file()) if folder else [Path(data_path)]
        model.provenance = provenance_for(files[0], rows=fit.data.rows_info()["rows_read"], tests=fit.data.n_tests,
                                          command=command, rmse={"rmse_torque_Nm": fit.rmse_torque_Nm,
                                                                 "rmse_temp_C": fit.rmse_temp_C})
        if folder:          # a folder of files per test: its name, and one hash over its files (names and contents)
            import hashlib

            from rollaway.model_file import file_sha256
            h = hashlib.sha256("".join(f"{f.name}:{file_sha256(f)}\n" for f in files).encode())
            model.provenance.update(data_file=Path(data_path).name + "/", data_sha256=h.hexdigest())
    return model


def save_fit(fit, path: str | Path, data_path: str | Path, command: str) -> Path:
    """Write the calibrated model of *fit* as a model file."""
    from rollaway.model_file import save_model

    model = calibrated_model(fit, data_path, command)
    effects = ", ".join(e.name for e in model.effects) or "no effect (paper chain, calibrated)"
    return save_model(model, path, comment=f"Calibrated by 'rollaway {command}' on {Path(data_path).name}: {effects}.")
