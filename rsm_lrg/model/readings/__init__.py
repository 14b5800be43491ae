"""What is read from a fitted model: the analysis of variance, the coefficients in actual
units, canonical and ridge analysis, effects, diagnostics, a fit at one categoric level and
the mixture trace (``anova``, ``actual``, ``actual_units``, ``canonical``, ``ridge``,
``effects``, ``diagnostics``, ``levels``, ``mixture_trace``).
"""
