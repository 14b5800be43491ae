"""The option, file or response at fault in an error: :func:`option_error` names a library error's
option by its ``parameter`` attribute (no message tables), :func:`about_file` and
:func:`about_response` name the file and the response."""

from __future__ import annotations

import argparse
from collections.abc import Iterator, Mapping
from contextlib import contextmanager

from ..io import STDIN_NAME, InputError, quote_user_value


@contextmanager
def about_file(path):
    """Re-raise a ValueError from the library as InputError: one that says which parameter it
    concerns (:class:`rsm_lrg.errors.ParameterError`) names that parameter's option (see
    :func:`option_error`), any other is prefixed with the file name."""
    from ..errors import ParameterError

    try:
        yield
    except InputError:
        raise
    except ParameterError as exc:  # the library checked an option's value (perhaps after the data were read)
        raise option_error(exc) from None
    except ValueError as exc:
        raise InputError(f"{STDIN_NAME if str(path) == '-' else path}: {exc}") from None


@contextmanager
def about_response(response: str, several: bool):
    """With ``several`` responses, a ValueError from one response's fit names that response
    (``response 'y2': the quadratic model cannot be estimated ...``) unless it is about an
    option (an :class:`~rsm_lrg.io.InputError` or a :class:`~rsm_lrg.errors.ParameterError`)
    or names the response already; :func:`about_file` then puts the file name in front."""
    from ..errors import ParameterError

    if not several:
        yield
        return
    try:
        yield
    except (InputError, ParameterError):
        raise
    except ValueError as exc:
        if quote_user_value(response) in str(exc):
            raise
        raise ValueError(f"response {quote_user_value(response)}: {exc}") from None


@contextmanager
def about_options(*, options: Mapping[str, str] | None = None, default: str | None = None,
                  catch: tuple[type[Exception], ...] = (ValueError,)) -> Iterator[None]:
    """Re-raise a library error (of the types ``catch``) as the InputError :func:`option_error`
    makes of it, naming its option; an InputError passes as it is.

    Parameters
    ----------
    options, default
        As for :func:`option_error`.
    catch : tuple of exception types
        The errors to name (ValueError and its kin by default).

    Yields
    ------
    None
    """
    try:
        yield
    except InputError:
        raise
    except catch as exc:
        raise option_error(exc, options=options, default=default) from None


#: The command-line option of each library parameter an error names
#: (:class:`rsm_lrg.errors.ParameterError`'s ``parameter``, e.g. a model specification's).
PARAMETER_OPTIONS = {
    "model": "--model", "terms": "--terms", "transform": "--transform", "reduce": "--alpha-out",
    "alpha_out": "--alpha-out", "alpha": "--alpha", "confidence": "--confidence", "bound": "--bound",
    "goal": "--goal", "radius": "--radius", "step": "--step", "setting": "--at", "weight": "--weight",
    "importance": "--importance", "limits": "--limits", "criterion": "--criterion", "effect_sd": "--effect",
    "region": "--region", "observed": "--observed", "held": "--bound", "parameters": "--parameter",
    "constraints": "--constraint", "random_effects": "--random-effect", "variance_ratios": "--variance-ratio-of",
}


def option_error(exc: Exception, opts: argparse.Namespace | None = None, *,
                 options: Mapping[str, str] | None = None, default: str | None = None) -> InputError:
    """An InputError naming the option of an error that says which parameter it concerns.

    Parameters
    ----------
    exc : Exception
        The library's error; its ``parameter`` attribute (:class:`rsm_lrg.errors.ParameterError`)
        alone chooses the option, never its message.
    opts : argparse.Namespace, optional
        The parsed options: the value given is shown after the option when it is text.
    options : mapping, optional
        The command's own options of library parameters, before :data:`PARAMETER_OPTIONS`
        (where a parameter means another option in this command, e.g. ``runs`` -> ``--runs``).
    default : str, optional
        The option of an error without a parameter (``--factor``); without it such an error
        keeps its bare message.

    Returns
    -------
    InputError
        ``--option [VALUE]: message``.

    Examples
    --------
    >>> from rsm_lrg.errors import ParameterError
    >>> str(option_error(ParameterError("alpha_out", "alpha_out must lie between 0 and 1, not 2")))
    '--alpha-out: alpha_out must lie between 0 and 1, not 2'
    >>> str(option_error(ParameterError("runs", "at most 10000 runs"), options={"runs": "--runs"}))
    '--runs: at most 10000 runs'
    >>> str(option_error(ValueError("no such factor"), default="--factor"))
    '--factor: no such factor'
    """
    param = getattr(exc, "parameter", None)
    if param is None:
        return InputError(f"{default}: {exc}" if default else str(exc))
    param = str(param)
    flag = (options or {}).get(param) or PARAMETER_OPTIONS.get(param, "--" + param.replace("_", "-"))
    value = getattr(opts, flag[2:].replace("-", "_"), None) if opts is not None else None
    shown = f" {quote_user_value(value)}" if isinstance(value, str) else ""
    return InputError(f"{flag}{shown}: {exc}")
