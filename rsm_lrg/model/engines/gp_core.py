"""The linear algebra of universal kriging at given hyper-parameters (the engine's core;
:mod:`rsm_lrg.model.pipelines.gp` estimates the hyper-parameters, :mod:`rsm_lrg.model.results.gp_result`
predicts from this factorisation).

The covariance of the runs is ``Sigma = sigma2 R + tau2 I`` (``R`` the kernel's correlation
matrix, :mod:`rsm_lrg.model.engines.gp_kernels`; ``tau2`` the nugget). It is factorised once by
Cholesky, ``Sigma = L L'``; when the factorisation fails (a matrix singular to working
precision) ``jitter * sigma2`` is added to the diagonal, ``jitter`` the smallest of
1e-12, 1e-11, ..., 1e-4 that succeeds, and the result says so. The trend coefficients are
the generalised least-squares ones, from a QR factorisation of ``L^-1 F``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import solve_triangular

from .gp_kernels import correlation

__all__ = ["KrigingCore", "kriging_core", "core_from_cholesky", "cholesky_jitter", "cholesky_in_place",
           "inverse_lower", "JITTERS", "POTRI_RUNS"]

#: Relative jitters tried, in order, when a Cholesky factorisation fails.
JITTERS = (0.0,) + tuple(10.0 ** e for e in range(-12, -3))


def cholesky_jitter(m: np.ndarray, scale: float) -> tuple[np.ndarray, float]:
    """Lower Cholesky factor of ``m + jitter * scale * I`` and the relative ``jitter`` used
    (0 when ``m`` itself factorises); LinAlgError when none of :data:`JITTERS` suffices."""
    n = m.shape[0]
    for jit in JITTERS:
        try:
            a = m if jit == 0.0 else m + (jit * scale) * np.eye(n)
            return np.linalg.cholesky(a), jit
        except np.linalg.LinAlgError:
            continue
    raise np.linalg.LinAlgError("the covariance matrix is not positive definite even with a jitter of 1e-4")


def cholesky_in_place(m: np.ndarray) -> np.ndarray | None:
    """The lower Cholesky factor of the symmetric C-ordered matrix ``m``, computed in ``m``'s
    own memory by LAPACK ``dpotrf`` (SciPy's), the strict upper triangle zeroed; ``None`` when
    ``m`` is not positive definite, ``m`` then overwritten (rebuild it before trying a jitter
    with :func:`cholesky_jitter`). No copy of ``m`` is made: on 2,000 runs (the benchmark's
    correlation matrix) this took 0.16 s of CPU against 0.26 s for ``numpy.linalg.cholesky``
    (one OpenBLAS thread, a copy of the matrix included in both), which copies the matrix into
    and out of Fortran order. Its factor agrees with NumPy's to rounding (about 1e-15
    here), not bit for bit: :mod:`rsm_lrg.model.pipelines.gp` uses it on all runs above
    ``MULTISTART_RUNS`` only.

    Parameters
    ----------
    m : (n, n) ndarray
        Symmetric, C-contiguous, float64; overwritten.

    Returns
    -------
    (n, n) ndarray or None
        ``m`` itself, holding ``L`` (``m = L L'`` before the call), or None.
    """
    from scipy.linalg.lapack import dpotrf

    if not (m.flags.c_contiguous and m.dtype == np.float64):
        raise ValueError("cholesky_in_place needs a C-contiguous float64 matrix")
    # m's memory read in Fortran order is m' = m: the upper factor U = L' there is L in C order
    _, info = dpotrf(m.T, lower=0, clean=1, overwrite_a=1)
    return m if info == 0 else None


#: From this many runs on, :func:`inverse_lower` inverts by LAPACK ``dpotri`` (a third of the
#: work of solving against the identity); below, by two triangular solves (the fits on fewer
#: runs keep their numbers). On 300 runs ``dpotri`` took 2.2 ms of CPU against 4.9 ms for the
#: solves on one OpenBLAS thread, 2.1 against 9.5 ms on two (the subsample's evaluations).
POTRI_RUNS = 300


def inverse_lower(chol: np.ndarray) -> np.ndarray:
    """``(L L')^-1`` from the lower Cholesky factor ``L``: from :data:`POTRI_RUNS` runs on by
    LAPACK ``dpotri``, which fills only the lower triangle; below, solved against the identity.

    Parameters
    ----------
    chol : (n, n) ndarray
        Lower Cholesky factor (C order).

    Returns
    -------
    (n, n) ndarray
        The inverse's lower triangle (the strict upper triangle is not defined).
    """
    from scipy.linalg import cho_solve
    from scipy.linalg.lapack import dpotri

    if chol.shape[0] < POTRI_RUNS:
        return cho_solve((chol, True), np.eye(chol.shape[0]), check_finite=False)
    # L (C order) is U = L' in Fortran order: dpotri on the upper factor, read back transposed
    inv, info = dpotri(chol.T, lower=0)
    if info != 0:
        raise np.linalg.LinAlgError(f"dpotri failed (info {info})")
    return np.asarray(inv).T


@dataclass(frozen=True)
class KrigingCore:
    """Universal kriging at fixed hyper-parameters.

    Attributes
    ----------
    chol : (n, n) ndarray
        Lower Cholesky factor ``L`` of ``Sigma`` (+ jitter).
    jitter : float
        Relative jitter added to the diagonal (``jitter * sigma2``); 0 when none.
    beta : (p,) ndarray
        GLS trend coefficients.
    alpha : (n,) ndarray
        ``Sigma^-1 (y - F beta)``.
    ft : (n, p) ndarray
        ``L^-1 F``.
    r_f : (p, p) ndarray
        Upper-triangular factor of ``ft`` (``F' Sigma^-1 F = r_f' r_f``).
    quad : float
        ``(y - F beta)' Sigma^-1 (y - F beta)``.
    logdet : float
        ``log det Sigma``.
    """

    chol: np.ndarray
    jitter: float
    beta: np.ndarray
    alpha: np.ndarray
    ft: np.ndarray
    r_f: np.ndarray
    quad: float
    logdet: float

    def scaled(self, s: float) -> KrigingCore:
        """The factorisation of ``s Sigma`` (``s > 0``) from this one, in O(n²) instead of a
        new Cholesky factorisation: ``L`` and ``L^-1 F`` scaled by ``sqrt(s)`` and
        ``1/sqrt(s)``, ``alpha`` and ``quad`` divided by ``s``, ``log det`` raised by
        ``n log s``; the trend coefficients and the relative jitter unchanged.

        Parameters
        ----------
        s : float
            Positive multiplier of the covariance [-].

        Returns
        -------
        KrigingCore
        """
        root = float(np.sqrt(s))
        return KrigingCore(chol=self.chol * root, jitter=self.jitter, beta=self.beta, alpha=self.alpha / s,
                           ft=self.ft / root, r_f=self.r_f / root, quad=self.quad / s,
                           logdet=self.logdet + self.alpha.size * float(np.log(s)))

    @property
    def log_likelihood(self) -> float:
        """``-(n log 2 pi + log det Sigma + quad) / 2``: at the maximum-likelihood variance
        this is the concentrated log-likelihood (DiceKriging's ``logLik``)."""
        n = self.alpha.size
        return float(-0.5 * (n * np.log(2.0 * np.pi) + self.logdet + self.quad))


def gls(chol: np.ndarray, F: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``beta``, ``ft = L^-1 F``, ``r_f`` and the whitened residual ``L^-1 (y - F beta)``;
    ValueError when the trend's columns are aliased on these runs."""
    ft = solve_triangular(chol, F, lower=True, check_finite=False)
    yt = solve_triangular(chol, y, lower=True, check_finite=False)
    q, r_f = np.linalg.qr(ft)
    d = np.abs(np.diag(r_f))
    if d.size and not d.min() > 1e-10 * max(d.max(), 1e-300):
        raise ValueError("the trend's columns are aliased on these runs (too few distinct settings for this trend)")
    beta = solve_triangular(r_f, q.T @ yt, lower=False, check_finite=False)
    return beta, ft, r_f, yt - ft @ beta


def kriging_core(x: np.ndarray, y: np.ndarray, F: np.ndarray, kernel: str, theta: np.ndarray, variance: float,
                 nugget: float) -> KrigingCore:
    """Factorise ``Sigma = variance R + nugget I`` at the runs ``x`` [coded] and solve the
    GLS trend (see the module docstring)."""
    R = correlation(x, x, theta, kernel)
    sigma = variance * R
    sigma[np.diag_indices_from(sigma)] += nugget
    chol, jit = cholesky_jitter(sigma, variance)
    return core_from_cholesky(chol, jit, F, y)


def core_from_cholesky(chol: np.ndarray, jitter: float, F: np.ndarray, y: np.ndarray) -> KrigingCore:
    """The kriging core from a Cholesky factor already computed (as :func:`kriging_core` computes
    it: ``cholesky_jitter(variance R + nugget I, variance)``): the GLS trend and the weights.

    Parameters
    ----------
    chol : (n, n) ndarray
        Lower Cholesky factor of ``Sigma`` (+ jitter).
    jitter : float
        Relative jitter in ``chol``.
    F : (n, p) ndarray
        Trend matrix.
    y : (n,) ndarray
        Responses.

    Returns
    -------
    KrigingCore
    """
    beta, ft, r_f, z = gls(chol, F, y)
    alpha = solve_triangular(chol, z, lower=True, trans="T", check_finite=False)
    return KrigingCore(chol=chol, jitter=jitter, beta=beta, alpha=alpha, ft=ft, r_f=r_f, quad=float(z @ z),
                       logdet=float(2.0 * np.sum(np.log(np.diag(chol)))))
