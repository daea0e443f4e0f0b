"""Figures: matplotlib (Agg) renderings of model results."""
