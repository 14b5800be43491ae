"""Argparse option types and builders shared by the commands: finite numbers and whole numbers, the
factor, component, model, terms, block, random-effect, reader and goal options, and the per-
response options and groups (no heavy imports here)."""

from __future__ import annotations

import argparse
import math
from typing import Any

from ..io import InputError, quote_user_value
from .paths import output_option


def whole_number(minimum: int | None = None, maximum: int | None = None):
    """An argparse ``type`` for a whole number, at least ``minimum`` and at most ``maximum``
    when given (argparse turns the ArgumentTypeError into a usage error naming the option)."""

    def parse(text: str) -> int:
        q = quote_user_value(text)
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {q}") from None
        if minimum is not None and v < minimum:
            raise argparse.ArgumentTypeError(f"expected a whole number >= {minimum}, got {q}")
        if maximum is not None and v > maximum:
            raise argparse.ArgumentTypeError(f"expected a whole number <= {maximum}, got {q}")
        return v

    return parse


def number(minimum: float | None = None, maximum: float | None = None, *, above: bool = False,
           below: bool = False):
    """An argparse ``type`` for a finite number (``nan`` and ``inf`` refused) in a range.

    ``minimum``/``maximum`` are inclusive bounds; ``above=True`` makes the lower bound strict
    (``x > minimum``) and ``below=True`` the upper one. The usage error names the option.

    >>> number(0, 1, above=True, below=True)("0.5")
    0.5
    """
    lo = "" if minimum is None else (f"> {minimum:g}" if above else f">= {minimum:g}")
    hi = "" if maximum is None else (f"< {maximum:g}" if below else f"<= {maximum:g}")
    want = "a number" + (f" {lo}" if lo else "") + (" and" if lo and hi else "") + (f" {hi}" if hi else "")

    def parse(text: str) -> float:
        q = quote_user_value(text)
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected {want}, got {q}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"expected a finite number, got {q}")
        if minimum is not None and (v <= minimum if above else v < minimum):
            raise argparse.ArgumentTypeError(f"expected {want}, got {q}")
        if maximum is not None and (v >= maximum if below else v > maximum):
            raise argparse.ArgumentTypeError(f"expected {want}, got {q}")
        return v

    return parse


#: A probability or significance level strictly between 0 and 1.
probability = number(0, 1, above=True, below=True)


def add_plot_option(p: argparse.ArgumentParser, what: str) -> None:
    """``--plot PATH.png|PATH.svg``: an output file holding ``what``."""
    output_option(p.add_argument("--plot", metavar="PATH.png", default=None, help=f"write {what} (.png or .svg)"))


def plot_format(path: str | None) -> str | None:
    """``"png"`` or ``"svg"`` from the ``--plot`` file's extension (None without --plot); any
    other extension is an error naming the option, raised before any work."""
    if path is None:
        return None
    fmt = path.rsplit(".", 1)[-1].lower() if "." in path else ""
    if fmt not in ("png", "svg"):
        raise InputError(f"--plot: {path!r} must end in .png or .svg")
    return fmt


#: Option values that begin with '-' but are values, not options: a negative number in any
#: form (``-2.5e-1``, ``-1E3``), a negative range (``-3:12``, ``-3:``) and an inequality
#: (``-A+B<=1``). argparse (3.11) takes only ``-2`` and ``-0.5`` for values.
NEGATIVE_VALUE = r"^-(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?(:.*)?$|^-[^<>]*[<>]"


def accept_negative_values(parser: argparse.ArgumentParser) -> None:
    """Let ``parser``'s options take values that begin with '-' (:data:`NEGATIVE_VALUE`):
    ``--observed -2.5e-1``, ``--limits -3:12``, ``--constraint "-A+B<=1"``; argparse would
    read them as unknown options and answer "expected one argument"."""
    import re

    if hasattr(parser, "_negative_number_matcher"):  # argparse's own test for '-2' (3.11 to 3.13)
        parser._negative_number_matcher = re.compile(NEGATIVE_VALUE)


def add_region_options(parser: argparse.ArgumentParser, *, bound_help: str, constraint_help: str) -> None:
    """``--bound NAME=LOW:HIGH`` (or ``NAME=LEVEL[,LEVEL...]`` for a categoric factor) and
    ``--constraint EXPR`` (an inequality on the factors in actual units), both repeatable: the
    region options of ``optimize`` and ``report``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    bound_help, constraint_help : str
        The options' help texts (what the region limits in that command).

    Returns
    -------
    None
    """
    parser.add_argument("--bound", action="append", default=None, metavar="NAME=LOW:HIGH", help=bound_help)
    parser.add_argument("--constraint", action="append", default=None, metavar="EXPR", help=constraint_help)


def add_where_options(parser: argparse.ArgumentParser, what: str, *, most_workers: int = 256,
                      group: Any = None) -> None:
    """``--workers N`` or ``--scheduler ADDRESS`` (one of the two) and ``--scheduler-timeout S``:
    where a command's independent pieces of work run (local processes or a Dask cluster).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.
    what : str
        The work, as the help texts say it ("run batches", "draw the simulator's runs").
    most_workers : int
        The most local processes accepted.
    group : argparse argument group, optional
        Where the options are listed (default: the parser's options).

    Returns
    -------
    None
    """
    where = (group or parser).add_mutually_exclusive_group()
    where.add_argument("--workers", type=whole_number(1, most_workers), default=None, metavar="N",
                       help=f"{what} in N local processes (at most {most_workers}; the numbers do not depend on N)")
    where.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help=f"{what} on a Dask distributed scheduler (e.g. tcp://10.0.0.5:8786; the numbers are "
                            "those of one process)")
    (group or parser).add_argument("--scheduler-timeout", type=number(0, 3600, above=True), default=60.0, metavar="S",
                                   help="seconds the --scheduler has to answer before the run is refused (default 60)")


def add_force(p: argparse.ArgumentParser) -> None:
    p.add_argument("--force", action="store_true", help="overwrite existing output files")


def add_json(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", metavar="PATH|-", help="also write the result as JSON ('-' for stdout)")


def add_factor_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--factor", action="append", metavar="NAME[=LOW:HIGH]", default=None,
        help="a factor column, optionally with the levels coded -1 and +1 (repeatable; "
             "default: a design's factors, found from its coded_A, coded_B, ... columns, else every "
             "numeric column except the response, block and bookkeeping columns)",
    )


#: The model orders a command can fit (rsm_lrg.model.build.terms).
MODEL_ORDERS = ("linear", "2fi", "quadratic", "cubic")


#: The Scheffé mixture models (with ``--component``; rsm_lrg.model.build.mixture).
MIXTURE_MODEL_NAMES = ("mixture-linear", "mixture-quadratic", "special-cubic", "mixture-cubic")


#: Every model a fitting command's ``--model`` takes.
FIT_MODELS = MODEL_ORDERS + MIXTURE_MODEL_NAMES


#: ``--reduce`` methods (those of :data:`rsm_lrg.model.build.spec.REDUCE_METHODS`, not imported here so that
#: building the parser loads no NumPy; a test checks that they agree).
REDUCE_METHOD_NAMES = ("backward", "forward", "stepwise", "all-subsets", "dsd")


def add_component_option(p: argparse.ArgumentParser) -> None:
    """``--component NAME[=LOW:HIGH]`` (repeatable): mixture components, fitted by a Scheffé
    ``--model`` on L-pseudo components (rsm_lrg.model.build.mixture)."""
    p.add_argument(
        "--component", action="append", metavar="NAME[=LOW:HIGH]", default=None,
        help="a mixture component column (repeatable; with --model "
             "mixture-linear|mixture-quadratic|special-cubic|mixture-cubic): LOW is its lower bound and the L-pseudo "
             "origin (default: its observed minimum); every row must sum to the same total within 1e-4 relative",
    )


def add_model_option(p: argparse.ArgumentParser, orders=MODEL_ORDERS, what: str = "model order", *,
                     default: str | None = "quadratic") -> None:
    """``--model ORDER`` (default quadratic). For a fitted model ``default=None``: with
    ``--component`` and ``--terms`` the terms are the Scheffé model, so :func:`model_spec`
    decides the order when none was given."""
    p.add_argument("--model", default=default, choices=list(orders),
                   help=f"{what} (default quadratic; with --component and --terms, the terms' Scheffé model)")


def add_terms_options(parser: argparse.ArgumentParser, *, per_response: bool = False) -> None:
    """``--terms "A B AB A^2"`` (an explicit model; beside ``--model``) and ``--no-intercept``."""
    kw: dict[str, Any] = {"action": PerResponseOption} if per_response else {}
    flag: dict[str, Any] = {"action": PerResponseOption, "nargs": 0, "const": True, "default": False} \
        if per_response else {"action": "store_true"}
    parser.add_argument("--terms", default=None, metavar='"A B AB A^2"',
                        help="fit exactly these terms instead of --model: letters, products (AB), powers (a term "
                             "of degree at most 20: A^3, A^2B), categoric terms as in the ANOVA; space- or comma-separated", **kw)
    parser.add_argument("--no-intercept",
                        help="fit without an intercept (with --terms; the ANOVA total is then uncorrected, as R's lm)",
                        **flag)


def add_block_option(p: argparse.ArgumentParser, role: str = "effects sum to zero") -> None:
    """``--block COL``; ``role`` says what the command does with the blocks."""
    p.add_argument("--block", metavar="COL", default=None, help=f"block column ({role})")


def add_random_effect_options(p: argparse.ArgumentParser) -> None:
    """``--whole-plot COL`` and ``--random-block COL``: a random intercept, fitted by REML with
    Kenward-Roger tests (:mod:`rsm_lrg.model.engines.mixed`)."""
    g = p.add_mutually_exclusive_group()
    g.add_argument("--whole-plot", metavar="COL", default=None,
                   help="whole-plot column of a split-plot experiment: a random intercept per whole plot, fitted by "
                        "REML with Kenward-Roger F tests")
    g.add_argument("--random-block", metavar="COL", default=None,
                   help="block column whose blocks are a random intercept (REML, Kenward-Roger), not fixed effects")
    p.add_argument("--random-effect", action="append", default=None, metavar="COL",
                   help="a grouping column with a random intercept (repeatable: several variance components, nested "
                        "or crossed as the data say, e.g. a split-split-plot's whole plots and subplots, a "
                        "strip-plot's rows and columns); fitted by REML with Kenward-Roger F tests; each value of "
                        "the column is one level, so a nested column needs unique labels; A:B is the interaction "
                        "of two columns. With --whole-plot or --random-block that column comes first")
    p.add_argument("--hard-to-change", action="append", default=None, metavar="NAME",
                   help="with --whole-plot: a factor that must be constant within every whole plot (repeatable); one "
                        "that varies inside a whole plot is an error naming the whole plot")


def add_data_response(parser: argparse.ArgumentParser, several: str | None = None) -> None:
    """DATA.csv (the runs), the reader options and ``--response COL``: what every analysis
    command reads. With ``several`` (its help), ``--response`` is repeatable and each one groups
    the model options that follow it (:class:`ResponseGroup`)."""
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each (CSV, .xlsx, .parquet or - for stdin)")
    if several is None:
        parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    else:
        parser.add_argument("--response", required=True, action=ResponseGroup, metavar="COL", help=several)
    add_reader_options(parser)


def check_at_settings(settings) -> None:
    """Each --at value is NAME=VALUE with a VALUE that is a finite number or, for a
    categoric factor, a level (checked against the factor once the data are read)."""
    from ..io import InputError

    for s in settings:
        name, sep, value = str(s).partition("=")
        ok = bool(sep and name.strip() and value.strip())
        if ok:
            try:
                ok = math.isfinite(float(value))
            except ValueError:
                ok = True  # a categoric level
        if not ok:
            raise InputError(f"--at {quote_user_value(s)}: expected NAME=VALUE with a finite number VALUE "
                             "(or a level of a categoric factor)")


#: ``--sep`` words for separators awkward to type.
SEP_WORDS = {"tab": "\t", "\\t": "\t", "comma": ",", "semicolon": ";", "pipe": "|"}


def _separator(text: str) -> str:
    sep = SEP_WORDS.get(text.lower(), text)
    if sep not in (",", ";", "\t", "|"):
        raise argparse.ArgumentTypeError(f"{text!r} is not a separator read (one of , ; tab |)")
    return sep


def add_reader_options(parser: argparse.ArgumentParser) -> None:
    """``--sep``, ``--decimal`` and ``--sheet``: how the input table is read
    (:func:`rsm_lrg.io.read_table`)."""
    g = parser.add_argument_group("reading the input table")
    g.add_argument("--sep", type=_separator, default=None, metavar="SEP",
                   help="CSV separator: , ; tab or | (default: detected, and stated)")
    g.add_argument("--decimal", choices=[".", ","], default=".", help="CSV decimal mark (default .)")
    g.add_argument("--sheet", metavar="NAME", default=None,
                   help="the sheet of an .xlsx workbook (needed when it has several)")


def add_model_inputs(parser: argparse.ArgumentParser, orders=FIT_MODELS) -> None:
    """DATA.csv, --response, --factor, --block and --model (one of ``orders``): the inputs of a fitted model."""
    add_data_response(parser)
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser)
    add_model_option(parser, orders, default=None)


class ResponseGroup(argparse.Action):
    """``--response COL`` that opens an option group: the per-response options
    (:class:`PerResponseOption`) that follow it apply to that response only. The columns are
    appended to ``dest``; the groups are kept in ``namespace.response_options`` (one dict per
    --response, in order)."""

    def __call__(self, parser, namespace, values, option_string=None):
        items = list(getattr(namespace, self.dest, None) or [])
        items.append(values)
        setattr(namespace, self.dest, items)
        groups = list(getattr(namespace, "response_options", None) or [])
        groups.append({})
        namespace.response_options = groups


class PerResponseOption(argparse.Action):
    """An option that belongs to the most recent ``--response`` (a :class:`ResponseGroup`);
    given before any --response it is the default for every response. ``nargs=0`` with
    ``const`` makes a flag."""

    def __call__(self, parser, namespace, values, option_string=None):
        value = self.const if self.nargs == 0 else values
        groups = getattr(namespace, "response_options", None)
        if groups:
            if self.dest in groups[-1]:
                raise argparse.ArgumentError(self, f"given twice for --response {namespace.response[-1]!r}")
            groups[-1][self.dest] = value
        else:
            setattr(namespace, self.dest, value)


def response_options(args: argparse.Namespace, i: int) -> argparse.Namespace:
    """The options of the i-th ``--response``: the command-wide values overridden by those
    given after that --response."""
    out = argparse.Namespace(**vars(args))
    groups = getattr(args, "response_options", None) or []
    if i < len(groups):
        for k, v in groups[i].items():
            setattr(out, k, v)
    return out


def add_model_refinements(parser: argparse.ArgumentParser, *, per_response: bool = False,
                          model: bool = False, gp: bool = False) -> None:
    """fit's model options: ``--reduce``, ``--alpha-out``, ``--criterion``, ``--transform``,
    ``--transform-constant`` (and ``--model`` when ``model``; ``--model gp`` too when ``gp``: a
    Gaussian process with its defaults, as ``fit --model gp``). With ``per_response`` each one
    given after a ``--response`` (declared with :class:`ResponseGroup`) applies to that
    response only; see :func:`response_options` and :func:`model_spec`."""
    kw: dict[str, Any] = {"action": PerResponseOption} if per_response else {}
    if model:
        parser.add_argument("--model", default=None, choices=[*FIT_MODELS, *(["gp"] if gp else [])],
                            help="model order (default quadratic; with --component and --terms the terms are the "
                                 "Scheffé model)", **kw)
    add_terms_options(parser, per_response=per_response)
    reduce_kw: dict[str, Any] = dict(kw, nargs="?", const="backward", default=False, choices=list(REDUCE_METHOD_NAMES))
    parser.add_argument("--reduce", metavar="backward|forward|stepwise|all-subsets|dsd",
                        help="choose the terms, hierarchy kept: backward elimination (the default), forward or "
                             "stepwise selection, the best of all hierarchical subsets, or dsd: the two-stage "
                             "analysis of a definitive screening design (main effects from the fold-over pairs, then "
                             "second-order terms of the active factors; threshold --alpha-in)", **reduce_kw)
    parser.add_argument("--alpha-out", type=number(0, 1, above=True, below=True), default=0.1, metavar="A",
                        help="with --reduce and --criterion p: remove terms while p > A (default 0.1)", **kw)
    parser.add_argument("--alpha-in", type=number(0, 1, above=True, below=True), default=None, metavar="A",
                        help="with --reduce forward|stepwise and --criterion p: add terms while p < A (default "
                             "0.1); with --reduce dsd: the threshold of both stages (default 0.05)",
                        **kw)
    parser.add_argument("--criterion", default=None, choices=["p", "aicc", "bic"],
                        help="with --reduce: by p-value (default), or while AICc or BIC falls (all-subsets: the "
                             "lowest AICc (default) or BIC)", **kw)
    parser.add_argument("--transform", default=None, metavar="log|log10|sqrt|inverse|power=L",
                        help="fit a transformed response (predictions and intervals back-transformed)", **kw)
    parser.add_argument("--transform-constant", type=number(), default=0.0, metavar="K",
                        help="add K to the response before transforming (default 0)", **kw)


def add_goal_options(parser: argparse.ArgumentParser, *, goal_help: str, limits_help: str,
                     goal_metavar: str = "minimize|maximize|target=V", desirability: bool = False) -> None:
    """Each response's ``--goal`` and ``--limits`` (repeatable, one per ``--response``), and with
    ``desirability`` its ``--weight`` and ``--importance`` (Derringer-Suich, Stat-Ease
    conventions): the options ``optimize`` and ``report`` share. ``goal_help`` and
    ``limits_help`` say what the command does with them."""
    kw: dict[str, Any] = {"action": ResponseValue, "default": None}
    parser.add_argument("--goal", metavar=goal_metavar, help=goal_help, **kw)
    if desirability:
        parser.add_argument("--weight", metavar="W[,W2]",
                            help="desirability weight 0.1..10 per response (multi-response; default 1)", **kw)
        parser.add_argument("--importance", metavar="R",
                            help="importance 1..5 per response (multi-response; default 3)", **kw)
    parser.add_argument("--limits", metavar="LOW:HIGH", help=limits_help, **kw)


class ResponseValue(argparse.Action):
    """A repeatable per-response value (``--goal``, ``--limits``, ...): each one is kept with
    the index of the ``--response`` it follows (-1 before the first), for
    :func:`per_response_values`."""

    def __call__(self, parser, namespace, values, option_string=None):
        items = list(getattr(namespace, self.dest, None) or [])
        items.append((len(getattr(namespace, "response", None) or []) - 1, values))
        setattr(namespace, self.dest, items)


def check_distinct_responses(responses) -> None:
    """Each ``--response`` once: a repeated one is an error naming it."""
    seen = set()
    for r in responses:
        if r in seen:
            raise InputError(f"--response: each response may be given once ({quote_user_value(r)} is given twice)")
        seen.add(r)


def per_response_values(items, n: int, option: str) -> list:
    """The values of a :class:`ResponseValue` option for ``n`` responses (None where not given).

    A value given right after a ``--response`` belongs to that response (``--response Y1
    --response Y2 --goal maximize`` maximises Y2); values listed together (several after the
    same ``--response``, or before the first) are taken in ``--response`` order (``--response
    Y1 --response Y2 --goal maximize --goal minimize``). More values than responses is an
    error naming the option.

    >>> per_response_values([(1, "maximize")], 2, "--goal")
    [None, 'maximize']
    >>> per_response_values([(1, "maximize"), (1, "minimize")], 2, "--goal")
    ['maximize', 'minimize']
    >>> per_response_values(["minimize"], 2, "--goal")  # plain values: in order
    ['minimize', None]
    """
    items = [v if isinstance(v, tuple) else (-1, v) for v in (items or [])]
    if len(items) > n:
        raise InputError(f"{option}: more values ({len(items)}) than --response options ({n})")
    positions = [p for p, _ in items]
    if all(p >= 0 for p in positions) and all(a < b for a, b in zip(positions, positions[1:])):
        out = [None] * n
        for p, v in items:
            out[p] = v
        return out
    return [v for _, v in items] + [None] * (n - len(items))


def add_boxcox_rule_option(parser: argparse.ArgumentParser) -> None:
    """``--boxcox-rule likelihood|design-expert`` for a command that prints Box–Cox (pass
    ``boxcox_rule=args.boxcox_rule`` to ``FitResult.diagnostics``)."""
    parser.add_argument("--boxcox-rule", default="likelihood", choices=["likelihood", "design-expert"],
                        help="Box-Cox lambda and interval: maximum likelihood with the chi-square(1) "
                             "interval (default), or Design-Expert's rule (grid minimum, ln SS_min + t^2/df)")
