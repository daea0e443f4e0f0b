"""One brake parameter of the drum calibration's identifiability report (:mod:`rollaway.identify.drum`): fitted,
held at its assumed value (with the spread it keeps in the bands) or not tested, and why."""
from __future__ import annotations

from dataclasses import dataclass, field

from rollaway.model.drum_parameters import FREE_PARAMETERS


@dataclass
class ParameterStatus:
    """One brake parameter of the identifiability report."""

    name: str
    status: str                      # "fitted", "fixed", "not tested", "logged", "fixed by you"
    value: float
    assumed_value: float
    unit: str
    stderr: float | None = None
    ci95: tuple[float, float] | None = None
    prior_sd: float | None = None    # the doubt kept for bands when not fitted [assumed]
    confounded_with: list[str] = field(default_factory=list)
    reason: str = ""

    def interval(self) -> tuple[tuple[float, float] | None, str | None]:
        """(95 % interval, its source): the fit's; for a parameter held with an assumed spread, its value ± 1.96
        spreads within its bounds — the doubt the bands and the other parameters' intervals count for it, since
        these data do not narrow it [assumed]; else (None, None)."""
        if self.ci95 is not None:
            return (float(self.ci95[0]), float(self.ci95[1])), "fit"
        if not self.prior_sd:
            return None, None
        p = FREE_PARAMETERS[self.name]
        return (max(p.lower, self.value - 1.96 * self.prior_sd), min(p.upper, self.value + 1.96 * self.prior_sd)), \
            "assumed spread"

    def as_dict(self) -> dict:
        ci, source = self.interval()
        return {"status": self.status, "value": self.value, "assumed_value": self.assumed_value, "unit": self.unit,
                "stderr": self.stderr, "ci95": None if ci is None else list(ci), "ci95_from": source,
                "prior_sd": self.prior_sd, "confounded_with": self.confounded_with, "reason": self.reason,
                "stands_for": FREE_PARAMETERS[self.name].stands_for}

    def line(self) -> str:
        p = FREE_PARAMETERS[self.name]
        if self.status == "fitted":
            ci = f" [{self.ci95[0]:.4g}, {self.ci95[1]:.4g}]" if self.ci95 else ""
            head = f"fitted        {self.value:.5g} ± {self.stderr:.2g}{ci} {p.unit}"
            tail = f"  (assumed {self.assumed_value:.4g}; stands for the {p.stands_for})"
        else:
            head = f"{self.status:<13} {self.value:.5g} {p.unit}"
            where = "in the bands" if p.drawn else ("in the parameter intervals, held in the bands (drawn facing "
                                                    "an untested direction)")
            ci = self.interval()[0]
            tail = f"  — {self.reason}" + (f" (kept as ±{self.prior_sd:.2g} {p.unit} {where}, 95 % "
                                            f"[{ci[0]:.4g}, {ci[1]:.4g}] [assumed])" if self.prior_sd else "")
        return f"  {self.name:<21} {head}{tail}"


__all__ = ["ParameterStatus"]
