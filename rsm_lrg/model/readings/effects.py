"""Effects of an unreplicated screening experiment: half-normal scores and Lenth's PSE.

For a two-level (or definitive screening) design fitted in coded units, the *effect* of a
one-degree-of-freedom term is the change of the predicted response from its low (-1) to its
high (+1) setting, twice the coded coefficient. With no replicates (or a saturated model) there
is no error estimate; Lenth (1989) takes one from the effects themselves:

- ``s0 = 1.5 * median(|c_j|)``
- pseudo standard error ``PSE = 1.5 * median(|c_j| : |c_j| <= 2.5 s0)`` (the ``<=`` of Lenth's
  own R package *unrepx*, ``Lenth_pse``),
- margin of error ``ME = t(1 - alpha/2; d) * PSE`` and simultaneous margin of error
  ``SME = t(gamma; d) * PSE`` with ``gamma = (1 + (1 - alpha)^(1/m)) / 2`` and ``d = m / 3``
  degrees of freedom, ``m`` the number of effects.

An effect beyond ME is active at level ``alpha`` taken one at a time; beyond SME, taken
together. The half-normal plot puts the sorted ``|c_j|`` against the half-normal quantiles
``Phi^-1(0.5 + 0.5 (i - 0.5) / m)`` (Daniel 1959): inactive effects lie on a line through the
origin, active ones stand off to the right.

References
----------
Lenth, R. V. (1989). Quick and easy analysis of unreplicated factorials. *Technometrics*
31(4), 469-473. Daniel, C. (1959). Use of half-normal plots in interpreting factorial two-level
experiments. *Technometrics* 1(4), 311-341. Montgomery, D. C. (2013). *Design and Analysis of
Experiments*, 8th ed., Example 6.2 (the filtration-rate 2^4 used in the tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from statistics import NormalDist
from typing import Any

import numpy as np

from ...errors import ParameterError

__all__ = ["EffectsResult", "EstimableModel", "largest_estimable_model", "lenth_pse", "lenth_margins",
           "half_normal_quantiles", "screening_effects"]

#: At most this many interaction terms are tried by :func:`largest_estimable_model` (orders are
#: taken whole, lowest first, while they fit: 2^20 products of 20 factors are not built).
MAX_CANDIDATE_TERMS = 5000


@dataclass(frozen=True)
class EstimableModel:
    """The largest model of main effects and interactions a two-level design estimates.

    Attributes
    ----------
    terms : tuple of str
        The terms kept (``"A"``, ``"AB"``, ...): main effects, then each interaction that is
        orthogonal to every term kept before it (lower orders first).
    aliases : dict
        ``{kept term: (aliased term, ...)}``: the terms whose column equals the kept term's
        (``"CDE"``) or its negative (``"-CDE"``) on these runs, so that the estimate is the
        sum of their effects (the alias chain ``AB = CDE``); under ``"Intercept"`` the words
        of the defining relation (``I = ABCDE``).
    partial : tuple of str
        Interactions neither orthogonal to the terms kept nor a full alias of one (partially
        aliased, as in Plackett-Burman designs): left out.
    """

    terms: tuple
    aliases: dict = field(default_factory=dict)
    partial: tuple = ()

    def chains(self) -> list[str]:
        """The alias chains as text: ``["AB = CDE", "AC = -BDE"]``."""
        out = []
        order = [t for t in ("Intercept", *self.terms) if t in self.aliases]
        order += [t for t in self.aliases if t not in order]
        for t in order:
            al = self.aliases[t]
            parts = [a if a.startswith("-") else f"+{a}" for a in al]
            out.append(f"{'I' if t == 'Intercept' else t} = {' '.join(parts).lstrip('+')}"
                       .replace(" +", " + ").replace(" -", " - "))
        return out


def largest_estimable_model(coded, letters, *, max_terms: int | None = None, tol: float = 1e-8) -> EstimableModel:
    """The saturated model of main effects and interactions that the runs ``coded`` estimate.

    Main effects first, then the products of 2, 3, ... distinct factors in order; a term is
    kept when its column is orthogonal to the intercept and to every term kept so far (for a
    regular fraction, one term of each alias chain, the lowest order first, as Design-Expert
    and JMP name the effects of a 2^(k-p) design); a column equal to a kept one or its
    negative joins that term's alias chain; any other is left out as partially aliased.

    Parameters
    ----------
    coded : array_like, shape (n, k)
        The runs in coded units (-1, +1; centre points 0).
    letters : sequence of str
        The factor letters (``"ABCDE"``).
    max_terms : int, optional
        At most this many terms (besides the intercept) are kept, default ``n - 1``; room for
        block effects is made by asking for fewer.
    tol : float
        Relative tolerance of "orthogonal" and "equal" (cosine of the columns' angle).

    Returns
    -------
    EstimableModel

    Examples
    --------
    The 2^(3-1) fraction with C = AB estimates A, B and C, each aliased with an interaction:

    >>> x = np.array([[-1, -1, 1], [1, -1, -1], [-1, 1, -1], [1, 1, 1]])
    >>> m = largest_estimable_model(x, "ABC")
    >>> m.terms, m.chains()
    (('A', 'B', 'C'), ['I = ABC', 'A = BC', 'B = AC', 'C = AB'])
    """
    from itertools import combinations

    x = np.asarray(coded, dtype=float)
    n, k = x.shape
    letters = list(letters)
    limit = n - 1 if max_terms is None else min(int(max_terms), n - 1)
    kept_cols = [np.ones(n)]
    kept: list[str] = []
    aliases: dict[str, list[str]] = {}
    partial: list[str] = []
    tried = 0
    for order in range(1, k + 1):
        combos = list(combinations(range(k), order))
        if order > 1 and tried + len(combos) > MAX_CANDIDATE_TERMS:
            break
        tried += len(combos)
        for combo in combos:
            name = "".join(letters[i] for i in combo)
            c = np.prod(x[:, list(combo)], axis=1)
            norm = float(np.linalg.norm(c))
            if norm == 0.0:
                partial.append(name)
                continue
            K = np.column_stack(kept_cols)
            cos = (K.T @ c) / (np.linalg.norm(K, axis=0) * norm)
            full = np.flatnonzero(np.abs(np.abs(cos) - 1.0) <= tol)
            if full.size:  # a column equal to a kept one (or to the intercept: a word of the defining relation)
                j = int(full[0])
                owner = "Intercept" if j == 0 else kept[j - 1]
                aliases.setdefault(owner, []).append(("-" if cos[j] < 0 else "") + name)
            elif order == 1 and len(kept) < limit:  # a main effect: kept when independent
                resid = c - K @ np.linalg.lstsq(K, c, rcond=None)[0]
                if np.linalg.norm(resid) > tol * norm:
                    kept.append(name)
                    kept_cols.append(c)
                else:
                    partial.append(name)
            elif np.all(np.abs(cos) <= tol) and len(kept) < limit:
                kept.append(name)
                kept_cols.append(c)
            else:
                partial.append(name)
    return EstimableModel(tuple(kept), {t: tuple(aliases[t]) for t in ["Intercept", *kept] if t in aliases},
                          tuple(partial))


def lenth_pse(effects) -> float:
    """Lenth's (1989) pseudo standard error of a set of effects [response units].

    >>> lenth_pse([3.5, 12, 22.5, 1, .5, 1, 2.5])   # BH^2 bicycle example (unrepx bikeEff)
    1.5
    """
    a = np.abs(np.asarray(effects, dtype=float))
    if a.size < 2 or not np.all(np.isfinite(a)):
        raise ValueError("Lenth's PSE needs at least two finite effects")
    s0 = 1.5 * float(np.median(a))
    return 1.5 * float(np.median(a[a <= 2.5 * s0]))


def lenth_margins(pse: float, m: int, alpha: float = 0.05) -> tuple[float, float, float]:
    """``(ME, SME, d)``: Lenth's margin of error, simultaneous margin of error and their
    degrees of freedom ``d = m/3`` for ``m`` effects at level ``alpha``."""
    from ..contract.statistics import stdtrit

    if not 0.0 < alpha < 1.0:
        raise ParameterError("alpha", f"alpha must lie between 0 and 1, not {alpha!r}")
    d = m / 3.0
    gamma = (1.0 + (1.0 - alpha) ** (1.0 / m)) / 2.0
    return float(stdtrit(d, 1.0 - alpha / 2.0)) * pse, float(stdtrit(d, gamma)) * pse, d


def half_normal_quantiles(m: int) -> np.ndarray:
    """Half-normal scores ``Phi^-1(0.5 + 0.5 (i - 0.5)/m)``, i = 1..m (ascending)."""
    nd = NormalDist()
    return np.array([nd.inv_cdf(0.5 + 0.5 * (i - 0.5) / m) for i in range(1, m + 1)])


@dataclass(frozen=True)
class EffectsResult:
    """Effects of the one-df terms of a fit with Lenth's PSE and the half-normal scores.

    Attributes
    ----------
    response : str
    terms : tuple of str
        Term names (``"A"``, ``"AC"``, ...), in the fit's order.
    labels : tuple of str
        The same terms with factor names (``"thickness_m × velocity_m_s"``).
    effects : ndarray
        Effect of each term: predicted change from -1 to +1 in coded units, ``2 b_j``
        [response units].
    half_normal : ndarray
        Half-normal score of each effect (by the rank of ``|effect|``).
    pse, me, sme : float
        Lenth's pseudo standard error, margin of error and simultaneous margin of error
        [response units].
    df : float
        Degrees of freedom of ME and SME, ``m / 3``.
    alpha : float
    notes : tuple of str
        What the reader should know (residual degrees of freedom left, unequal variances).
    """

    response: str
    terms: tuple
    labels: tuple
    effects: np.ndarray = field(repr=False)
    half_normal: np.ndarray = field(repr=False)
    pse: float
    me: float
    sme: float
    df: float
    alpha: float = 0.05
    notes: tuple = ()
    aliases: dict = field(default_factory=dict)

    @property
    def active(self) -> tuple:
        """Terms whose ``|effect|`` exceeds ME (level ``alpha`` one at a time)."""
        return tuple(t for t, e in zip(self.terms, self.effects) if abs(e) > self.me)

    @property
    def active_simultaneous(self) -> tuple:
        """Terms whose ``|effect|`` exceeds SME (level ``alpha`` taken together)."""
        return tuple(t for t, e in zip(self.terms, self.effects) if abs(e) > self.sme)

    def to_frame(self):
        """One row per term, largest ``|effect|`` first: ``term``, ``label``, ``effect``,
        ``abs_effect``, ``half_normal``, ``t_lenth`` (effect / PSE), ``active``,
        ``active_sme``.

        Returns
        -------
        pandas.DataFrame
            The table described above.
        """
        import pandas as pd

        e = np.asarray(self.effects, dtype=float)
        t = e / self.pse if self.pse > 0 else np.full_like(e, np.nan)
        df = pd.DataFrame({"term": self.terms, "label": self.labels, "effect": e, "abs_effect": np.abs(e),
                           "half_normal": self.half_normal, "t_lenth": t,
                           "active": np.abs(e) > self.me, "active_sme": np.abs(e) > self.sme})
        return df.sort_values("abs_effect", ascending=False, kind="stable").reset_index(drop=True)

    def to_dict(self) -> dict[str, Any]:
        """The effects as plain data.

        Returns
        -------
        dict
            JSON-safe: numbers, strings, lists and dicts.
        """
        rows = self.to_frame().to_dict(orient="records")
        for r in rows:
            for k in ("effect", "abs_effect", "half_normal", "t_lenth"):
                r[k] = None if not math.isfinite(r[k]) else float(r[k])
            r["active"], r["active_sme"] = bool(r["active"]), bool(r["active_sme"])
        return {"response": self.response, "method": "Lenth (1989)", "alpha": self.alpha, "m": len(self.terms),
                "pse": self.pse, "me": self.me, "sme": self.sme, "df": self.df,
                "active": list(self.active), "active_sme": list(self.active_simultaneous),
                "effects": rows, "aliases": {t: list(a) for t, a in self.aliases.items()}, "notes": list(self.notes)}

    def summary(self) -> str:
        """A few lines of text for people.

        Returns
        -------
        str
            The text, several lines.
        """
        from ...present import format_number

        f = self.to_frame()
        head = ["Term", "Effect", "|Effect|", "Half-normal", "Effect/PSE", "Active"]
        rows = [[r.label if r.label == r.term else f"{r.term}  {r.label}", format_number(r.effect, 4),
                 format_number(r.abs_effect, 4), f"{r.half_normal:.3f}", format_number(r.t_lenth, 3),
                 "SME" if r.active_sme else ("ME" if r.active else "")] for r in f.itertuples()]
        widths = [max(len(h), *(len(row[i]) for row in rows)) for i, h in enumerate(head)]
        line = lambda cells: "  ".join(c.ljust(w) if i == 0 else c.rjust(w) for i, (c, w) in enumerate(zip(cells, widths)))  # noqa: E731
        conf = f"{100 * (1 - self.alpha):g} %"
        out = [f"Effects of {self.response} (Lenth 1989, {len(self.terms)} one-df effects)", line(head),
               *(line(r) for r in rows), "",
               f"PSE {format_number(self.pse, 4)}   ME {format_number(self.me, 4)}   "
               f"SME {format_number(self.sme, 4)}   (t on {self.df:.3g} df, {conf})",
               "Active beyond ME: " + (", ".join(self.active) or "none"),
               "Active beyond SME: " + (", ".join(self.active_simultaneous) or "none")]
        if self.aliases:
            chains = EstimableModel(self.terms, self.aliases).chains()
            out.append("Alias chains (each effect is the sum of its chain): " + "; ".join(chains))
        out += [f"Note: {n}" for n in self.notes]
        return "\n".join(out) + "\n"

    def __str__(self) -> str:
        return self.summary()

    def _repr_html_(self) -> str:
        from html import escape

        from ...present import format_number

        f = self.to_frame()
        body = "".join(
            f"<tr><td>{escape(r.term)}</td><td>{escape(r.label)}</td><td>{format_number(r.effect, 6)}</td>"
            f"<td>{format_number(r.half_normal, 3)}</td><td>{'SME' if r.active_sme else ('ME' if r.active else '')}</td></tr>"
            for r in f.itertuples())
        cap = escape(f"Effects of {self.response}: PSE {format_number(self.pse)}, ME {format_number(self.me)}, "
                     f"SME {format_number(self.sme)}")
        return ("<table class='rsm-lrg-effects'><caption>" + cap + "</caption><tr><th>Term</th><th>Factors</th>"
                "<th>Effect</th><th>Half-normal</th><th>Active</th></tr>" + body + "</table>")


def screening_effects(result, alpha: float = 0.05, aliases: dict | None = None) -> EffectsResult:
    """Effects (``2 b_j``, coded units) of every term of a fit, with Lenth's PSE, ME and SME.

    Parameters
    ----------
    result : FitResult
        A fit in coded units (:func:`rsm_lrg.model.fit`); every term must have one degree
        of freedom (a categoric factor with more than two levels has no single effect).
    alpha : float
        Level of ME and SME (default 0.05).
    aliases : dict, optional
        The alias chains of the terms (:attr:`EstimableModel.aliases`), shown with the effects.

    Returns
    -------
    EffectsResult

    Notes
    -----
    Lenth's method assumes effects of equal variance (an orthogonal two-level design); when
    ``(X'X)^-1`` gives the effects unequal variances (definitive screening designs, designs
    with runs missing) the result says by how much in ``notes``. A fit with residual degrees
    of freedom has t-tests of its own in the ANOVA; the note says so.
    """
    terms = result.terms[1:] if result.terms and result.terms[0].name == "Intercept" else result.terms
    many = [t.name for t in terms if t.df != 1]
    if many:
        raise ValueError(f"term {many[0]} has {[t.df for t in terms if t.df != 1][0]} degrees of freedom; "
                         "effects and Lenth's PSE need one-df terms (two-level factors)")
    if len(terms) < 2:
        raise ValueError("effects need at least two model terms besides the intercept")
    coef = result.coefficients
    names = [t.name for t in terms]
    e = 2.0 * coef.loc[names, "coded"].to_numpy(dtype=float)
    m = e.size
    pse = lenth_pse(e)
    me, sme, d = lenth_margins(pse, m, alpha)
    order = np.argsort(np.abs(e), kind="stable")
    hn = np.empty(m)
    hn[order] = half_normal_quantiles(m)
    letters = {f.letter: f.name for f in result.space.factors}
    labels = tuple(" × ".join(letters.get(ch, ch) for ch in nm) if nm.isalpha() and nm.isupper() else nm
                   for nm in names)
    notes = []
    if result.df_resid > 0:
        notes.append(f"the fit leaves {result.df_resid} residual degrees of freedom: its ANOVA has t- and F-tests "
                     "of its own; Lenth's PSE is meant for unreplicated, saturated fits")
    var = np.diag(result.cov_unscaled)[result.term_index][1:]  # one column per one-df term
    spread = float(var.max() / var.min() - 1.0) if var.min() > 0 else math.inf
    if spread > 1e-9:
        notes.append(f"the effects' variances differ by up to {100 * spread:.3g} % (Lenth's PSE assumes them equal)")
    return EffectsResult(result.response, tuple(names), labels, e, hn, pse, me, sme, d, alpha, tuple(notes),
                         dict(aliases or {}))
