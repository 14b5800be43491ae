"""Fitted models, one result type per kind: ``result`` (:class:`FitResult`: OLS, transformed,
blocked, categoric, mixture, REML), ``glm_result`` (:class:`GLMResult`) and ``gp_result``
(:class:`GPResult`); each answers the prediction contract (:mod:`rsm_lrg.model.contract`).
"""
