"""The design space of a mixture: the probability map on the constrained simplex and the
largest operating window as a sub-simplex (bounds per component, the total kept).

The grid is the L-pseudo simplex lattice with ``M = grid - 1`` divisions: the nodes
``x_i = L_i + R k_i / M`` (``k_i ≥ 0`` whole numbers, ``Σ k_i = M``, ``R = T - Σ L_j`` the
pseudo range, ``L_i`` the lower bounds), those with every ``x_i ≤ U_i`` forming the constrained
region; the probability at a node is the one of :mod:`rsm_lrg.optimize.design_space` (the
posterior predictive probability that every response meets its specification).

A **window** is a set of per-component bounds ``a_i ≤ k_i ≤ b_i`` (actual units
``L_i + R a_i / M ≤ x_i ≤ L_i + R b_i / M``) whose region nodes all reach the target
probability; the blends inside it keep the total, so the window is the part of the simplex
inside those bounds (a sub-simplex when only the lower bounds bind). It is grown from each of
the most probable nodes: at each step every relaxation of one bound by one grid step, and of
two bounds at once (on the simplex a single relaxation from a single blend takes in no new
node: one component can only rise if another falls), is tried, and the one taking in the most
new nodes, all at the target, is made, until none can be. The bounds reported are the
smallest and largest ``x_i`` over the window's nodes, so every bound is reached by a node, and
relaxing any one of them by one grid step either takes in a node below the target or takes
in no node of the region at all (then the other bounds hold it). The window with the most
nodes wins (ties: the larger smallest probability).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from ..errors import ParameterError

__all__ = ["simplex_lattice_nodes", "mixture_window", "relaxations", "mixture_design_space_parts",
           "check_mixture_options"]


def simplex_lattice_nodes(q: int, m: int) -> np.ndarray:
    """Every ``k`` in whole numbers ``≥ 0`` with ``Σ k = m`` (``(n, q)`` int array, ``n =
    C(m + q - 1, q - 1)``), in lexicographic order."""
    out = [c for c in itertools.product(range(m + 1), repeat=q - 1) if sum(c) <= m]
    arr = np.array([list(c) + [m - sum(c)] for c in out], dtype=int)
    return arr


def _inside(nodes: np.ndarray, box: np.ndarray) -> np.ndarray:
    return np.all((nodes >= box[:, 0]) & (nodes <= box[:, 1]), axis=1)


def relaxations(q: int) -> list[tuple[tuple[int, int], ...]]:
    """The moves of the search: each ``((component, side), ...)`` with one or two bounds
    (side 0: the lower bound moves down, 1: the upper bound moves up)."""
    singles: list[tuple[tuple[int, int], ...]] = [((i, s),) for i in range(q) for s in (0, 1)]
    pairs: list[tuple[tuple[int, int], ...]] = [a + b for a, b in itertools.combinations(singles, 2)
                                                if a[0][0] != b[0][0]]
    return singles + pairs


def _grow(nodes: np.ndarray, ok: np.ndarray, start: np.ndarray, m: int) -> np.ndarray:
    q = nodes.shape[1]
    box = np.stack([start, start], axis=1).astype(int)
    member = _inside(nodes, box)
    moves = relaxations(q)
    while True:
        best_gain = 0
        best_box: np.ndarray | None = None
        best_member: np.ndarray | None = None
        for move in moves:
            cand = box.copy()
            for i, side in move:
                cand[i, side] += -1 if side == 0 else 1
            if np.any(cand[:, 0] < 0) or np.any(cand[:, 1] > m):
                continue
            inside = _inside(nodes, cand)
            new = inside & ~member
            gain = int(new.sum())
            if gain > best_gain and bool(ok[new].all()):
                best_gain, best_box, best_member = gain, cand, inside
        if best_box is None or best_member is None:
            break
        sel = nodes[best_member]  # tightened to the nodes taken in: every bound is reached by a node
        box, member = np.stack([sel.min(axis=0), sel.max(axis=0)], axis=1), best_member
    return box


def mixture_window(nodes: np.ndarray, p: np.ndarray, target: float, m: int,
                   n_starts: int = 25) -> np.ndarray | None:
    """The window (``(q, 2)`` int bounds on ``k``) grown from the ``n_starts`` most probable
    region nodes at the target (module docstring), or None when no node reaches it.

    Parameters
    ----------
    nodes : (n, q) int ndarray
        The region's lattice nodes (``Σ k = m``).
    p : (n,) ndarray
        The probability at each node [-].
    target : float
        The target probability [-].
    m : int
        The lattice divisions.
    n_starts : int
        The most probable nodes grown from.
    """
    ok = p >= target
    if not ok.any():
        return None
    idx = np.flatnonzero(ok)
    starts = idx[np.argsort(-p[idx], kind="stable")[:n_starts]]
    best, key = None, (-1, -math.inf)
    for s in starts:
        box = _grow(nodes, ok, nodes[s], m)
        inside = _inside(nodes, box)
        k = (int(inside.sum()), float(p[inside].min()))
        if k > key:
            best, key = box, k
    return best


def mixture_design_space_parts(space: Any, grid: int, target: float, prob: Callable[[np.ndarray], np.ndarray],
                               max_nodes: int) -> dict:
    """The lattice, the probability, the window and the maps of a mixture (module docstring).

    Parameters
    ----------
    space : FactorSpace
        Components only (process factors are refused by the caller).
    grid : int
        Levels per component: ``M = grid - 1`` lattice divisions of the pseudo range.
    target : float
        The target probability [-].
    prob : callable
        ``coded (n, q) -> p (n,)``: the probability of meeting every specification.
    max_nodes : int
        The most lattice nodes evaluated.

    Returns
    -------
    dict
        ``levels`` (per component, actual), ``nodes`` (region nodes, actual units), ``k``
        (their lattice indices), ``p``, ``window`` (``{name: (low, high)}`` or None),
        ``window_nodes``, ``window_min``, ``best``, ``best_p``, ``maps``, ``notes``.
    """
    comps = list(space.factors)
    q = len(comps)
    m = int(grid) - 1
    n_all = math.comb(m + q - 1, q - 1)
    if n_all > max_nodes:
        raise ParameterError("grid", f"grid {grid} in {q} components is {n_all:,} lattice nodes; at most "
                                     f"{max_nodes:,} (give a smaller grid)")
    lower = np.array([c.lower for c in comps])
    upper = np.array([c.upper for c in comps])
    r = float(comps[0].pseudo_range)
    total = float(comps[0].total)
    k_all = simplex_lattice_nodes(q, m)
    actual_all = lower + r * k_all / m
    region = np.all(actual_all <= upper + 1e-9 * max(1.0, abs(total)), axis=1)
    k = k_all[region]
    if not len(k):
        raise ParameterError("grid", f"no node of the {grid}-level lattice lies inside the components' bounds "
                                     "(give a finer grid)")
    coded = k / m
    p = np.concatenate([prob(coded[s:s + 4096]) for s in range(0, len(k), 4096)])
    ib = int(np.argmax(p))
    names = [c.name for c in comps]
    best = {n: float(v) for n, v in zip(names, lower + r * k[ib] / m)}
    box = mixture_window(k, p, target, m)
    window, wmin, wnodes = None, math.nan, 0
    if box is not None:
        inside = _inside(k, box)
        window = {n: (float(lower[i] + r * box[i, 0] / m), float(lower[i] + r * box[i, 1] / m))
                  for i, n in enumerate(names)}
        wmin, wnodes = float(p[inside].min()), int(inside.sum())
        centre = k[inside].mean(axis=0) / m
    else:
        centre = k[ib] / m
    levels = tuple(lower[i] + r * np.arange(m + 1) / m for i in range(q))
    maps = []
    for a, b in itertools.combinations(range(q), 2):
        rest = [i for i in range(q) if i not in (a, b)]
        share = centre[rest] / centre[rest].sum() if centre[rest].sum() > 0 else np.full(len(rest), 1 / len(rest))
        za, zb = np.meshgrid(np.arange(m + 1) / m, np.arange(m + 1) / m, indexing="xy")
        z = np.zeros((za.size, q))
        z[:, a], z[:, b] = za.ravel(), zb.ravel()
        left = 1.0 - z[:, a] - z[:, b]
        z[:, rest] = left[:, None] * share[None, :]
        x = lower + r * z
        valid = (left >= -1e-12) & np.all(x <= upper + 1e-9 * max(1.0, abs(total)), axis=1)
        pm = np.full(za.size, np.nan)
        if valid.any():
            pm[valid] = prob(z[valid])
        tol = 1e-9 * max(1.0, abs(total))
        in_window = (valid & np.all((x >= np.array([window[n][0] for n in names]) - tol)
                                    & (x <= np.array([window[n][1] for n in names]) + tol), axis=1)
                     if window is not None else np.zeros(za.size, dtype=bool))
        maps.append({"x": names[a], "y": names[b], "x_levels": levels[a], "y_levels": levels[b],
                     "p": pm.reshape(za.shape), "in_window": in_window.reshape(za.shape)})
    held_text = ("the third component is the rest of the total" if q == 3 else
                 "the other components share the rest of the total in the proportions of the window's centroid")
    notes = [f"mixture: the grid is the L-pseudo simplex lattice with {m} divisions ({len(k)} blends inside the "
             f"components' bounds, total {total:g}); the window is bounds per component with the total kept (the part "
             "of the simplex inside them), grown by relaxing one or two bounds a grid step at a time",
             f"maps: each over two components, {held_text}; blends outside the region are blank; the red outline encloses "
             "the blends of the map inside the window"]
    return {"levels": levels, "nodes": lower + r * k / m, "k": k, "p": p, "window": window, "window_nodes": wnodes,
            "window_min": wmin, "best": best, "best_p": float(p[ib]), "maps": maps, "notes": notes,
            "divisions": m}


def check_mixture_options(space: Any, factor_sd: Mapping[str, float] | None) -> None:
    """A mixture design space takes components only and no factor noise (not yet)."""
    if any(f.kind == "categoric" or not hasattr(f, "pseudo_range") for f in space.factors):
        raise ParameterError("factor", "the design space of a mixture with process factors is not available yet "
                                       "(components only)")
    if factor_sd:
        raise ParameterError("factor_sd", "factor noise in a mixture's design space is not available yet (the "
                                          "variation would have to keep the total)")
