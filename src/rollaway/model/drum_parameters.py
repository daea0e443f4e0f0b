"""The brake parameters bench data can calibrate: names, units, bounds, assumed spreads, confounders.

A bench measures torque and drum temperature, not the drum's dimensions.  Through the chain
(docs/model.md) the torque of one drum is

    T = μ_d·r_d / (1 − s·μ_d·ρ) · [K·(a·F + b) + C·ΔT],      ρ = l_fr/l_f,

with K the series stiffness of drum and lining and C the thermal clamp-force coefficient of
eq. (16a/b) (both products of A·E, α and thicknesses), u_6 = a·F + b (eq. 24), and the drum
temperature follows eq. (10) with τ = ρ_d·c_p·V / (h·A_conv) and the ambient T_amb.  So the
data identify at most: the torque scale per newton (μ_d·r_d·K·a), the thermal torque (μ_d·r_d·C),
the force offset (b/a), the self-energising product μ_d·ρ (only from the downhill/uphill
ratio), τ and T_amb.  The calibration therefore frees one name per identifiable product:

====================  ==========================================  =====================================
free name             what it stands for                          confounded with (enter as products)
====================  ==========================================  =====================================
``mu_drum``           torque scale (eq. 17b)                      r_d, A_d·E_d, A_l·E_l, l_od, l_ol, l_g
``u6_slope_m_per_N``  eq. (24) slope a (force term / thermal term) A_l·E_l, l_ol (through K/C)
``u6_offset_m``       eq. (24) offset b (the force where u_6 = 0)  —
``shoe_arm_ratio``    ρ = l_fr/l_f (eqs. 18–21)                    l_fr, l_f separately
``heat_transfer_W_m2K`` τ (eq. 10)                               ρ_d·c_p·V (drum mass), A_conv
``ambient_temp_C``    T_amb (eq. 10), when the bench did not log it —
``gap_m``             installation gap l_g (eq. 16b), never freed  μ_d (the same torque drop both ways)
                      by itself: held, its doubt kept
====================  ==========================================  =====================================

Each has a spread ``prior_sd`` **[assumed]**: how far a drum that is not the paper's may be
from the paper's value.  It scales the identifiability test (a direction of the parameter
space that the data pin down less tightly than this is "not identifiable") and carries the
doubt of every parameter left at its assumed value into the uncertainty bands.

The installation gap l_g is held at the set's value (0 in the paper set, eq. 16a) with a spread of
0.6 mm **[assumed]**: Table 1 lists 1 mm, and a gap lowers the torque by the same fraction in both
directions and nearly the same hot and cold, which a torque scale μ_d does as well, so a torque and
temperature log cannot tell the two apart.  Held as known, it would leave μ_d's interval centred on the
gap-free drum and missing the truth of a drum with Table 1's gap (the fit's μ_d then lies 0.03–0.06
low); with its spread, the 1 mm of Table 1 sits at 1.7 spreads, inside the 95 % range.  The bands do not
draw it (``drawn=False``): the road margin follows the torque the data pin, not how it splits between μ_d
and l_g (refitted along that valley from 0 to 1.5 mm the margins of a campaign move 0.6 % inside the
tested range and 1.3 % 80 °C hotter), while drawing the split from the linearised covariance widened the
bands by half again; they draw the covariance conditional on the set's gap
(:meth:`rollaway.model.covariance.Covariance.conditional`) — except facing a direction the bench did not
test, where the split decides the torque (μ_d sets the self-energising factor, the gap does not) and the gap is
drawn with μ_d (:func:`rollaway.uncertainty.draws.draw_values`).  ``--free gap_m`` fits it (rarely
identifiable); a fitted ``installation_gap`` effect takes its place.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from rollaway.model.parameters import BrakeParameters


@dataclass(frozen=True)
class FreeParameter:
    name: str
    symbol: str
    unit: str
    lower: float
    upper: float
    prior_sd: float            # [assumed] spread of real drums around the paper's value (absolute units)
    relative_sd: bool          # prior_sd is relative to the value
    channel: str               # "torque" or "temperature"
    stands_for: str
    confounded_with: tuple[str, ...] = ()
    automatic: bool = True     # the drum calibration may free it by itself (False: held unless --free names it)
    effect: str | None = None  # a catalogue effect that, when fitted, takes its place (its prior is dropped)
    drawn: bool = True         # held, its doubt is drawn in the bands (False: in the parameter intervals only)
    law: str | None = None     # the effect hook whose input its law sets (an effect replacing that law is compared
                               # with it free where the bare drum held it: identify.selection.own_channel_plan)

    def spread(self, value: float) -> float:
        return self.prior_sd * abs(value) if self.relative_sd else self.prior_sd


FREE_PARAMETERS: dict[str, FreeParameter] = {p.name: p for p in (
    FreeParameter("mu_drum", "μ_d", "–", 0.02, 1.0, 0.25, True, "torque",
                  "torque scale μ_d·r_d·A·E (eq. 17b)",
                  ("drum_radius_m", "drum_area_m2·drum_modulus_Pa", "lining_area_m2·lining_modulus_Pa",
                   "lining_thickness_m", "drum_thickness_m", "gap_m")),
    FreeParameter("u6_slope_m_per_N", "a", "m/N", 2e-8, 4e-6, 0.3, True, "torque",
                  "eq. (24) slope: hand-force term against thermal term",
                  ("lining_area_m2·lining_modulus_Pa", "lining_thickness_m"), law="displacement"),
    FreeParameter("u6_offset_m", "b", "m", -2e-4, 1e-4, 1.5e-5, False, "torque",
                  "eq. (24) offset: the hand force below which the lining does not bear", law="displacement"),
    FreeParameter("shoe_arm_ratio", "l_fr/l_f", "–", 0.1, 2.0, 0.25, True, "torque",
                  "self-energising geometry (eqs. 18–21): the downhill/uphill torque ratio",
                  ("shoe_arm_friction_m", "shoe_arm_normal_m")),
    FreeParameter("heat_transfer_W_m2K", "h", "W/(m² K)", 1.0, 400.0, 0.5, True, "temperature",
                  "cooling time constant τ (eq. 10)",
                  ("drum_density_kg_m3·drum_specific_heat_J_kgK·drum_volume_m3", "cooled_area_m2"),
                  law="drum_temperature"),
    FreeParameter("ambient_temp_C", "T_amb", "°C", -40.0, 60.0, 8.0, False, "temperature",
                  "ambient air of the bench (eq. 10)", law="drum_temperature"),
    FreeParameter("gap_m", "l_g", "m", 0.0, 3e-3, 6e-4, False, "torque",
                  "installation gap lining/drum (eq. 16b): Table 1 lists 1 mm, the set assumes 0",
                  ("mu_drum",), automatic=False, effect="installation_gap", drawn=False),
)}

BASELINE_FREE = tuple(FREE_PARAMETERS)          # every name a calibration may free, in chain order
NOT_DRAWN = tuple(n for n, p in FREE_PARAMETERS.items() if not p.drawn)   # held ones the bands hold at the set's value
LEGACY_FREE = ("mu_drum", "heat_transfer_W_m2K")
BASELINE_BOUNDS = {n: (p.lower, p.upper) for n, p in FREE_PARAMETERS.items()}
BASELINE_UNITS = {n: p.unit for n, p in FREE_PARAMETERS.items()}


def value_of(params: BrakeParameters, name: str) -> float:
    """The free parameter *name* read off a parameter set (``shoe_arm_ratio`` = l_fr/l_f)."""
    if name == "shoe_arm_ratio":
        return params.shoe_arm_friction_m / params.shoe_arm_normal_m
    return float(getattr(params, name))


def values_of(params: BrakeParameters) -> dict[str, float]:
    return {n: value_of(params, n) for n in BASELINE_FREE}


def apply(params: BrakeParameters, values: dict) -> BrakeParameters:
    """*params* with the free parameters in *values* written in (l_fr = ρ·l_f; other keys ignored)."""
    changes = {}
    for name, v in values.items():
        if name == "shoe_arm_ratio":
            changes["shoe_arm_friction_m"] = float(v) * params.shoe_arm_normal_m
        elif name in FREE_PARAMETERS:
            changes[name] = float(v)
    if not changes:
        return params
    return dataclasses.replace(params, **changes)


__all__ = ["BASELINE_BOUNDS", "BASELINE_FREE", "BASELINE_UNITS", "FREE_PARAMETERS", "FreeParameter", "LEGACY_FREE",
           "NOT_DRAWN", "apply", "value_of", "values_of"]
