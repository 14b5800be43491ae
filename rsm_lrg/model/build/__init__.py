"""Specify and build (the floor under every fit, before any estimation).

``spec`` (:class:`~rsm_lrg.model.build.spec.ModelSpec`: everything fitted, one value object),
``data`` (the factors, the response, the runs left out), ``inputs`` (the checked inputs:
factors coded, blocks coded, the model matrix's terms chosen and every check made), ``terms``
(the model matrix, in :mod:`rsm_lrg.terms`), ``transform`` (response transformations),
``mixture`` and ``mixture_region`` (Scheffé models on L-pseudo-components and their
constrained simplex), ``goals`` (minimise, maximise, target). Nothing here estimates.
"""
