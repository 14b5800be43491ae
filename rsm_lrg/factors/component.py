"""A mixture component (:class:`MixtureComponent`): a proportion of a blend, coded as an
L-pseudo-component.

The components of a blend sum to a total ``T`` (1 for proportions). With lower bounds
``L_i`` (0 when none), the L-pseudo-components

    x'_i = (x_i - L_i) / (T - sum_j L_j)            (Cornell, *Experiments with Mixtures*,
                                                     3rd ed., Sec. 4.1; Eq. 4.1)

sum to one and span the whole unit simplex over the constrained region. A component is a
numeric :class:`~rsm_lrg.factors.factor.Factor` whose levels coded -1 and +1 are
``L_i - R`` and ``L_i + R`` (``R = T - sum L``), so that the ordinary coding
``(x - centre) / half_range`` *is* the pseudo coding: every consumer of a factor's coding
(the model matrix, predictions) works on pseudo-components unchanged. ``lower`` and
``upper`` are the component's real bounds.
"""

from __future__ import annotations

from dataclasses import dataclass

from .factor import Factor

__all__ = ["MixtureComponent"]


@dataclass(frozen=True)
class MixtureComponent(Factor):
    """One mixture component.

    Parameters
    ----------
    name, letter
        As for :class:`Factor`.
    low, high : float
        The levels coded -1 and +1: ``lower - pseudo_range`` and ``lower + pseudo_range``
        (use :meth:`build`), so that coded = L-pseudo value [-].
    lower, upper : float
        The component's bounds [the total's units, e.g. proportion]; ``lower`` is the
        L-pseudo origin.
    total : float
        The blend's total ``T`` [same units].
    pseudo_range : float
        ``R = T - sum of every component's lower bound`` (> 0).
    """

    lower: float = 0.0
    upper: float = 1.0
    total: float = 1.0
    pseudo_range: float = 1.0

    @classmethod
    def build(cls, name: str, letter: str, lower: float, upper: float, total: float,
              pseudo_range: float) -> MixtureComponent:
        """The component whose coding is ``(x - lower) / pseudo_range``.

        Parameters
        ----------
        name : str
            The data column.
        letter : str
            The letter in model terms.
        lower, upper : float
            The component's bounds [proportion].
        total : float
            What the blend sums to.
        pseudo_range : float
            ``total`` less the sum of the lower bounds: the L-pseudo scale.

        Returns
        -------
        MixtureComponent
            The component.
        """
        if not pseudo_range > 0:
            raise ValueError(f"component {name!r}: the lower bounds leave no room (T - sum L = {pseudo_range:g})")
        return cls(name=name, low=lower - pseudo_range, high=lower + pseudo_range, letter=letter,
                   lower=float(lower), upper=float(upper), total=float(total), pseudo_range=float(pseudo_range))

    @property
    def lower_sum(self) -> float:
        """The sum of every component's lower bound, ``T - R``."""
        return self.total - self.pseudo_range

    def to_dict(self) -> dict:
        """As a numeric factor (``low``/``high`` are the levels coded ±1) with ``"component":
        true`` and the real ``lower``, ``upper`` and ``total``.

        Returns
        -------
        dict
            Plain JSON-safe data.
        """
        return dict(super().to_dict(), component=True, lower=self.lower, upper=self.upper, total=self.total)
