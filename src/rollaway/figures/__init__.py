"""Figures: matplotlib (Agg) renderings of model results: the paper's Figures 9–14 (:mod:`~rollaway.figures.paper`)
and the design chart of least hand force against grade (:mod:`~rollaway.figures.design`)."""
