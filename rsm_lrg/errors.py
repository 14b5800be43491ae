"""Errors that say which parameter they concern (the base layer: every layer may raise them).

A :class:`ParameterError` is a ``ValueError`` whose ``parameter`` attribute names the
library argument at fault (``"alpha_out"``, ``"goal"``, ``"terms"``, ...), as scikit-learn's
``InvalidParameterError`` does; the command line maps it to its own option (``--alpha-out``)
by that attribute, not by the message's wording.

>>> e = ParameterError("alpha_out", "alpha_out must lie between 0 and 1, not 2")
>>> isinstance(e, ValueError), e.parameter, str(e)
(True, 'alpha_out', 'alpha_out must lie between 0 and 1, not 2')
"""

from __future__ import annotations

__all__ = ["ParameterError"]


class ParameterError(ValueError):
    """A bad value of the argument ``parameter`` (a ValueError with a sentence for the user)."""

    def __init__(self, parameter: str, message: str) -> None:
        super().__init__(message)
        self.parameter = parameter
