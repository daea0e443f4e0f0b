"""The torque transducer's zero is re-set before every test, and never exactly."""
from __future__ import annotations

from rollaway.effects.base import Effect, EffectParameter


class TorqueZeroOffset(Effect):
    name = "torque_zero_offset"
    elementwise = True
    summary = "per-test zero offset of the torque transducer (zeroed by hand before each lever application)"
    physics = ("measured torque = T_gen (eq. 17b) + z_k, one constant z_k per test k: a strain-gauge bridge or "
               "load cell re-zeroed before each test keeps a small offset (drift of the bridge, seating of the "
               "reaction arm).")
    signature = ("each test's torque residual is shifted by its own constant, the same at every time and "
                 "unrelated to hand force, direction or temperature; the drum-temperature channel is unchanged")
    reference = ("HBM/ISO 376 practice for torque transducers (zero-point stability); Doebelin, Measurement "
                 "Systems, 5th ed. 2004, §4 (zero drift of strain-gauge bridges)")
    parameters = (EffectParameter("offset_Nm", "N·m", neutral=0.0, lower=-3000.0, upper=3000.0, initial=0.0,
                                  typical=25.0, per_test=True,
                                  description="zero offset of the torque reading in each test"),)

    def torque(self, state, torque_Nm, v):
        return torque_Nm + v["offset_Nm"]
