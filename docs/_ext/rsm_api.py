"""The public names of rsm-lrg, as the API reference documents them and ``tests/test_docs.py``
checks their docstrings (no Sphinx import here).

Public: every name in ``rsm_lrg.__all__`` and in the ``__all__`` of the sub-packages below; for a
class, its public methods and properties (those it defines itself, not inherited ones).
"""

from __future__ import annotations

import importlib
import inspect
import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

#: The packages whose ``__all__`` is public, in the order of the API reference.
PACKAGES = ["rsm_lrg", "rsm_lrg.factors", "rsm_lrg.design", "rsm_lrg.model", "rsm_lrg.optimize",
            "rsm_lrg.surrogate", "rsm_lrg.report", "rsm_lrg.paper"]

_SECTION = re.compile(r"^(Parameters|Other Parameters|Returns|Yields|Attributes|Raises|Warns|Notes|Examples|"
                      r"See Also|References)\n-{3,}$", re.M)


@dataclass(frozen=True)
class PublicName:
    """One public name: where the reference documents it and the object itself.

    Parameters
    ----------
    package : str
        The package whose ``__all__`` lists it first (``"rsm_lrg"`` for the top level).
    name : str
        The name in that package.
    obj : object
        The object (a function, class or constant).
    """

    package: str
    name: str
    obj: Any

    @property
    def qualname(self) -> str:
        """``package.name``, the path the reference documents."""
        return f"{self.package}.{self.name}"

    @property
    def kind(self) -> str:
        """``"class"``, ``"function"`` or ``"data"``."""
        if inspect.isclass(self.obj):
            return "class"
        return "function" if callable(self.obj) else "data"


def _resolve(package: str, name: str) -> Any:
    obj = getattr(importlib.import_module(package), name)
    if inspect.ismodule(obj):  # rsm_lrg.optimize is the callable package
        obj = getattr(obj, name)
    return obj


def public_names() -> list[PublicName]:
    """Every public name once, under the first package (in :data:`PACKAGES` order) that lists it.

    Returns
    -------
    list of PublicName
        In package order, then in the order of each ``__all__``.
    """
    seen: set[int] = set()
    out: list[PublicName] = []
    for package in PACKAGES:
        mod = importlib.import_module(package)
        for name in mod.__all__:
            if name.startswith("__"):
                continue
            obj = _resolve(package, name)
            if not (inspect.isclass(obj) or callable(obj)):
                out.append(PublicName(package, name, obj))  # a constant: listed under each package
                continue
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            out.append(PublicName(package, name, obj))
    return out


def members(cls: type) -> Iterator[tuple[str, Any]]:
    """The public methods and properties a class defines itself.

    Parameters
    ----------
    cls : type
        The class.

    Yields
    ------
    tuple of (str, object)
        The member's name and the function (for a static or class method, the function
        beneath) or the property.
    """
    for name, value in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(value, (staticmethod, classmethod)):
            value = value.__func__
        if inspect.isfunction(value) or isinstance(value, property):
            yield name, value
        elif callable(getattr(value, "func", None)) and hasattr(value, "attrname"):  # functools.cached_property
            yield name, value


def sections(doc: str | None) -> set[str]:
    """The numpydoc section titles of a docstring.

    Parameters
    ----------
    doc : str or None
        The docstring as :func:`inspect.getdoc` gives it (dedented).

    Returns
    -------
    set of str
        ``{"Parameters", "Returns", ...}``.
    """
    return set(_SECTION.findall(doc or ""))


def missing_sections(obj: Any, *, is_property: bool = False) -> list[str]:
    """What the docstring of a public function, method, property or class lacks.

    A docstring is required; a callable that takes parameters (other than ``self``/``cls``)
    needs a ``Parameters`` section (a class may document its fields under ``Attributes``
    instead); one that returns something (its return annotation is not ``None``; no
    annotation counts as returning) needs ``Returns`` or ``Yields``. A property needs only a
    docstring.

    Parameters
    ----------
    obj : object
        The function, method, class or property.
    is_property : bool
        Whether ``obj`` is a property (or cached property).

    Returns
    -------
    list of str
        ``"docstring"``, ``"Parameters"``, ``"Returns"``: empty when nothing is missing.
    """
    doc = inspect.getdoc(obj) if not is_property else (getattr(obj, "__doc__", None) or "").strip()
    if not doc:
        return ["docstring"]
    if is_property:
        return []
    found = sections(doc)
    if inspect.isclass(obj):  # its constructor's parameters, if it defines one (a Protocol does not)
        if getattr(obj, "_is_protocol", False) or ("__init__" not in vars(obj)
                                                    and not hasattr(obj, "__dataclass_fields__")):
            return []
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    missing = []
    params = [p for p in sig.parameters.values() if p.name not in ("self", "cls")]
    if params and not found & ({"Parameters", "Attributes"} if inspect.isclass(obj) else {"Parameters"}):
        missing.append("Parameters")
    if not inspect.isclass(obj):
        ret = sig.return_annotation
        if ret not in (None, "None") and not found & {"Returns", "Yields"}:
            missing.append("Returns")
    return missing
