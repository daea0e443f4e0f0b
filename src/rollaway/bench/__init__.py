"""Bench data against the model: compare, diagnose missing physics, refit with effects (issue 5)."""
from rollaway.bench.effects import (CATALOGUE, Effect, EffectParameter, available_effects, get_effect,
                                    load_effect_file, register_effect)
from rollaway.bench.measurements import Measurements, load_measurements
from rollaway.bench.model import BenchModel

__all__ = ["CATALOGUE", "Effect", "EffectParameter", "available_effects", "get_effect", "load_effect_file",
           "register_effect", "Measurements", "load_measurements", "BenchModel"]
