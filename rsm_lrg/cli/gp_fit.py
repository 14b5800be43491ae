"""``rsm-lrg fit --model gp``: the Gaussian-process options of ``fit`` (``--kernel``,
``--trend``, ``--nugget``, ``--seed``, ``--length-scale-bounds``) and the run of a GP fit (text or ``--json``)."""

from __future__ import annotations

import argparse
import math

from ..io import InputError, quote_user_value

__all__ = ["GP_MODELS", "add_gp_options", "check_gp_options", "gp_keywords", "length_scale_bounds", "run_gp"]

#: The ``--model`` value of a Gaussian process.
GP_MODELS = ("gp",)
KERNEL_CHOICES = ("matern52", "matern32", "gauss")
TREND_CHOICES = ("constant", "linear", "quadratic")


def _nugget(text: str) -> str | float:
    if text.strip().lower() == "estimate":
        return "estimate"
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected 'estimate' or a number >= 0, got {quote_user_value(text)}") from None
    if not math.isfinite(v) or v < 0:
        raise argparse.ArgumentTypeError(f"expected 'estimate' or a finite number >= 0, got {quote_user_value(text)}")
    return v


def _seed(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {quote_user_value(text)}") from None
    if v < 0:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0, got {quote_user_value(text)}")
    return v


def length_scale_bounds(text: str) -> tuple[float, float]:
    """``--length-scale-bounds LOW:HIGH``: two finite numbers, ``0 < LOW < HIGH`` (multiples of
    each factor's coded range in the data; an ``argparse`` type).

    Parameters
    ----------
    text : str
        The option's value.

    Returns
    -------
    (float, float)
        ``(LOW, HIGH)``.
    """
    from ..errors import ParameterError
    from ..model.pipelines.gp import check_length_scale_bounds  # the library's check, the option's words

    lo_text, sep, hi_text = text.partition(":")
    try:
        if sep:
            return check_length_scale_bounds((lo_text, hi_text))
    except ParameterError:
        pass
    raise argparse.ArgumentTypeError(f"expected LOW:HIGH, two finite numbers with 0 < LOW < HIGH, got "
                                     f"{quote_user_value(text)}")


def add_gp_options(parser: argparse.ArgumentParser, *, loop_bounds: bool = False) -> None:
    """``--kernel``, ``--trend``, ``--nugget``, ``--seed`` and ``--length-scale-bounds`` (with
    ``--model gp``).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    loop_bounds : bool
        The command chooses runs (``suggest``): its length-scale bounds default to the loop's,
        :data:`rsm_lrg.model.pipelines.gp.LOOP_THETA_BOUNDS` (see :func:`gp_keywords`).
    """
    g = parser.add_argument_group("Gaussian process (with --model gp)")
    g.add_argument("--kernel", default=None, choices=list(KERNEL_CHOICES),
                   help="correlation kernel, one length-scale per factor on the coded factors (default matern52)")
    g.add_argument("--trend", default=None, choices=list(TREND_CHOICES),
                   help="trend, by generalised least squares (default constant)")
    g.add_argument("--nugget", default=None, type=_nugget, metavar="estimate|VALUE",
                   help="estimate the nugget (noisy runs) or fix it [response units^2]; default: estimated when runs "
                        "share a setting, else 0 (the model interpolates the runs)")
    g.add_argument("--seed", default=None, type=_seed, metavar="S",
                   help="seed of the likelihood's starting points (default 0)")
    g.add_argument("--length-scale-bounds", default=None, type=length_scale_bounds, metavar="LOW:HIGH",
                   help="bounds of the estimated length-scales, as multiples of each factor's coded range in the "
                        + ("data (default 0.001:2, as the loop's; the upper one is R DiceKriging km's default)"
                           if loop_bounds else "data (default 0.001:10; 0.001:2 has R DiceKriging km's default upper "
                                               "bound, which loop and suggest use)"))


def _refuse(args: argparse.Namespace) -> None:
    """An InputError naming the first option that a GP fit does not take."""
    for opt, attr in (("--block", "block"), ("--component", "component"), ("--terms", "terms"),
                      ("--no-intercept", "no_intercept"), ("--transform", "transform"), ("--reduce", "reduce"),
                      ("--whole-plot", "whole_plot"), ("--random-block", "random_block"),
                      ("--random-effect", "random_effect"),
                      ("--hard-to-change", "hard_to_change"), ("--diagnostics", "diagnostics"),
                      ("--report", "report")):
        if getattr(args, attr, None):
            raise InputError(f"{opt}: not available with --model gp (a Gaussian process)")


def check_gp_options(args: argparse.Namespace, *, on: bool | None = None, flag: str = "--model gp",
                     keep: tuple[str, ...] = ()) -> None:
    """The GP options given without ``--model gp`` (``on`` false; default: ``args.model`` is
    not ``gp``) are an error naming the option and ``flag``; ``keep`` names the attributes a
    command uses without a GP as well (``suggest``'s ``seed``)."""
    if on is None:
        on = getattr(args, "model", None) in GP_MODELS
    if on:
        return
    for opt, attr in (("--kernel", "kernel"), ("--trend", "trend"), ("--nugget", "nugget"), ("--seed", "seed"),
                      ("--length-scale-bounds", "length_scale_bounds")):
        if attr not in keep and getattr(args, attr, None) is not None:
            raise InputError(f"{opt}: only with {flag} (a Gaussian process)")


def gp_keywords(args: argparse.Namespace, *, loop_bounds: bool = False) -> dict:
    """The ``kernel=``, ``trend=``, ``nugget=``, ``seed=``, ``length_scale_bounds=`` keywords of
    ``rsm_lrg.fit`` from the options.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.
    loop_bounds : bool
        Without ``--length-scale-bounds``, the loop's bounds
        (:data:`rsm_lrg.model.pipelines.gp.LOOP_THETA_BOUNDS`) instead of ``fit``'s default.

    Returns
    -------
    dict
        Keywords of :func:`rsm_lrg.fit`.
    """
    bounds = getattr(args, "length_scale_bounds", None)
    if bounds is None and loop_bounds:
        from ..model.pipelines.gp import LOOP_THETA_BOUNDS

        bounds = LOOP_THETA_BOUNDS
    return {"kernel": args.kernel or "matern52", "trend": args.trend or "constant", "nugget": args.nugget,
            "seed": 0 if args.seed is None else args.seed, "length_scale_bounds": bounds}


def run_gp(args: argparse.Namespace) -> int:
    """Fit the GP and print its summary, or its JSON with ``--json``."""
    from ..io import dump_json
    from ..model import fit
    from .errors import about_file
    from .paths import print_notes, read_input

    _refuse(args)
    from .file_sets import expand_data_path

    if expand_data_path(str(args.data)) is not None:
        raise InputError(f"{args.data}: a Gaussian process is fitted from one file, not several")
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, model="gp", **gp_keywords(args))
        out = result.to_dict()
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.json == "-":
        print_notes(result.notes)
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        print(result.summary(), end="")
    return 0
