"""Enough samples to judge a fit: more in each channel than the parameters it frees.

A fit with as many parameters as samples interpolates them: its residual variance is no estimate, and the
information criteria, which take its logarithm, run towards −∞ — one 0.5-s test reduced to two window means
"explained" by a friction law at ΔBIC −49.  :func:`require` refuses such data with what to change, before a fit
is judged (the drum calibration of ``diagnose``, every rung of ``fit``).
"""
from __future__ import annotations

from rollaway.errors import UserError

SPARE = 2       # [assumed] samples a channel needs beyond the parameters fitted: its residual variance from at least
                # two degrees of freedom (one leaves a variance estimate with an infinite relative variance of its log)


def require(data, n_params: int, what: str) -> None:
    """Raise a :class:`~rollaway.errors.UserError` naming *data*'s source when its samples (each a temperature and
    a torque) are fewer than *n_params* + :data:`SPARE`: too few to *what* (e.g. "calibrate the drum")."""
    need = int(n_params) + SPARE
    if len(data) >= need:
        return
    window = (data.rows_info() if hasattr(data, "rows_info") else {}).get("window_s")
    hint = ", or reduce the log to shorter windows (--window-s; 0: every sample)" if window else ""
    raise UserError(f"{data.source}: {len(data)} samples in {data.n_tests} test{'s' if data.n_tests != 1 else ''} "
                    f"are too few to {what} ({n_params} parameters, each test's T_0 included; it needs at least "
                    f"{need} samples); log longer tests or more of them{hint}")


__all__ = ["SPARE", "require"]
