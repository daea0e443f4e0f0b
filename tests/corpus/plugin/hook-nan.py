import numpy as np
from rollaway.effects.base import Effect, EffectParameter


class Humidity(Effect):
    name = "humidity"
    summary = "moisture raises the lining friction while the drum is cold"
    physics = "mu = mu_d (1 + a exp(-(T_l - T_amb)/30 K))"
    signature = "torque residual at the cold end"
    reference = "corpus"
    parameters = (EffectParameter("a", "-", neutral=0.0, lower=0.0, upper=1.0, initial=0.05),)

    def friction(self, state, mu, v):
        return mu * np.nan
