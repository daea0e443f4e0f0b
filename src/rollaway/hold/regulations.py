"""Regulation presets for parking-brake hold checks, each with its source.

Laden means the car with all five 70 kg seats taken (1600 kg) [assumed: the paper's
car has no published GVWR].  Initial drum temperature is the paper's 200 °C (its Fig. 12
compliance check) [assumed: FMVSS 135 S7.12 itself requires IBT ≤ 100 °C, so 200 °C
is the harder case for the 1D model, which loses clamp force as the drum cools].
"""
from __future__ import annotations

from dataclasses import dataclass

from rollaway.errors import check_choice


@dataclass(frozen=True)
class Preset:
    name: str
    grade_pct: float
    hand_force_N: float
    duration_s: float
    directions: tuple[str, ...]
    occupants: int
    initial_temp_C: float
    source: str
    note: str = ""


PRESETS: dict[str, Preset] = {p.name: p for p in (
    Preset("fmvss135", 20.0, 400.0, 300.0, ("downhill", "uphill"), 5, 200.0,
           "FMVSS 135 S7.12 (49 CFR 571.135): 20 % grade, ≤ 400 N hand (500 N foot), 5 min, "
           "both directions, laden (GVWR)",
           "hand lever, so 400 N; IBT 200 °C [assumed, paper Fig. 12]"),
    Preset("unr13h", 20.0, 400.0, 300.0, ("downhill", "uphill"), 5, 200.0,
           "UN R13-H §2.3.1 / Annex 3 §2.3: laden vehicle held on a 20 % up or down gradient, "
           "hand control ≤ 400 N",
           "R13-H states no hold time: 300 s [assumed]; IBT 200 °C [assumed]"),
    Preset("paper30", 30.0, 445.0, 3600.0, ("downhill", "uphill"), 1, 200.0,
           "Ishak et al. 2018, Introduction (after Thiessen 1987): 30 % gradient with ≤ 445 N on a "
           "hand lever, held over any desired time; the paper's 1 h cooling from 200 °C",
           "driver only (1320 kg), as in docs/model.md's T_req on 30 %"),
)}


def get_preset(name: str) -> Preset:
    return PRESETS[check_choice(name, PRESETS, "regulation preset")]
