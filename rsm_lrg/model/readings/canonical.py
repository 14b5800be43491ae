"""Canonical analysis of a fitted second-order surface.

Write the coded quadratic as ``ŷ = b0 + x'b + x'Bx`` with ``B_ii`` the pure-quadratic
coefficients and ``B_ij = b_ij / 2`` half the interaction coefficients. The stationary point
is ``x_s = -½ B⁻¹ b`` with ``ŷ_s = b0 + ½ x_s'b``; the eigenvalues of ``B`` (listed in
decreasing order, as R ``rsm`` prints them) tell a minimum (all > 0), a maximum (all < 0)
or a saddle (mixed signs). Reference: Myers, Montgomery & Anderson-Cook, *Response Surface
Methodology*, 3rd ed., Sec. 6.2; R ``rsm`` ``canonical()``.

R ``rsm``'s ``canonical(object, threshold)`` treats eigenvalues with ``|λ| <= threshold``
as zero and returns the stationary point restricted to the other eigen-directions;
``threshold=None`` here (the default) is the exact ``-½ B⁻¹ b``, and a number reproduces
R's rule.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

__all__ = ["StationaryPoint", "quadratic_parts", "canonical_analysis", "numeric_surface"]


@dataclass(frozen=True)
class StationaryPoint:
    """Stationary point and eigen-analysis of the quadratic part of a fit.

    Attributes
    ----------
    coded : dict or None
        ``{letter: x_s}`` [coded units]; ``None`` when there is no unique stationary point.
    actual : dict or None
        ``{factor name: value}`` [actual units].
    eigenvalues : tuple of float or None
        Eigenvalues of ``B``, decreasing.
    eigenvectors : ndarray or None
        Columns are the eigenvectors (rows follow the factors), sign normalised so that
        the largest component of each is positive.
    kind : str or None
        ``"minimum"``, ``"maximum"`` or ``"saddle"``; ``None`` when not defined.
    predicted : float or None
        ``ŷ`` at the stationary point (average block) [response units].
    inside : bool or None
        Whether the point lies inside the coded cube [-1, 1]^k.
    note : str
        Why something is ``None`` (linear or 2FI model, singular ``B``), else ``""``.
    """

    coded: dict | None
    actual: dict | None
    eigenvalues: tuple | None
    eigenvectors: np.ndarray | None = field(default=None, repr=False)
    kind: str | None = None
    predicted: float | None = None
    inside: bool | None = None
    note: str = ""
    letters: tuple = ()

    def to_dict(self) -> dict:
        """The ``stationary_point`` object of the fit JSON (INTERFACE.md), plus extras.

        Returns
        -------
        dict
            Plain JSON-safe data.
        """
        vec = None
        if self.eigenvectors is not None:
            vec = {L: [float(v) for v in row] for L, row in zip(self.letters, self.eigenvectors)}
        return {
            "coded": None if self.coded is None else dict(self.coded),
            "actual": None if self.actual is None else dict(self.actual),
            "eigenvalues": None if self.eigenvalues is None else list(self.eigenvalues),
            "kind": self.kind,
            "eigenvectors": vec,
            "predicted": self.predicted,
            "inside": self.inside,
            "note": self.note or None,
        }

    # -- faces: read like the CLI's "Canonical analysis" block -------------------------------
    def _lines(self) -> list[str]:
        from ...present import format_number as fmt

        if self.eigenvalues is None and self.coded is None:
            return [self.note or "no canonical analysis"]
        out = []
        if self.coded is None:
            out.append(self.note or "no unique stationary point")
        else:
            out.append(f"Kind: {self.kind}" + ("" if self.inside is None else
                       ", inside the design box" if self.inside else ", outside the design box (extrapolation)"))
            out.append(f"Predicted response there: {fmt(self.predicted, 6, missing='n/a')}")
            actual = self.actual if self.actual is not None else {}  # given with coded
            rows = [(f"{L} {n}", fmt(c, 6), fmt(a, 6))
                    for (L, c), (n, a) in zip(self.coded.items(), actual.items())]
            w = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(("factor", "coded", "actual"))]
            out.append(f"  {'factor':<{w[0]}}  {'coded':>{w[1]}}  {'actual':>{w[2]}}")
            out += [f"  {a:<{w[0]}}  {b:>{w[1]}}  {c:>{w[2]}}" for a, b, c in rows]
            if self.note:
                out.append(f"Note: {self.note}")
        if self.eigenvalues is not None:
            out.append("Eigenvalues: " + ", ".join(fmt(v, 6) for v in self.eigenvalues))
        return out

    def __str__(self) -> str:
        """Multi-line, as the CLI prints the canonical analysis.

        >>> sp = StationaryPoint({"A": 0.5}, {"x": 1.25}, (-2.0,), kind="maximum", predicted=3.0, inside=True)
        >>> print(sp)
        Kind: maximum, inside the design box
        Predicted response there: 3
          factor  coded  actual
          A x       0.5    1.25
        Eigenvalues: -2
        """
        return "\n".join(self._lines())

    def __repr__(self) -> str:
        return "StationaryPoint(\n  " + "\n  ".join(self._lines()) + "\n)"

    def _repr_html_(self) -> str:
        from html import escape

        return ("<div class='rsm-lrg-stationary'><b>Stationary point</b>"
                f"<pre>{escape(chr(10).join(self._lines()))}</pre></div>")


def quadratic_parts(coefs: Mapping[str, float], terms, k: int):
    """``(b0, b, B)`` of the coded polynomial from ``{term name: coefficient}``.

    Terms of order 3 or more are not representable; the caller checks for them.
    """
    b0 = 0.0
    b = np.zeros(k)
    B = np.zeros((k, k))
    for t in terms:
        c = float(coefs[t.name])
        nz = [i for i, p in enumerate(t.powers) if p]
        if t.order == 0:
            b0 = c
        elif t.order == 1:
            b[nz[0]] = c
        elif t.order == 2 and len(nz) == 1:
            B[nz[0], nz[0]] = c
        elif t.order == 2:
            i, j = nz
            B[i, j] = B[j, i] = c / 2.0
    return b0, b, B


def canonical_analysis(coefs: Mapping[str, float], terms, space, *, threshold: float | None = None,
                       rel_tol: float = 1e-10, level: Mapping[str, str] | None = None) -> StationaryPoint:
    """Canonical analysis of the fitted surface (see the module docstring).

    Parameters
    ----------
    coefs : mapping
        Coded coefficients by term name.
    terms : sequence of Term
    space : FactorSpace
    threshold : float, optional
        R ``rsm``'s threshold on ``|eigenvalue|`` [response units per coded unit²];
        ``None`` uses the exact inverse (eigenvalues below ``rel_tol`` times the largest
        count as zero and make ``B`` singular).
    level : mapping, optional
        With categoric factors: the level of each (``{"stage": "rms"}``) at which the
        surface in the numeric factors is analysed; by default the first level of each
        (the note says which).

    Returns
    -------
    StationaryPoint
        The stationary point, the eigenvalues and the kind.
    """
    if space.has_categoric:
        return _canonical_at_levels(coefs, terms, space, threshold=threshold, rel_tol=rel_tol, level=level)
    letters = tuple(space.letters)
    k = len(letters)
    has_square = any(t.order == 2 and max(t.powers) == 2 for t in terms)
    if any(t.order > 2 for t in terms):
        return StationaryPoint(None, None, None, note="canonical analysis needs a second-order model (the model has cubic terms)", letters=letters)
    if not has_square:
        return StationaryPoint(None, None, None, note="no canonical analysis: the model has no pure quadratic terms", letters=letters)
    b0, b, B = quadratic_parts(coefs, terms, k)
    vals, vecs = np.linalg.eigh(B)
    order = np.argsort(vals)[::-1]
    vals, vecs = vals[order], vecs[:, order]
    for j in range(k):  # deterministic sign
        if vecs[np.argmax(np.abs(vecs[:, j])), j] < 0:
            vecs[:, j] = -vecs[:, j]
    scale = float(np.max(np.abs(vals))) if vals.size else 0.0
    cut = threshold if threshold is not None else rel_tol * scale
    active = np.abs(vals) > cut
    eig = tuple(float(v) for v in vals)
    if scale == 0.0 or not active.any():
        return StationaryPoint(None, None, eig, vecs, None, note="B is zero: no stationary point", letters=letters)
    if threshold is None and not active.all():
        return StationaryPoint(None, None, eig, vecs, None,
                               note="B is singular (an eigenvalue is zero): no unique stationary point; the surface has a ridge",
                               letters=letters)
    U = vecs[:, active]
    xs = -0.5 * U @ ((U.T @ b) / vals[active])
    if threshold is not None and not active.all():
        eig = tuple(float(v) if a else 0.0 for v, a in zip(vals, active))
    sig = np.sign(vals[active])
    kind = "minimum" if (sig > 0).all() and active.all() else "maximum" if (sig < 0).all() and active.all() else "saddle"
    if not active.all() and ((sig > 0).all() or (sig < 0).all()):
        kind = "ridge"
    pred = float(b0 + 0.5 * xs @ b)
    coded = {L: float(v) for L, v in zip(letters, xs)}
    actual = {f.name: float(f.decode(v)) for f, v in zip(space.factors, xs)}
    inside = bool(np.all(np.abs(xs) <= 1.0 + 1e-12))
    note = "" if active.all() else f"eigenvalues with |value| <= {cut:g} treated as zero (R rsm threshold)"
    return StationaryPoint(coded, actual, eig, vecs, kind, pred, inside, note, letters)


def numeric_surface(coefs: Mapping[str, float], terms, space, level: Mapping[str, str] | None = None):
    """The fitted polynomial in the numeric factors at one combination of categoric levels.

    Returns ``(coefs, terms, subspace, level)``: coded coefficients by term name of the
    numeric terms (each categoric column weighted by its effect code at ``level`` and
    added to its numeric monomial), those terms over the numeric factors only, the
    :class:`~rsm_lrg.factors.FactorSpace` of the numeric factors (same letters) and the
    level used (``{name: level}``; the first level of each factor by default).
    """
    from ...factors import FactorSpace
    from ...terms import Term as _Term
    from ...terms import effect_codes, term_name

    cats = {i: f for i, f in enumerate(space.factors) if f.kind == "categoric"}
    level = dict(level or {})
    unknown = [k for k in level if k not in [f.name for f in cats.values()]]
    if unknown:
        raise ValueError(f"{unknown[0]!r} is not a categoric factor of this model")
    chosen = {f.name: level.get(f.name, f.levels[0]) for f in cats.values()}
    idx = {i: f.index(chosen[f.name]) for i, f in cats.items()}
    num = space.numeric_index
    letters = [space.letters[i] for i in num]
    out: dict = {}
    for t in terms:
        pw = tuple(t.powers[i] for i in num)
        for combo, col in zip(t.level_combinations() if t.cat else [()], t.columns):
            w = 1.0
            for (i, lv), j in zip(t.cat, combo):
                w *= effect_codes(np.array([idx[i]]), len(lv))[0, j]
            out[pw] = out.get(pw, 0.0) + w * float(coefs[col])
    order = sorted(out, key=lambda p: (sum(p), max(p, default=0), [-x for x in p]))
    new_terms = [_Term(p, term_name(p, letters)) for p in order]
    return ({t.name: out[t.powers] for t in new_terms}, new_terms, FactorSpace(tuple(space.numeric)), chosen)


def _canonical_at_levels(coefs, terms, space, *, threshold, rel_tol, level) -> StationaryPoint:
    if not space.numeric:
        return StationaryPoint(None, None, None, note="no canonical analysis: every factor is categoric")
    c2, t2, sub, chosen = numeric_surface(coefs, terms, space, level)
    sp = canonical_analysis(c2, t2, sub, threshold=threshold, rel_tol=rel_tol)
    at = ", ".join(f"{k} = {v}" for k, v in chosen.items())
    note = f"surface in the numeric factors at {at}" + (f"; {sp.note}" if sp.note else "")
    from dataclasses import replace

    return replace(sp, note=note)
