"""Estimation engines: the numerical cores behind every kind of fit.

``least_squares`` (one QR factorisation and every OLS statistic from it), ``mixed`` (REML with
a random intercept and Kenward–Roger), ``glm_family`` (families and links of a generalised
linear model), ``gp_core``, ``gp_kernels`` and ``gp_trend`` (universal kriging at given
hyper-parameters). An engine takes built inputs and returns numbers; it builds no result.
"""
