"""``rsm-lrg fit --model gp``: the Gaussian-process options of ``fit`` (``--kernel``,
``--trend``, ``--nugget``, ``--seed``) and the run of a GP fit (text or ``--json``)."""

from __future__ import annotations

import argparse
import math

from ..io import InputError, quote_user_value

__all__ = ["GP_MODELS", "add_gp_options", "check_gp_options", "gp_keywords", "run_gp"]

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


def add_gp_options(parser: argparse.ArgumentParser) -> None:
    """``--kernel``, ``--trend``, ``--nugget`` and ``--seed`` (with ``--model gp``)."""
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


def check_gp_options(args: argparse.Namespace, *, on: bool | None = None, flag: str = "--model gp") -> None:
    """The GP options given without ``--model gp`` (``on`` false; default: ``args.model`` is
    not ``gp``) are an error naming the option and ``flag``."""
    if on is None:
        on = getattr(args, "model", None) in GP_MODELS
    if on:
        return
    for opt, attr in (("--kernel", "kernel"), ("--trend", "trend"), ("--nugget", "nugget"), ("--seed", "seed")):
        if getattr(args, attr, None) is not None:
            raise InputError(f"{opt}: only with {flag} (a Gaussian process)")


def gp_keywords(args: argparse.Namespace) -> dict:
    """The ``kernel=``, ``trend=``, ``nugget=``, ``seed=`` keywords of ``rsm_lrg.fit`` from the options."""
    return {"kernel": args.kernel or "matern52", "trend": args.trend or "constant", "nugget": args.nugget,
            "seed": 0 if args.seed is None else args.seed}


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
