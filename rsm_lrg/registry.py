"""Conveniences that a lower layer offers and a higher layer provides.

``FitResult.optimize``, ``FitResult.to_html``, ``FitResult.profiler`` and ``FitResult._repr_html_`` are methods of
the model layer, but the work is done by the optimize and report layers above it. The model
must not import them (the layers are one-way, checked by import-linter), so the methods ask
this registry for the function registered under a name and call it.

The wiring is declared once, by the package facade ``rsm_lrg/__init__.py`` (which Python
always runs before any of its sub-modules), as ``"module:function"`` strings resolved on the
first call. A higher layer (or a user) may also register a function object directly with
:func:`register`; the last registration wins.

>>> from rsm_lrg import registry
>>> registry.names()
['FitResult.notebook_html', 'FitResult.optimize', 'FitResult.profiler', 'FitResult.to_html', 'fit']
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["register", "lookup", "provider", "names"]

_PROVIDERS: dict[str, str | Callable] = {}


def register(name: str, provider: str | Callable) -> None:
    """Register ``provider`` (a callable, or ``"module:function"`` imported on first use)
    under ``name`` (e.g. ``"FitResult.optimize"``)."""
    if not (callable(provider) or (isinstance(provider, str) and provider.count(":") == 1)):
        raise TypeError(f"provider for {name!r} must be a callable or 'module:function', not {provider!r}")
    _PROVIDERS[name] = provider


def provider(name: str) -> str | Callable | None:
    """What is registered under ``name`` (``None`` when nothing is)."""
    return _PROVIDERS.get(name)


def names() -> list[str]:
    """The registered names, sorted."""
    return sorted(_PROVIDERS)


def lookup(name: str) -> Callable:
    """The function registered under ``name``, imported on first use."""
    p = _PROVIDERS.get(name)
    if p is None:
        raise NotImplementedError(f"{name} is not available: no layer has registered it")
    if isinstance(p, str):
        import importlib

        module, _, attr = p.partition(":")
        p = getattr(importlib.import_module(module), attr)
        _PROVIDERS[name] = p
    return p
