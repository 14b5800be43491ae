"""A fitted polynomial in actual units: the coded coefficients re-expressed in the factors'
own units (no refit), and the actual-units equations once per level combination.

The exact route is the binomial expansion of every coded monomial
``prod ((x_i - c_i) / h_i) ** e_i``; :func:`actual_coefficients` gives it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from math import comb
from typing import Any

from ...factors import FactorSpace
from ..build.terms import Term, term_name

__all__ = ["actual_coefficients", "actual_equations", "actual_expansion"]


def actual_coefficients(coded: Mapping[str, float], terms: Sequence[Term], space: FactorSpace) -> dict:
    """Coefficients of the same polynomial in actual units (no refit).

    Each coded monomial ``prod ((x_i - c_i) / h_i) ** e_i`` is expanded by the binomial
    theorem into monomials of the actual ``x_i``; the coefficients are collected by
    monomial and returned under the same column names (``"A"`` is then the coefficient of
    the actual thickness, and so on). For a hierarchical model (every standard model) the
    keys are exactly the coded keys. A categoric factor keeps its effect coding: the
    coefficient of ``"AE[rms]"`` multiplies the actual A and the effect code of level rms
    (:func:`actual_equations` gives one plain polynomial per level combination).

    Parameters
    ----------
    coded : mapping
        ``{term name: coefficient}`` in coded units.
    terms : sequence of Term
        The model's terms.
    space : FactorSpace
        The factors and their coding.

    Returns
    -------
    dict
        ``{term name: coefficient}`` in actual units (products of the factors' units).
    """
    acc, names = actual_expansion(coded, terms, space)
    out = {col: acc.get(key, 0.0) for key, col in names.items()}
    for (pw, sig), v in acc.items():
        if (pw, sig) not in names and v != 0.0:
            out[_column_label(pw, sig, space)] = v
    return out


def actual_expansion(coded: Mapping[str, float], terms: Sequence[Term], space: FactorSpace) -> tuple[dict, dict]:
    """``({(numeric exponents, categoric (factor, level) pairs): actual coefficient}, {same key: column name})``."""
    k = len(space)
    centres = [f.center if f.kind == "numeric" else 0.0 for f in space.factors]
    halves = [f.half_range if f.kind == "numeric" else 1.0 for f in space.factors]
    acc: dict[tuple, float] = {}
    names: dict[tuple, str] = {}
    for t in terms:
        npw = t.numeric_powers
        for combo, col in zip(t.level_combinations() if t.cat else [()], t.columns):
            sig = tuple((i, j) for (i, _), j in zip(t.cat, combo))
            names[(npw, sig)] = col
            c = float(coded[col])
            parts: list[tuple[tuple[int, ...], float]] = [((), c)]  # expand factor by factor: list of (powers, coefficient)
            for i in range(k):
                e = npw[i]
                new: list[tuple[tuple[int, ...], float]] = []
                for pw, v in parts:
                    for m in range(e + 1):
                        coef = comb(e, m) * (-centres[i]) ** (e - m) / halves[i] ** e
                        new.append((pw + (m,), v * coef))
                parts = new
            for pw, v in parts:
                acc[(pw, sig)] = acc.get((pw, sig), 0.0) + v
    return acc, names


def _column_label(pw: tuple, sig: tuple, space: FactorSpace) -> str:
    """Name of the column with numeric exponents ``pw`` and categoric ``(factor, level)`` ``sig``."""
    powers = list(pw)
    for i, _ in sig:
        powers[i] = 1
    letters = space.letters
    t = Term(tuple(powers), term_name(powers, letters), tuple((i, space.factors[i].levels) for i, _ in sig),
             tuple(letters[i] for i, _ in sig))
    return t.columns[t.level_combinations().index(tuple(j for _, j in sig))] if sig else t.name


def actual_equations(result: Any, coded: Mapping[str, float] | None = None) -> list[tuple[dict, dict]]:
    """The fitted polynomial in actual units once per combination of categoric levels
    (Design-Expert's "stage = rfcms: ..." equations): ``[({name: level}, {term: coefficient})]``,
    the terms being numeric monomials (``"A"``, ``"AB"``, ``"A^2"``, ``"Intercept"``).
    One entry with an empty setting when every factor is numeric. ``coded`` replaces the
    fitted coded coefficients (by column name)."""
    space, letters = result.space, result.space.letters
    cats = [i for i, f in enumerate(space.factors) if f.kind == "categoric"]
    if coded is None:
        coded = dict(zip(result.coefficients.index, result.coefficients["coded"]))
    acc, _ = actual_expansion(coded, result.terms, space)
    out = []
    for setting in space.level_combinations():
        idx = {i: space.factors[i].levels.index(setting[space.factors[i].name]) for i in cats}
        eq: dict[str, float] = {}
        for (pw, sig), v in acc.items():
            for i, j in sig:
                last = len(space.factors[i].levels) - 1
                v *= 1.0 if idx[i] == j else (-1.0 if idx[i] == last else 0.0)
            if sig and v == 0.0:
                continue
            key = term_name(pw, letters)
            eq[key] = eq.get(key, 0.0) + v
        out.append((setting, eq))
    return out

