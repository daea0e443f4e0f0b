"""Bench data against the model: compare, diagnose missing physics, refit with effects."""
from rollaway.effects import (CATALOGUE, Effect, EffectParameter, available_effects, get_effect,
                                    load_effect_file, register_effect)
from rollaway.identify.measurements import Measurements, load_measurements
from rollaway.identify.model import BenchModel

__all__ = ["CATALOGUE", "Effect", "EffectParameter", "available_effects", "get_effect", "load_effect_file",
           "register_effect", "Measurements", "load_measurements", "BenchModel"]
