"""rollaway: will this parked car roll away?

Drum parking-brake model with cooling (Ishak et al. 2018, doi:10.22201/fi.25940732e.2018.19n1.004),
analytic hold checks against FMVSS 135 / UN R13-H, and a MuJoCo roll-away simulator.
"""
__version__ = "0.1.0"

from rollaway.brake import BrakeSeries, drum_brake
from rollaway.parameters import BrakeParameters, load_parameters, paper

__all__ = ["BrakeParameters", "BrakeSeries", "drum_brake", "load_parameters", "paper", "__version__"]
