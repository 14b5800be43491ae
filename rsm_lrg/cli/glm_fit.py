"""``rsm-lrg fit --family binomial|poisson [--link L] [--trials COL]``: a generalised linear
model of a pass/fail or count response (:mod:`rsm_lrg.model.pipelines.glm`), for ``cmd_fit``.

The options are added by :func:`add_glm_options`; :func:`wants_glm` says whether they were
given and :func:`run_glm` makes the one library call and writes the text or the JSON
(``--json PATH`` also prints the text; ``--json -`` prints the JSON instead).
"""

from __future__ import annotations

import argparse

from ..io import InputError

__all__ = ["add_glm_options", "wants_glm", "run_glm", "GLM_UNSUPPORTED", "FAMILY_NAMES", "LINK_NAMES"]

#: ``--family`` and ``--link`` choices: those of :mod:`rsm_lrg.model.engines.glm_family` (not imported
#: here, so that building the parser loads no NumPy; a test checks that they agree).
FAMILY_NAMES = ("binomial", "poisson")
LINK_NAMES = ("logit", "probit", "cloglog", "log")

#: fit's options that a GLM does not take yet (checked before any data is read).
GLM_UNSUPPORTED = ("transform", "diagnostics", "report", "block", "component", "whole_plot", "random_block",
                   "random_effect", "hard_to_change")


def add_glm_options(parser: argparse.ArgumentParser) -> None:
    """``--family``, ``--link`` and ``--trials``."""
    g = parser.add_argument_group("pass/fail and count responses (generalised linear model)")
    g.add_argument("--family", choices=list(FAMILY_NAMES), default=None,
                   help="fit a generalised linear model by maximum likelihood: binomial (a 0/1 response, or successes "
                        "with --trials) or poisson (a count); prints the analysis of deviance")
    g.add_argument("--link", choices=list(LINK_NAMES), default=None,
                   help="with --family: the link (binomial: logit (default), probit, cloglog; poisson: log)")
    g.add_argument("--trials", metavar="COL", default=None,
                   help="with --family binomial: the column of trials per row; the response counts the successes")


def wants_glm(args: argparse.Namespace) -> bool:
    """Whether ``--family``, ``--link`` or ``--trials`` was given."""
    return any(getattr(args, o, None) is not None for o in ("family", "link", "trials"))


def run_glm(args: argparse.Namespace) -> int:
    """Fit the GLM of the command's options and print it (text or JSON)."""
    from ..io import dump_json
    from ..model import fit
    from .errors import about_file
    from .paths import print_notes, read_input
    from .specs import model_spec

    if args.family is None:
        raise InputError(f"--{'link' if args.link is not None else 'trials'}: give --family binomial or --family "
                         "poisson too")
    for opt in GLM_UNSUPPORTED:
        value = getattr(args, opt, None)
        if value not in (None, False, []):
            raise InputError(f"--{opt.replace('_', '-')}: not available with --family (a generalised linear model) "
                             "yet")
    spec = model_spec(args)  # a bad --model/--terms is named before any data is read
    data = read_input(args)
    with about_file(args.data):
        result = fit(data, args.response, factors=args.factor, model=spec, family=args.family, link=args.link,
                     trials=args.trials)
        out = result.to_dict()
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.json == "-":
        print_notes(result.input_notes)
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        print(result.summary(), end="")
    return 0
