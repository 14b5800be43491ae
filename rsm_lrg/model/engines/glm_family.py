"""Families and links of a generalised linear model (:mod:`rsm_lrg.model.pipelines.glm`).

A :class:`Family` is a distribution of the response (``binomial``: a proportion of ``m``
trials, ``m = 1`` for a 0/1 response; ``poisson``: a count) with one link ``g`` between the
mean ``mu`` and the linear predictor ``eta = g(mu)``. The formulas, and the bounds that keep
``mu`` inside its range, are those of R's ``binomial()``, ``poisson()`` and ``make.link()``
(``stats/R/family.R``, ``src/library/stats/src/family.c``), so that a fit equals R's ``glm``
to the last digits.

=========  =====================================  ==================================
family     links (the first is the default)       variance ``V(mu)``
=========  =====================================  ==================================
binomial   ``logit``, ``probit``, ``cloglog``     ``mu (1 - mu)`` (per trial)
poisson    ``log``                                ``mu``
=========  =====================================  ==================================

>>> f = family("binomial", "logit")
>>> float(f.linkinv(f.linkfun(0.25)))
0.25
>>> family("poisson").link
'log'
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import ParameterError

__all__ = ["Family", "family", "FAMILIES", "LINKS"]

#: The links each family takes; the first is its canonical (default) link.
FAMILIES: dict[str, tuple[str, ...]] = {"binomial": ("logit", "probit", "cloglog"), "poisson": ("log",)}
#: Every link named by some family.
LINKS: tuple[str, ...] = ("logit", "probit", "cloglog", "log")

EPS = float(np.finfo(float).eps)
#: R's ``binomial()$linkinv`` for the logit: beyond ``|eta| > 30`` mu is held at ``eps / (1 + eps)`` and ``1 / (1 + eps)``.
LOGIT_BOUND = 30.0
#: R's probit bound: ``-qnorm(DBL_EPSILON)``.
PROBIT_BOUND = 8.125890664701906


def _ndtr(x: np.ndarray) -> np.ndarray:
    from scipy.special import ndtr

    return np.asarray(ndtr(x), dtype=float)


def _ndtri(p: np.ndarray) -> np.ndarray:
    from scipy.special import ndtri

    return np.asarray(ndtri(p), dtype=float)


@dataclass(frozen=True)
class Family:
    """A response distribution with its link (frozen; build it with :func:`family`).

    Attributes
    ----------
    name : str
        ``"binomial"`` or ``"poisson"``.
    link : str
        ``"logit"``, ``"probit"``, ``"cloglog"`` (binomial) or ``"log"`` (poisson).
    """

    name: str
    link: str

    # -- the link ----------------------------------------------------------------------
    def linkfun(self, mu: np.ndarray) -> np.ndarray:
        """``eta = g(mu)``."""
        mu = np.asarray(mu, dtype=float)
        if self.link == "logit":
            return np.log(mu / (1.0 - mu))
        if self.link == "probit":
            return _ndtri(mu)
        if self.link == "cloglog":
            return np.log(-np.log1p(-mu))
        return np.log(mu)

    def linkinv(self, eta: np.ndarray) -> np.ndarray:
        """``mu = g^-1(eta)``, held inside the family's range as R holds it."""
        eta = np.asarray(eta, dtype=float)
        if self.link == "logit":
            with np.errstate(over="ignore"):
                e = np.exp(-np.abs(eta))
                mu = np.where(eta >= 0, 1.0 / (1.0 + e), e / (1.0 + e))
            return np.where(eta < -LOGIT_BOUND, EPS / (1.0 + EPS), np.where(eta > LOGIT_BOUND, 1.0 / (1.0 + EPS), mu))
        if self.link == "probit":
            return _ndtr(np.clip(eta, -PROBIT_BOUND, PROBIT_BOUND))
        if self.link == "cloglog":
            with np.errstate(over="ignore"):
                return np.clip(-np.expm1(-np.exp(eta)), EPS, 1.0 - EPS)
        with np.errstate(over="ignore"):
            return np.maximum(np.exp(eta), EPS)

    def mu_eta(self, eta: np.ndarray) -> np.ndarray:
        """``d mu / d eta`` (at least eps, as R holds it)."""
        eta = np.asarray(eta, dtype=float)
        if self.link == "logit":
            with np.errstate(over="ignore"):
                e = np.exp(-np.abs(eta))
                d = e / (1.0 + e) ** 2
            return np.where(np.abs(eta) > LOGIT_BOUND, EPS, d)
        if self.link == "probit":
            return np.maximum(np.exp(-0.5 * eta * eta) / math.sqrt(2.0 * math.pi), EPS)
        if self.link == "cloglog":
            e = np.minimum(eta, 700.0)
            with np.errstate(over="ignore"):
                return np.maximum(np.exp(e) * np.exp(-np.exp(e)), EPS)
        with np.errstate(over="ignore"):
            return np.maximum(np.exp(eta), EPS)

    # -- the distribution ----------------------------------------------------------------
    def variance(self, mu: np.ndarray) -> np.ndarray:
        """``V(mu)``: ``mu (1 - mu)`` per trial (binomial), ``mu`` (poisson)."""
        mu = np.asarray(mu, dtype=float)
        return mu * (1.0 - mu) if self.name == "binomial" else mu

    def unit_deviance(self, y: np.ndarray, mu: np.ndarray, m: np.ndarray) -> np.ndarray:
        """Each run's deviance contribution ``d_i`` (the residual deviance is their sum);
        ``y`` a proportion of ``m`` trials (binomial) or a count (poisson, ``m`` ignored)."""
        from scipy.special import xlogy

        y, mu = np.asarray(y, dtype=float), np.asarray(mu, dtype=float)
        if self.name == "binomial":
            return 2.0 * m * (xlogy(y, y / mu) + xlogy(1.0 - y, (1.0 - y) / (1.0 - mu)))
        return 2.0 * (xlogy(y, y / mu) - (y - mu))

    def log_likelihood(self, y: np.ndarray, mu: np.ndarray, m: np.ndarray) -> float:
        """The log-likelihood with every constant (R's ``logLik`` of a ``glm``): binomial
        ``sum log C(m, s) + s log mu + (m - s) log(1 - mu)`` with ``s = m y``; poisson
        ``sum y log mu - mu - log y!``."""
        from scipy.special import gammaln, xlog1py, xlogy

        y, mu = np.asarray(y, dtype=float), np.asarray(mu, dtype=float)
        if self.name == "binomial":
            s = np.round(m * y)
            mm = np.round(m)
            return float(np.sum(gammaln(mm + 1.0) - gammaln(s + 1.0) - gammaln(mm - s + 1.0)
                                + xlogy(s, mu) + xlog1py(mm - s, -mu)))
        return float(np.sum(xlogy(y, mu) - mu - gammaln(y + 1.0)))

    def start(self, y: np.ndarray, m: np.ndarray) -> np.ndarray:
        """R's ``mustart``: ``(m y + 0.5) / (m + 1)`` (binomial), ``y + 0.1`` (poisson)."""
        return (m * y + 0.5) / (m + 1.0) if self.name == "binomial" else y + 0.1

    @property
    def label(self) -> str:
        """``"binomial (logit link)"``."""
        return f"{self.name} ({self.link} link)"

    @property
    def mean_name(self) -> str:
        """What the response-scale prediction is: ``"probability"`` or ``"mean count"``."""
        return "probability" if self.name == "binomial" else "mean count"


def family(name: str | Family, link: str | None = None) -> Family:
    """The family ``name`` with ``link`` (its canonical link when ``None``).

    Raises
    ------
    ParameterError
        An unknown family (``parameter="family"``) or a link the family does not take
        (``parameter="link"``), with the choices in the sentence.
    """
    if isinstance(name, Family):
        if link is not None and link != name.link:
            raise ParameterError("link", f"link {link!r} given with a Family whose link is {name.link!r}")
        return name
    key = str(name).strip().lower()
    if key not in FAMILIES:
        raise ParameterError("family", f"family must be one of {', '.join(FAMILIES)}, not {name!r}")
    links = FAMILIES[key]
    if link is None:
        return Family(key, links[0])
    lk = str(link).strip().lower()
    if lk not in links:
        if lk in LINKS:
            raise ParameterError("link", f"the {key} family takes the link{'s' if len(links) > 1 else ''} "
                                         f"{', '.join(links)}, not {link!r}")
        raise ParameterError("link", f"link must be one of {', '.join(LINKS)}, not {link!r}")
    return Family(key, lk)
