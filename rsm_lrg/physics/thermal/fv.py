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

Steady state: sparse direct solve (SuperLU), Jacobi-preconditioned conjugate gradients, or
conjugate gradients preconditioned by one V-cycle of classical (Ruge-Stueben) algebraic
multigrid (``method="amg"``, optional package ``pyamg``).
Transient: backward Euler or Crank-Nicolson with a constant step; the set-up of the system
matrix ``A = C/dt + K`` (or ``C/dt + K/2``) is done ONCE and reused by every step:

* ``solver="direct"``: ``A`` is factorised once with ``scipy.sparse.linalg.splu`` and every
  step is two triangular solves (cheapest for small grids, but the fill of a 3-D LU grows
  much faster than the number of cells);
* ``solver="amg"``: the multigrid hierarchy of ``A`` is built once and every step is a few
  AMG-preconditioned CG iterations warm-started from the previous step (cost ~ linear in
  the number of cells).
* ``solver="auto"`` (default) picks ``"direct"`` up to :data:`AUTO_AMG_CELLS` cells and
  ``"amg"`` above (measured cross-over, ``benchmarks/bench_thermal.py``); without pyamg it
  stays direct and says so in ``info["fallback"]``.

Why AMG applies: ``K`` is a symmetric, irreducibly diagonally dominant matrix with positive
diagonal and non-positive off-diagonal entries (conductances between cells, Robin terms
``G_conv`` added to the diagonal), i.e. a non-singular M-matrix and therefore symmetric
positive definite (Varga, *Matrix Iterative Analysis*, 2nd ed., Cor. 3.20; Saad, 2nd ed.,
Thm. 1.29 / Sec. 1.10); ``C/dt`` only adds a positive diagonal. :meth:`FVSystem.check_spd`
verifies these conditions. Classical AMG is built for exactly this class of matrices
(Ruge & Stueben, "Algebraic multigrid", in *Multigrid Methods*, SIAM 1987; Stueben,
J. Comput. Appl. Math. 128 (2001) 281-309).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .geometry import VoxelModel

__all__ = [
    "AUTO_AMG_CELLS", "AMGSolver", "FVSystem", "SteadyResult", "TransientResult", "have_pyamg",
    "time_to_fraction",
]

#: Cell count above which ``method="auto"`` / ``solver="auto"`` switch from the sparse
#: direct path to AMG-preconditioned CG. Cross-over measured with
#: ``benchmarks/bench_thermal.py`` on the quarter guide (2 shared cores): a 5-h transient
#: (300 steps) takes 3.2 s direct vs 4.8 s AMG at 18,114 cells and 36 s vs 18 s at 46,219;
#: the steady solve is already cheaper with AMG above ~5,000 cells (0.16 s vs 0.07 s at
#: 10,816), but the direct path is instant there either way. Growth (10^4..8.6x10^5 cells):
#: AMG ~cells^1.1-1.2, direct LU ~cells^1.9-2.4.
AUTO_AMG_CELLS = 20_000


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


def have_pyamg() -> bool:
    """True if the optional package ``pyamg`` (needed by ``method="amg"``) is importable."""
    try:
        import pyamg  # noqa: F401
    except ImportError:
        return False
    return True


def _require_pyamg():
    try:
        import pyamg
    except ImportError as exc:
        raise ImportError(
            "the 'amg' solver needs the optional package pyamg (pip install pyamg, or "
            "pip install 'rsm-lrg[all]'); without it use method/solver 'direct' (or 'cg')."
        ) from exc
    return pyamg


def _dot(a, b) -> float:
    # Plain NumPy reduction instead of BLAS ddot: multithreaded BLAS on short vectors
    # oversubscribes a loaded machine (measured 2-7x slower solves on 2 shared cores).
    return float(np.add.reduce(a * b))


class AMGSolver:
    """CG preconditioned by one classical AMG V-cycle, for a fixed SPD M-matrix ``A``.

    The hierarchy (Ruge-Stueben coarsening, classical strength of connection theta = 0.25,
    classical interpolation, one forward Gauss-Seidel sweep before and one backward sweep
    after the coarse-grid correction, ``R = P^T``, sparse LU on the coarsest level;
    ``pyamg.ruge_stuben_solver``) is built once in the constructor; :meth:`solve` can then
    be called any number of times. With the post-smoother the adjoint of the pre-smoother
    and ``R = P^T`` the V-cycle is a symmetric positive-definite operator, so it is a valid
    CG preconditioner (Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed.,
    Alg. 9.1 and Sec. 13.4; Stueben 2001). Measured on the quarter guide at 1.2e5 cells:
    forward/backward sweeps cost 22 ms per V-cycle against 34 ms for symmetric sweeps on
    both sides, for 13-14 instead of 11-12 CG iterations.

    Parameters
    ----------
    A : sparse matrix
        Symmetric positive-definite system matrix (n x n) [W/K].
    max_coarse : int
        Largest coarsest-level size, solved by sparse LU.

    Attributes
    ----------
    setup_s : float
        Wall-clock time of the hierarchy set-up [s].
    levels : int
        Number of multigrid levels.
    operator_complexity : float
        Sum of nnz over levels / nnz(A).
    """

    def __init__(self, A, *, max_coarse: int = 500):
        pyamg = _require_pyamg()
        t0 = time.perf_counter()
        self.A = sp.csr_matrix(A, dtype=float)
        self.n = self.A.shape[0]
        if self.n <= max_coarse:
            # too small for a hierarchy: one exact LU "cycle" (CG then stops after 1 step)
            self._ml = None
            self._lu = _factorise(self.A)
            self.levels = 1
            self.operator_complexity = 1.0
        else:
            self._ml = pyamg.ruge_stuben_solver(
                self.A, strength=("classical", {"theta": 0.25}), max_coarse=max_coarse,
                coarse_solver="splu",
                presmoother=("gauss_seidel", {"sweep": "forward"}),
                postsmoother=("gauss_seidel", {"sweep": "backward"}),
            )
            self.levels = len(self._ml.levels)
            self.operator_complexity = float(self._ml.operator_complexity())
            if self.levels < 2:  # pyamg could not coarsen: fall back to one exact LU
                self._ml = None
                self._lu = _factorise(self.A)
        self.setup_s = time.perf_counter() - t0

    def _cycle(self, lvl, b):
        """One V-cycle for ``A_lvl x = b`` from ``x = 0`` (the algorithm of
        ``pyamg.MultilevelSolver`` without its per-cycle residual norms)."""
        levels = self._ml.levels
        A = levels[lvl].A
        x = np.zeros_like(b)
        levels[lvl].presmoother(A, x, b)
        coarse_b = levels[lvl].R @ (b - A @ x)
        if lvl == len(levels) - 2:
            coarse_x = self._ml.coarse_solver(levels[-1].A, coarse_b)
        else:
            coarse_x = self._cycle(lvl + 1, coarse_b)
        x += levels[lvl].P @ coarse_x
        levels[lvl].postsmoother(A, x, b)
        return x

    def precondition(self, r):
        """Approximate ``A^-1 r`` by one V-cycle."""
        if self._ml is None:
            return self._lu.solve(r)
        return self._cycle(0, r)

    def solve(self, b, *, x0=None, rtol: float = 1e-10, maxiter: int = 500):
        """Solve ``A x = b`` to ``||b - A x||_2 <= rtol ||b||_2``; returns ``(x, iterations)``.

        ``x0`` is the initial guess (warm start); 0 iterations if it already satisfies the
        tolerance. Raises ``RuntimeError`` if ``maxiter`` iterations do not suffice.
        """
        A = self.A
        b = np.asarray(b, float)
        bn = math.sqrt(_dot(b, b))
        if bn == 0:
            return np.zeros_like(b), 0
        if x0 is None:
            x = np.zeros_like(b)
            r = b.copy()
        else:
            x = np.array(x0, float)
            r = b - A @ x
        tol = rtol * bn
        if math.sqrt(_dot(r, r)) <= tol:
            return x, 0
        z = self.precondition(r)
        p = z.copy()
        rz = _dot(r, z)
        for k in range(1, maxiter + 1):
            Ap = A @ p
            alpha = rz / _dot(p, Ap)
            x += alpha * p
            r -= alpha * Ap
            if math.sqrt(_dot(r, r)) <= tol:
                return x, k
            z = self.precondition(r)
            rz_new = _dot(r, z)
            p = z + (rz_new / rz) * p
            rz = rz_new
        raise RuntimeError(f"AMG-preconditioned CG did not converge in {maxiter} iterations.")


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
    setups : dict
        How many sparse LU factorisations (``"lu"``) and AMG hierarchies (``"amg"``) this
        system has built so far (the steady solve caches its own; every transient builds
        exactly one).
    """

    def __init__(self, model: VoxelModel):
        self.model = model
        self._assemble()
        self._lu: Any = None  # scipy's SuperLU (untyped), built on the first direct solve
        self._amg: AMGSolver | None = None
        self.setups = {"lu": 0, "amg": 0}

    def _new_lu(self, A):
        self.setups["lu"] += 1
        return _factorise(A)

    def _new_amg(self, A):
        self.setups["amg"] += 1
        return AMGSolver(A)

    def _pick(self, choice: str, what: str, allowed: tuple) -> tuple[str, str | None]:
        """Resolve ``"auto"`` to ``"direct"`` or ``"amg"`` (see :data:`AUTO_AMG_CELLS`)."""
        if choice not in allowed:
            raise ValueError(f"{what} must be one of {', '.join(map(repr, allowed))}, got {choice!r}.")
        if choice != "auto":
            return choice, None
        if self.n <= AUTO_AMG_CELLS:
            return "direct", None
        if have_pyamg():
            return "amg", None
        msg = (f"{self.n} cells > AUTO_AMG_CELLS = {AUTO_AMG_CELLS} but pyamg is not installed: "
               "using the sparse direct solver (slow and memory-hungry on big grids).")
        warnings.warn(msg, RuntimeWarning, stacklevel=3)
        return "direct", msg

    def check_spd(self) -> dict:
        """Verify that ``K`` is a non-singular symmetric M-matrix, hence SPD (module docstring).

        Checks, in O(nnz): symmetry, positive diagonal, non-positive off-diagonal entries,
        weak diagonal dominance of every row, and that every connected group of cells has a
        cooled face (strict dominance somewhere in each irreducible block). Raises
        ``ValueError`` naming the failed condition; returns the measured margins.
        """
        from scipy.sparse.csgraph import connected_components

        K = sp.csr_matrix(self.K)
        scale = float(abs(K).max())
        asym = float(abs(K - K.T).max()) if K.nnz else 0.0
        if asym > 1e-12 * scale:
            raise ValueError(f"K is not symmetric (max |K - K^T| = {asym:.3g} W/K).")
        d = K.diagonal()
        if np.any(d <= 0):
            raise ValueError("K has a non-positive diagonal entry.")
        off = K - sp.diags(d)
        if off.nnz and off.data.max() > 0:
            raise ValueError("K has a positive off-diagonal entry (a negative conductance).")
        excess = d + np.asarray(off.sum(axis=1)).ravel()  # = d - sum |off| = convective part
        if np.any(excess < -1e-12 * d):
            raise ValueError("K is not diagonally dominant (a row loses more than it holds).")
        n_comp, label = connected_components(off, directed=False)
        cooled = np.bincount(label, weights=self.g_conv, minlength=n_comp)
        if np.any(cooled <= 0):
            raise ValueError(
                f"{int(np.sum(cooled <= 0))} group(s) of connected cells have no cooled face: "
                "K is singular there (no steady state)."
            )
        return {"asymmetry": asym, "min_row_excess_w_k": float(excess.min()),
                "components": int(n_comp)}

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
    def steady(self, heat_w: float = 1.0, *, method: str = "auto", rtol: float = 1e-10) -> SteadyResult:
        """Steady rise ``K theta = b Q`` for the total heat ``heat_w`` [W] (Eq. 7 with dT/dt = 0).

        Parameters
        ----------
        heat_w : float
            Total heat of the whole guide [W] (Eq. 8/9).
        method : {"auto", "direct", "amg", "cg"}
            ``"direct"``: SuperLU, factorisation cached. ``"amg"``: CG preconditioned by a
            classical AMG V-cycle (needs pyamg; hierarchy cached; ~linear cost in the
            number of cells). ``"cg"``: CG with a Jacobi preconditioner (iterations grow
            like the grid's inverse spacing). ``"auto"``: ``"direct"`` up to
            :data:`AUTO_AMG_CELLS` cells, ``"amg"`` above.
        rtol : float
            Iterative methods stop at ``||b Q - K theta||_2 <= rtol ||b Q||_2``; the energy
            balance then holds to ``copies * sqrt(n) * rtol * ||b Q||_2`` [W] (the column sums
            of ``K`` are the convective conductances, so heat out - heat in = -copies * sum(r)).
        """
        if not math.isfinite(heat_w):
            raise ValueError(f"heat_w must be finite, got {heat_w!r}.")
        chosen, fallback = self._pick(method, "method", ("auto", "direct", "amg", "cg"))
        info = {"method": chosen, "n_cells": self.n}
        if fallback:
            info["fallback"] = fallback
        rhs = self.b * heat_w
        t0 = time.perf_counter()
        if chosen == "direct":
            if self._lu is None:
                self._lu = self._new_lu(self.K)
            theta = self._lu.solve(rhs)
        elif chosen == "amg":
            if self._amg is None:
                self.check_spd()
                self._amg = self._new_amg(self.K)
            t1 = time.perf_counter()
            theta, it = self._amg.solve(rhs, rtol=rtol)
            info.update(iterations=it, setup_s=self._amg.setup_s, solve_s=time.perf_counter() - t1,
                        levels=self._amg.levels, operator_complexity=self._amg.operator_complexity)
        else:
            theta, it = _pcg_jacobi(self.K, rhs, rtol, maxiter=20 * self.n)
            info["iterations"] = it
        info["elapsed_s"] = time.perf_counter() - t0
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
        solver: str = "auto",
        rtol: float = 1e-10,
    ) -> TransientResult:
        """Rise from ``theta0`` (default 0: the guide starts at ambient) under a step heat input.

        Implicit time stepping of ``C dtheta/dt + K theta = b Q`` (Eq. 7) with a constant
        step ``dt_s`` [s]. The system matrix ``A`` is set up ONCE and reused for every step:
        one LU factorisation (``solver="direct"``, ``info["factorisations"] == 1``) or one
        AMG hierarchy (``solver="amg"``, ``info["hierarchies"] == 1``); ``info["setups"]``
        is 1 either way.

        Parameters
        ----------
        heat_w : float
            Total heat [W] switched on at t = 0 (Eq. 8/9).
        duration_s, dt_s : float
            Length of the run and time step [s]; the record has one sample per step.
        scheme : {"backward-euler", "crank-nicolson"}
            ``A = C/dt + K`` or ``C/dt + K/2``.
        theta0 : array_like, optional
            Initial rise per active cell [K].
        solver : {"auto", "direct", "amg"}
            ``"auto"``: ``"direct"`` up to :data:`AUTO_AMG_CELLS` cells, ``"amg"`` above.
            The AMG path warm-starts CG from the linear extrapolation ``2 theta_k -
            theta_(k-1)`` of the last two steps.
        rtol : float
            AMG path only: each step stops at ``||rhs - A theta||_2 <= rtol ||rhs||_2``.
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
        chosen, fallback = self._pick(solver, "solver", ("auto", "direct", "amg"))
        theta = np.zeros(self.n) if theta0 is None else np.array(theta0, float)
        if theta.shape != (self.n,):
            raise ValueError(f"theta0 must have one value per active cell ({self.n}), got shape {theta.shape}.")

        t0 = time.perf_counter()
        if chosen == "direct":
            lu = self._new_lu(A)
        else:
            self.check_spd()
            amg = self._new_amg(A)
        t_setup = time.perf_counter() - t0

        rhs_src = self.b * heat_w
        times = np.arange(n_steps + 1) * dt_s
        probe = np.empty((n_steps + 1, len(self.probes)))
        tmax = np.empty(n_steps + 1)
        probe[0] = theta[self.probes]
        tmax[0] = theta.max()
        iters = []
        prev = theta
        t0 = time.perf_counter()
        for k in range(1, n_steps + 1):
            rhs = B @ theta + rhs_src
            if chosen == "direct":
                new = lu.solve(rhs)
            else:
                new, it = amg.solve(rhs, x0=2.0 * theta - prev, rtol=rtol)
                iters.append(it)
            prev, theta = theta, new
            probe[k] = theta[self.probes]
            tmax[k] = theta.max()
        t_steps = time.perf_counter() - t0
        info = {
            "scheme": scheme,
            "solver": chosen,
            "dt_s": dt_s,
            "n_steps": n_steps,
            "n_cells": self.n,
            "setups": 1,
            "setup_s": t_setup,
            "step_s": t_steps / max(n_steps, 1),
        }
        if chosen == "direct":
            info.update(factorisations=1, factorise_s=t_setup)
        else:
            info.update(factorisations=0, hierarchies=1, rtol=rtol, levels=amg.levels,
                        operator_complexity=amg.operator_complexity,
                        iterations_total=int(sum(iters)), iterations_max=int(max(iters, default=0)))
        if fallback:
            info["fallback"] = fallback
        return TransientResult(times, probe, tmax, theta, info)
