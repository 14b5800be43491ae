"""The region of ``report --constraint ... --bound ...`` as the page's script evaluates it.

A constraint is written in actual units (``"velocity_m_s**2/acceleration_m_s2 <= stroke_m"``)
and checked by :class:`rsm_lrg.design.constraints.Constraints`, which parses it safely (a
whitelist of Python's syntax tree). The page needs the same inequalities in its own language:
each one becomes a small expression tree (plain JSON: numbers, factor names, ``+ - * / **``,
the whitelisted functions) that ``profiler.js`` evaluates at a setting. A ``--bound`` becomes
two more inequalities. The page then keeps "deepest inside every limit" and the overlay's
shading inside the region; the optimum buttons jump to optima found inside it by the optimise
layer.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping, Sequence
from typing import Any

__all__ = ["region_data"]

_OPS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**", ast.BitXor: "**"}


def _tree(node: ast.AST, names: Mapping[str, str]) -> Any:
    """The JSON tree of an expression already accepted by ``Constraints.parse``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return float(node.value)
    if isinstance(node, ast.Name):
        return {"f": names[node.id]}
    if isinstance(node, ast.UnaryOp):
        inner = _tree(node.operand, names)
        return {"op": "neg", "a": inner} if isinstance(node.op, ast.USub) else inner
    if isinstance(node, ast.BinOp):
        return {"op": _OPS[type(node.op)], "a": _tree(node.left, names), "b": _tree(node.right, names)}
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        return {"call": node.func.id, "args": [_tree(a, names) for a in node.args]}
    raise ValueError(f"cannot show the constraint part {ast.dump(node)[:60]} in the page")


def region_data(space, constraints: Sequence[str] | None = None,
                bounds: Mapping[str, Sequence[float]] | None = None) -> dict | None:
    """The page's region: ``{"constraints": [{"text", "lhs", "rhs"}], "text": [...]}``, or ``None``.

    Parameters
    ----------
    space : FactorSpace
        The factors of the report (names and letters a constraint may use).
    constraints : list of str, optional
        Inequalities in actual units, as ``--constraint`` takes them (each ``lhs <= rhs`` or
        ``>=``, chains allowed). Checked by :class:`~rsm_lrg.design.constraints.Constraints`
        first (a bad one raises its ValueError).
    bounds : mapping, optional
        ``{factor name: (low, high)}`` in actual units (``--bound`` of numeric factors).

    Returns
    -------
    dict or None
        ``lhs``/``rhs`` are expression trees: a number, ``{"f": NAME}``, ``{"op": "+", "a",
        "b"}`` (``+ - * / **``), ``{"op": "neg", "a"}`` or ``{"call": "sqrt", "args": [...]}``;
        every inequality reads ``lhs <= rhs``. ``None`` without constraints or bounds.
    """
    from ..design.constraints import Constraints

    items: list[dict] = []
    texts: list[str] = []
    if constraints:
        parsed = Constraints.parse(list(constraints), space)
        names = {f.name: f.name for f in space.factors}
        names.update({f.letter: f.name for f in space.factors})
        for c in (parsed[j] for j in range(len(parsed))):
            cmp = ast.parse(c.text, mode="eval").body
            assert isinstance(cmp, ast.Compare) and len(cmp.ops) == 1
            left, right = _tree(cmp.left, names), _tree(cmp.comparators[0], names)
            lhs, rhs = (left, right) if isinstance(cmp.ops[0], (ast.LtE, ast.Lt)) else (right, left)
            items.append({"text": c.text, "lhs": lhs, "rhs": rhs})
            texts.append(c.text)
    for name, pair in (bounds or {}).items():
        lo, hi = (float(v) for v in pair)
        if not (math.isfinite(lo) and math.isfinite(hi)):
            raise ValueError(f"bound for {name!r}: LOW and HIGH must be finite numbers")
        items.append({"text": f"{name} >= {lo:g}", "lhs": lo, "rhs": {"f": name}})
        items.append({"text": f"{name} <= {hi:g}", "lhs": {"f": name}, "rhs": hi})
        texts.append(f"{lo:g} <= {name} <= {hi:g}")
    if not items:
        return None
    return {"constraints": items, "text": texts}
