"""Three-dimensional finite-volume solution of the heat-conduction equation (paper Eq. 7).

``rho c dT/dt = div(lambda grad T) + Phi``  on the solid cells of a :class:`VoxelModel`,
with Newton cooling (Eq. 4) ``q = h (T_s - T_inf)`` on every face that looks onto ambient
and the source ``Phi = Q / V`` (Eq. 9) in the source cells.

Discretisation (cell-centred finite volumes on a tensor-product grid; Patankar, *Numerical
Heat Transfer and Fluid Flow*, 1980, Sections 4.2-4.3; Incropera et al., *Fundamentals of
Heat and Mass Transfer*, 6th ed., Section 4.4 "finite-difference equations" for the energy
balance per node):

* interior face between cells P and N: ``G = A / (dx_P / (2 lambda_P) + dx_N / (2 lambda_N))``
  (series resistances of the two half cells: the harmonic mean of the conductivities),
* exposed face: ``G = A / (dx_P / (2 lambda_P) + 1 / h)`` to ambient,
* the unknown is the temperature rise ``theta = T - T_inf``, so ``K theta = b Q`` in steady
  state and ``C dtheta/dt + K theta = b Q`` in time, with ``K`` symmetric positive definite.

Steady state: sparse direct solve (SuperLU) or preconditioned conjugate gradients.
Transient: backward Euler or Crank-Nicolson with a constant step; ``C/dt + K`` (or
``C/dt + K/2``) is factorised ONCE with ``scipy.sparse.linalg.splu`` and every step is two
triangular solves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .geometry import VoxelModel

__all__ = ["FVSystem", "assemble", "SteadyResult", "TransientResult", "time_to_fraction"]


@dataclass(frozen=True)
class SteadyResult:
    """Steady temperature rise of every solid cell for a heat input ``heat_w`` [W]."""

    heat_w: float
    theta_k: np.ndarray  # rise per active cell [K]
    probe_rise_k: np.ndarray  # rise at each probe [K]
    max_rise_k: float
    heat_out_w: float  # convected to ambient [W]
    info: dict

    @property
    def mean_probe_rise_k(self) -> float:
        """Mean of the probes (the paper averages its two thermocouples, Section 4.1)."""
        return float(np.mean(self.probe_rise_k))

    @property
    def energy_balance_error(self) -> float:
        """(heat out - heat in) / heat in (0 to solver precision)."""
        return (self.heat_out_w - self.heat_w) / self.heat_w if self.heat_w else 0.0


@dataclass(frozen=True)
class TransientResult:
    """Temperature rise at the probes (and its maximum over all cells) against time."""

    times_s: np.ndarray
    probe_rise_k: np.ndarray  # shape (n_times, n_probes)
    max_rise_k: np.ndarray  # shape (n_times,)
    theta_final_k: np.ndarray
    info: dict

    @property
    def mean_probe_rise_k(self) -> np.ndarray:
        return self.probe_rise_k.mean(axis=1)


def time_to_fraction(times_s, history, final, fraction=0.95) -> float:
    """First time [s] at which ``history`` reaches ``fraction * final`` (linear interpolation).

    Returns ``nan`` if it never does within the record.
    """
    t = np.asarray(times_s, float)
    y = np.asarray(history, float)
    target = fraction * final
    above = np.nonzero(y >= target)[0]
    if final <= 0 or len(above) == 0:
        return float("nan")
    i = above[0]
    if i == 0:
        return float(t[0])
    t0, t1, y0, y1 = t[i - 1], t[i], y[i - 1], y[i]
    return float(t0 + (target - y0) * (t1 - t0) / (y1 - y0))


def _factorise(A):
    """Sparse LU of a symmetric positive-definite matrix (SuperLU, symmetric mode).

    Minimum-degree ordering on A + A^T with no pivoting: the fill of a symmetric ordering,
    about half of the default COLAMD's on these 3-D grids.
    """
    return spla.splu(
        sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
        options={"SymmetricMode": True},
    )


def _pcg_jacobi(A, b, rtol, maxiter):
    """Conjugate gradients with a Jacobi preconditioner (Saad, *Iterative Methods for Sparse
    Linear Systems*, 2nd ed., Algorithm 9.1); stops at ||r|| <= rtol ||b||."""
    A = sp.csr_matrix(A)
    dinv = 1.0 / A.diagonal()
    x = np.zeros_like(b)
    r = b.copy()
    z = dinv * r
    p = z.copy()
    rz = r @ z
    bn = np.linalg.norm(b)
    if bn == 0:
        return x, 0
    for k in range(1, maxiter + 1):
        Ap = A @ p
        alpha = rz / (p @ Ap)
        x += alpha * p
        r -= alpha * Ap
        if np.linalg.norm(r) <= rtol * bn:
            return x, k
        z = dinv * r
        rz_new = r @ z
        p = z + (rz_new / rz) * p
        rz = rz_new
    raise RuntimeError(f"conjugate gradients did not converge in {maxiter} iterations.")


class FVSystem:
    """Assembled finite-volume system of one :class:`VoxelModel` (see module docstring).

    Attributes
    ----------
    K : scipy.sparse.csc_matrix
        Conductance matrix [W/K] (n x n), including the convective faces on its diagonal.
    C : ndarray
        Heat capacity per cell [J/K].
    b : ndarray
        Source distribution per watt (sums to 1).
    g_conv : ndarray
        Convective conductance of each cell to ambient [W/K] (sum over its exposed faces).
    copies : int
        Mirror copies of the grid in the whole guide (4 for the symmetric quarter); ``b``
        is per watt of the whole guide, so it sums to ``1 / copies``.
    probes : ndarray of int
        Active-cell index of each probe.
    """

    def __init__(self, model: VoxelModel):
        self.model = model
        self._assemble()
        self._lu = None

    # -------------------------------------------------------------------------- assembly
    def _assemble(self):
        m = self.model
        body = m.body
        nx, ny, nz = body.shape
        active = body > 0
        n = int(active.sum())
        if n == 0:
            raise ValueError("the voxel model has no solid cells.")
        index = np.full(body.shape, -1, dtype=np.int64)
        index[active] = np.arange(n)
        dx, dy, dz = np.diff(m.x_edges), np.diff(m.y_edges), np.diff(m.z_edges)
        if min(dx.min(), dy.min(), dz.min()) <= 0:
            raise ValueError("cell edges must increase strictly along every axis.")
        lam = m.lam[body]
        if np.any(lam[active] <= 0):
            raise ValueError("every solid body needs a positive conductivity.")
        vol = dx[:, None, None] * dy[None, :, None] * dz[None, None, :]
        cap = (m.rho * m.cp)[body] * vol
        sizes = (dx[:, None, None], dy[None, :, None], dz[None, None, :])
        areas = (
            dy[None, :, None] * dz[None, None, :],
            dx[:, None, None] * dz[None, None, :],
            dx[:, None, None] * dy[None, :, None],
        )
        rows, cols, vals = [], [], []
        diag = np.zeros(n)
        g_conv = np.zeros(n)
        # half-cell resistance per unit area, per axis: dx/(2 lambda)
        for ax in range(3):
            half = np.broadcast_to(sizes[ax], body.shape) / (2.0 * np.where(active, lam, 1.0))
            area = np.broadcast_to(areas[ax], body.shape)
            lo = [slice(None)] * 3
            hi = [slice(None)] * 3
            lo[ax] = slice(0, -1)
            hi[ax] = slice(1, None)
            lo, hi = tuple(lo), tuple(hi)
            # interior faces between two solid cells
            both = active[lo] & active[hi]
            G = area[lo][both] / (half[lo][both] + half[hi][both])
            i, j = index[lo][both], index[hi][both]
            rows += [i, j]
            cols += [j, i]
            vals += [-G, -G]
            np.add.at(diag, i, G)
            np.add.at(diag, j, G)
            # exposed faces: the neighbour in direction (-, +) is ambient or outside the grid
            for side, direction in ((0, 2 * ax), (1, 2 * ax + 1)):
                nb_amb = np.ones(body.shape, dtype=bool)
                if side == 0:
                    nb_amb[hi] = ~active[lo]
                else:
                    nb_amb[lo] = ~active[hi]
                face = active & nb_amb
                if direction in m.mirror_faces:  # symmetry plane on the domain border
                    border = [slice(None)] * 3
                    border[ax] = 0 if side == 0 else -1
                    face[tuple(border)] = False
                hval = m.h_table[body[face], direction]
                ok = hval > 0
                Gc = np.zeros(hval.shape)
                Gc[ok] = area[face][ok] / (half[face][ok] + 1.0 / hval[ok])
                idx = index[face]
                np.add.at(diag, idx, Gc)
                np.add.at(g_conv, idx, Gc)
        rows.append(np.arange(n))
        cols.append(np.arange(n))
        vals.append(diag)
        K = sp.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n)
        )
        src = (body == m.source_body)
        if not src.any():
            raise ValueError("the voxel model has no source cells.")
        b = np.zeros(n)
        # per watt of the WHOLE guide: the grid holds 1/copies of it
        self.copies = m.copies
        b[index[src]] = vol[src] / vol[src].sum() / self.copies
        if g_conv.sum() <= 0:
            raise ValueError("no face of the model is cooled (all h = 0): there is no steady state.")
        self.n = n
        self.K = K
        self.C = cap[active].astype(float)
        self.b = b
        self.g_conv = g_conv
        self.index = index
        self.volume = vol[active]
        self.body_of_cell = body[active]
        self.probes = np.array([index[m.cell_index(p)] for p in m.probes], dtype=np.int64)
        if np.any(self.probes < 0):
            raise ValueError("a probe point lies in an ambient (non-solid) cell.")

    # --------------------------------------------------------------------------- steady
    def steady(self, heat_w: float = 1.0, *, method: str = "direct", rtol: float = 1e-10) -> SteadyResult:
        """Steady rise ``K theta = b Q`` for the total heat ``heat_w`` [W] (Eq. 7 with dT/dt = 0).

        ``method``: ``"direct"`` (SuperLU, factorisation cached) or ``"cg"`` (conjugate
        gradients with a Jacobi preconditioner, for large grids).
        """
        if not math.isfinite(heat_w):
            raise ValueError(f"heat_w must be finite, got {heat_w!r}.")
        info = {"method": method, "n_cells": self.n}
        rhs = self.b * heat_w
        if method == "direct":
            if self._lu is None:
                self._lu = _factorise(self.K)
            theta = self._lu.solve(rhs)
        elif method == "cg":
            theta, it = _pcg_jacobi(self.K, rhs, rtol, maxiter=20 * self.n)
            iters = [it]
            info["iterations"] = iters[0]
        else:
            raise ValueError(f"method must be 'direct' or 'cg', got {method!r}.")
        heat_out = float(self.g_conv @ theta) * self.copies
        return SteadyResult(
            heat_w=float(heat_w),
            theta_k=theta,
            probe_rise_k=theta[self.probes],
            max_rise_k=float(theta.max()) if heat_w >= 0 else float(theta.min()),
            heat_out_w=heat_out,
            info=info,
        )

    # ------------------------------------------------------------------------ transient
    def transient(
        self,
        heat_w: float = 1.0,
        *,
        duration_s: float = 6 * 3600.0,
        dt_s: float = 60.0,
        scheme: str = "backward-euler",
        theta0=None,
    ) -> TransientResult:
        """Rise from ``theta0`` (default 0: the guide starts at ambient) under a step heat input.

        Implicit time stepping with a constant step ``dt_s`` [s]; the system matrix is
        factorised once and reused for every step (``info["factorisations"] == 1``).

        Parameters
        ----------
        heat_w : float
            Total heat [W] switched on at t = 0 (Eq. 8/9).
        duration_s, dt_s : float
            Length of the run and time step [s]; the record has one sample per step.
        scheme : {"backward-euler", "crank-nicolson"}
        """
        if not (math.isfinite(duration_s) and duration_s > 0):
            raise ValueError(f"duration_s must be positive, got {duration_s!r}.")
        if not (math.isfinite(dt_s) and 0 < dt_s <= duration_s):
            raise ValueError(f"dt_s must be in (0, duration_s], got {dt_s!r}.")
        n_steps = int(round(duration_s / dt_s))
        if abs(n_steps * dt_s - duration_s) > 1e-9 * duration_s:
            raise ValueError("duration_s must be a whole number of time steps dt_s.")
        Cdt = sp.diags(self.C / dt_s)
        if scheme == "backward-euler":
            A = (Cdt + self.K).tocsc()
            B = Cdt
        elif scheme == "crank-nicolson":
            A = (Cdt + 0.5 * self.K).tocsc()
            B = (Cdt - 0.5 * self.K).tocsr()
        else:
            raise ValueError(f"scheme must be 'backward-euler' or 'crank-nicolson', got {scheme!r}.")
        import time as _time

        t0 = _time.perf_counter()
        lu = _factorise(A)
        t_fact = _time.perf_counter() - t0
        theta = np.zeros(self.n) if theta0 is None else np.array(theta0, float)
        rhs_src = self.b * heat_w
        times = np.arange(n_steps + 1) * dt_s
        probe = np.empty((n_steps + 1, len(self.probes)))
        tmax = np.empty(n_steps + 1)
        probe[0] = theta[self.probes]
        tmax[0] = theta.max()
        t0 = _time.perf_counter()
        for k in range(1, n_steps + 1):
            theta = lu.solve(B @ theta + rhs_src)
            probe[k] = theta[self.probes]
            tmax[k] = theta.max()
        t_steps = _time.perf_counter() - t0
        info = {
            "scheme": scheme,
            "dt_s": dt_s,
            "n_steps": n_steps,
            "n_cells": self.n,
            "factorisations": 1,
            "factorise_s": t_fact,
            "step_s": t_steps / max(n_steps, 1),
        }
        return TransientResult(times, probe, tmax, theta, info)
