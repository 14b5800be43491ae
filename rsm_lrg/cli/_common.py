"""Pieces shared by the command modules (no heavy imports here), by concern: argparse option
types and builders (finite numbers, factor and bound specs, per-response options and groups),
input reading and the naming of the file, column or option at fault in an error, the model
options as a specification (:func:`model_spec`, :func:`random_effect`), output paths and the
outputs a command plans, and the one-line summaries and notes a command prints."""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Mapping
from contextlib import contextmanager
from typing import Any

from ..io import STDIN_NAME, InputError, check_output, quote_user_value, show_path


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

#: Destinations (argparse ``dest``) of the options that name an output file; ``planned_outputs``
#: checks every one of them before a command runs.
OUTPUT_DESTS = ("output", "json", "report")


def output_option(action: argparse.Action) -> argparse.Action:
    """Mark an option as naming an output file (for a dest outside :data:`OUTPUT_DESTS`):
    ``output_option(p.add_argument("--html", metavar="PATH"))``. It is then checked with the
    others before the command runs and written in the same transaction."""
    action.rsm_output = True  # type: ignore[attr-defined]  # our marker on argparse's Action
    return action


def output_labels(parser: argparse.ArgumentParser) -> dict[str, str]:
    """``{dest: "-o/--output"}`` for the output options of ``parser``."""
    return {a.dest: "/".join(a.option_strings) for a in parser._actions
            if (a.dest in OUTPUT_DESTS or getattr(a, "rsm_output", False)) and a.option_strings}


def path_labels(parser: argparse.ArgumentParser) -> dict[str, str]:
    """``{dest: label}`` for the other arguments that name a file (metavar ``PATH``,
    ``DATA.csv``, ``PATH.toml``): an empty value is an error naming them."""
    outs = output_labels(parser)
    found = {}
    for a in parser._actions:
        mv = a.metavar if isinstance(a.metavar, str) else ""
        if a.dest not in outs and ("PATH" in mv or mv.lower().endswith((".csv", ".toml"))):
            found[a.dest] = "/".join(a.option_strings) or mv
    return found


def mark_outputs(parser: argparse.ArgumentParser) -> None:
    """Record the output options of ``parser`` and of its sub-parsers on the parsed namespace
    (``_output_labels``), for :func:`planned_outputs`, and the other file arguments
    (``_path_labels``)."""
    parser.set_defaults(_output_labels=output_labels(parser), _path_labels=path_labels(parser))
    for a in parser._actions:
        if isinstance(a, argparse._SubParsersAction):
            for sp in a.choices.values():
                mark_outputs(sp)


def matched_files(path: str) -> list[str]:
    """The files the DATA argument reads when it names several (a directory, or a glob pattern
    when no file of that name exists: :func:`rsm_lrg.cli.file_sets.expand_data_path`). Empty
    for one file."""
    from .file_sets import expand_data_path

    return expand_data_path(path) or []


#: The name that stands for standard input when it is a file the shell opened (``fit - < runs.csv``).
STDIN_PATH = "/dev/stdin"


def _regular_stream(fd: int):
    """``os.fstat(fd)`` when descriptor ``fd`` is open on a regular file, else None."""
    import stat

    try:
        st = os.fstat(fd)
    except (OSError, ValueError):
        return None
    return st if stat.S_ISREG(st.st_mode) else None


def input_paths(args: argparse.Namespace) -> list[str]:
    """Every option or argument value (other than an output) that names an existing file: the
    files a command may read, which it must never write (with every file that a directory or
    glob given as DATA matches: :func:`matched_files`). An input given as ``-`` whose standard
    input is a file (``fit - < runs.csv``) counts as that file (:data:`STDIN_PATH`)."""
    labels = getattr(args, "_output_labels", {}) or {}
    found = []
    for dest, value in vars(args).items():
        if dest.startswith("_") or dest in labels or dest in OUTPUT_DESTS:
            continue
        if dest == "data" and isinstance(value, str) and len(value) < 4096:
            found.extend(matched_files(value))
        if value == "-" and STDIN_PATH not in found and _regular_stream(0) is not None:
            found.append(STDIN_PATH)
        for v in value if isinstance(value, (list, tuple)) else [value]:
            if isinstance(v, (str, os.PathLike)) and str(v) and str(v) != "-" and len(str(v)) < 4096:
                try:
                    if os.path.lexists(v) and not os.path.isdir(v):
                        found.append(str(v))
                except (OSError, ValueError):
                    pass
    return found


def planned_outputs(args: argparse.Namespace, module=None) -> list[tuple[str, str]]:
    """Check every output of the command before it runs, or raise InputError naming the option.

    The outputs are the values of the options in ``args._output_labels`` (``'-'`` for
    ``--json`` is standard output), or what ``module.outputs(args)`` returns when the command
    defines it. Each must pass :func:`rsm_lrg.io.check_output` (not empty, not a directory,
    absent unless ``--force``, its directory writable, not an input file) and no two may name
    the same file.
    """
    labels = getattr(args, "_output_labels", {}) or {}
    hook = getattr(module, "outputs", None)
    if hook is not None:
        pairs = list(hook(args))
    else:
        pairs = [(labels[d], getattr(args, d)) for d in labels if getattr(args, d, None) is not None]
    force = bool(getattr(args, "force", False))
    inputs = input_paths(args)
    check_standard_output(inputs)
    checked: list[tuple[str, str]] = []
    for label, path in pairs:
        if str(path) == "-":
            if "json" in label:
                continue
            raise InputError(f"cannot write {label} -: '-' (standard output) is taken by --json only; give a file "
                             f"name (./- for a file named '-', /dev/stdout for standard output)")
        p = check_output(path, force=force, inputs=inputs, option=label, probe=True)
        for other_label, other in checked:
            if os.path.realpath(other) == os.path.realpath(p) or _samefile(other, p):
                raise InputError(f"cannot write {label} {show_path(p)}: "
                                 f"{other_label} names the same file")
        checked.append((label, str(p)))
    return checked


def claim_standard_output(args: argparse.Namespace, outputs: list[tuple[str, str]]) -> bool:
    """Make an output that names standard output (``/dev/stdout``, ``/dev/fd/1``, a link to
    one: :func:`rsm_lrg.io.output_stream`) behave exactly as ``-``: ``--json /dev/stdout``
    becomes ``--json -``; for any other output (``-o``, ``--report``) the command's printed
    text must go to standard error, so that standard output holds the data alone (returns
    True). Two outputs that both name standard output are an error naming them."""
    from ..io import output_stream

    claims = [(label, path) for label, path in outputs if output_stream(path) == 1]
    if getattr(args, "json", None) == "-":
        claims.insert(0, ("--json", "-"))
    if len(claims) > 1:
        (first, a), (second, b) = claims[:2]
        raise InputError(f"cannot write {second} {show_path(b)}: {first} {show_path(a)} writes standard output "
                         f"already; give one of them a file name")
    if not claims:
        return False
    label, path = claims[0]
    if path != "-" and getattr(args, "json", None) is not None and "--json" in label.split("/"):
        args.json = "-"  # written, and the summary left out, as for --json -
        return False
    return path != "-"


def check_standard_output(inputs) -> None:
    """Refuse to run when standard output is one of the input files (``rsm-lrg fit runs.csv ...
    >> runs.csv``): what the command prints would be appended to its own input (as ``cat``
    refuses "input file is output file")."""
    out = _regular_stream(1)
    if out is None:
        return
    for inp in inputs:
        try:
            st = os.stat(inp)
        except (OSError, ValueError):
            continue
        if (st.st_dev, st.st_ino) == (out.st_dev, out.st_ino):
            shown = "read from standard input" if str(inp) == STDIN_PATH else show_path(inp)
            raise InputError(f"standard output is the input file {shown}; an input is never written "
                             f"(redirect the output to another file)")


def _samefile(a, b) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


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


#: The model orders a command can fit (rsm_lrg.model.terms).
MODEL_ORDERS = ("linear", "2fi", "quadratic", "cubic")
#: The Scheffé mixture models (with ``--component``; rsm_lrg.model.mixture).
MIXTURE_MODEL_NAMES = ("mixture-linear", "mixture-quadratic", "special-cubic", "mixture-cubic")
#: Every model a fitting command's ``--model`` takes.
FIT_MODELS = MODEL_ORDERS + MIXTURE_MODEL_NAMES
#: ``--reduce`` methods (those of :data:`rsm_lrg.model.spec.REDUCE_METHODS`, not imported here so that
#: building the parser loads no NumPy; a test checks that they agree).
REDUCE_METHOD_NAMES = ("backward", "forward", "stepwise", "all-subsets")


def add_component_option(p: argparse.ArgumentParser) -> None:
    """``--component NAME[=LOW:HIGH]`` (repeatable): mixture components, fitted by a Scheffé
    ``--model`` on L-pseudo components (rsm_lrg.model.mixture)."""
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
    Kenward-Roger tests (:mod:`rsm_lrg.model.mixed`)."""
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


def random_effect(args: argparse.Namespace) -> dict:
    """The ``whole_plot=``/``random_block=`` (and ``hard_to_change=``) keywords of
    :func:`rsm_lrg.fit` from the options."""
    out = {}
    if getattr(args, "whole_plot", None) is not None:
        out["whole_plot"] = args.whole_plot
    if getattr(args, "random_block", None) is not None:
        out["random_block"] = args.random_block
    if getattr(args, "random_effect", None):
        out["random_effects"] = list(args.random_effect)
    if getattr(args, "hard_to_change", None) is not None:
        if out.get("whole_plot") is None:
            raise InputError("--hard-to-change: give --whole-plot COL too (the factors are checked against the whole "
                             "plots)")
        out["hard_to_change"] = list(args.hard_to_change)
    return out


def random_effect_columns(args: argparse.Namespace) -> list[str]:
    """The whole-plot, random-block and random-effect columns named on the command line, kept out
    of the inferred factors (the columns of an ``A:B`` interaction too when no ``--factor`` is
    given, as :func:`rsm_lrg.fit` keeps them out)."""
    cols = [c for c in (getattr(args, "whole_plot", None), getattr(args, "random_block", None)) if c is not None]
    for c in getattr(args, "random_effect", None) or []:
        cols += [c] + (c.split(":") if ":" in c and not getattr(args, "factor", None) else [])
    return cols


def add_data_response(parser: argparse.ArgumentParser) -> None:
    """DATA.csv (the runs) and ``--response COL``: what every analysis command reads."""
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each (CSV, .xlsx, .parquet or - for stdin)")
    parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    add_reader_options(parser)


# --- reading the input table (rsm_lrg.io.read_table_as) --------------------------------------

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


def read_input(args: argparse.Namespace, path=None):
    """The table ``path`` (default ``args.data``) read with the command's ``--sep``,
    ``--decimal`` and ``--sheet``. Unless it was plain comma-separated CSV, what was read
    (format, separator and whether detected, decimal mark, sheet) is added to
    ``args.notes_at_end``: ``rsm-lrg`` prints them as ``note:`` lines on stderr when the command
    succeeds (after an error only the one ``error:`` line is printed)."""
    from ..io import STDIN_NAME, read_table_as

    path = args.data if path is None else path
    df, how = read_table_as(path, sep=getattr(args, "sep", None), decimal=getattr(args, "decimal", "."),
                            sheet=getattr(args, "sheet", None))
    if how is not None and (not how.plain or str(path) == "-"):
        name = STDIN_NAME if str(path) == "-" else str(path)
        notes = getattr(args, "notes_at_end", None)
        if notes is None:
            notes = []
            args.notes_at_end = notes
        notes.append(f"read {name}: {how.describe()}")
    return df


def print_summary_or_json(args: argparse.Namespace, result, *, extra: dict | None = None,
                          header: tuple[str, ...] = ()) -> None:
    """The output of an analysis command: ``--json FILE`` writes ``result.to_dict()`` updated
    with ``extra`` (and the text still prints), ``--json -`` prints it instead of the text; the
    text is ``Data: DATA.csv``, the ``header`` lines (``Model: ...``) and ``result.summary()``
    (ending in one newline)."""
    from ..io import dump_json

    out = result.to_dict()
    out.update(extra or {})
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.json == "-":
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        for line in header:
            print(line)
        text = result.summary()
        print(text, end="" if text.endswith("\n") else "\n")


def add_model_inputs(parser: argparse.ArgumentParser, orders=FIT_MODELS) -> None:
    """DATA.csv, --response, --factor, --block and --model (one of ``orders``): the inputs of a fitted model."""
    add_data_response(parser)
    add_factor_options(parser)
    add_component_option(parser)
    add_block_option(parser)
    add_model_option(parser, orders, default=None)


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


def check_option_specs(args: argparse.Namespace) -> None:
    """Check the ``--factor`` and ``--bound NAME=LOW:HIGH`` values before any data is read, so
    that an error names the option rather than the data file (categoric ``NAME=cat...`` specs
    are left to the library)."""
    for dest, label in (getattr(args, "_path_labels", None) or {}).items():
        value = getattr(args, dest, None)
        for v in value if isinstance(value, list) else [value]:
            if isinstance(v, str) and not v.strip():
                raise InputError(f"{label}: an empty path was given")
    for dest in ("factor", "bound"):
        for spec in getattr(args, dest, None) or []:
            if not isinstance(spec, str):
                continue
            rest = spec.split("=", 1)[1].strip().lower() if "=" in spec else ""
            if rest.startswith("cat") and dest == "factor":
                continue
            if dest == "bound" and rest and ":" not in rest:
                continue  # NAME=LEVEL[,LEVEL]: a categoric factor held at its level(s), checked with the data
            from ..factors import parse_factor_spec  # only when there is a spec: it loads numpy

            try:
                if parse_factor_spec(spec)[1] is None and dest == "bound":
                    raise ValueError("expected NAME=LOW:HIGH")
            except ValueError as exc:
                raise InputError(f"--{dest} {quote_user_value(spec)}: {exc}") from None


def print_notes(notes) -> None:
    """Print each note on the input (factors inferred, columns and runs left out) to stderr as
    ``note: ...``, so that nothing is left out silently even when stdout carries JSON."""
    import sys

    for n in notes or ():
        print(f"note: {n}", file=sys.stderr)


# --- fit's model options, shared (confirm, optimize; per response where several) -------------

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
                          model: bool = False) -> None:
    """fit's model options: ``--reduce``, ``--alpha-out``, ``--criterion``, ``--transform``,
    ``--transform-constant`` (and ``--model`` when ``model``). With ``per_response`` each one
    given after a ``--response`` (declared with :class:`ResponseGroup`) applies to that
    response only; see :func:`response_options` and :func:`model_spec`."""
    kw: dict[str, Any] = {"action": PerResponseOption} if per_response else {}
    if model:
        parser.add_argument("--model", default=None, choices=list(FIT_MODELS),
                            help="model order (default quadratic; with --component and --terms the terms are the "
                                 "Scheffé model)", **kw)
    add_terms_options(parser, per_response=per_response)
    reduce_kw: dict[str, Any] = dict(kw, nargs="?", const="backward", default=False, choices=list(REDUCE_METHOD_NAMES))
    parser.add_argument("--reduce", metavar="backward|forward|stepwise|all-subsets",
                        help="choose the terms, hierarchy kept: backward elimination (the default), forward or "
                             "stepwise selection, or the best of all hierarchical subsets", **reduce_kw)
    parser.add_argument("--alpha-out", type=number(0, 1, above=True, below=True), default=0.1, metavar="A",
                        help="with --reduce and --criterion p: remove terms while p > A (default 0.1)", **kw)
    parser.add_argument("--alpha-in", type=number(0, 1, above=True, below=True), default=0.1, metavar="A",
                        help="with --reduce forward|stepwise and --criterion p: add terms while p < A (default 0.1)",
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


#: The command-line option of each library parameter an error names
#: (:class:`rsm_lrg.errors.ParameterError`'s ``parameter``, e.g. a model specification's).
PARAMETER_OPTIONS = {
    "model": "--model", "terms": "--terms", "transform": "--transform", "reduce": "--alpha-out",
    "alpha_out": "--alpha-out", "alpha": "--alpha", "confidence": "--confidence", "bound": "--bound",
    "goal": "--goal", "radius": "--radius", "step": "--step", "setting": "--at", "weight": "--weight",
    "importance": "--importance", "limits": "--limits", "criterion": "--criterion", "effect_sd": "--effect",
    "region": "--region", "observed": "--observed", "held": "--bound", "parameters": "--parameter",
    "constraints": "--constraint", "random_effects": "--random-effect",
}


def model_spec(opts: argparse.Namespace, *, order: str | None = None):
    """The :class:`~rsm_lrg.model.spec.ModelSpec` of a command's model options (``--model``,
    ``--terms``, ``--no-intercept``, ``--transform``, ``--transform-constant``, ``--reduce``,
    ``--alpha-out``, ``--criterion``; those a command lacks take their defaults). A bad value
    is an InputError naming its option, before any data is read."""
    from ..model.spec import ModelSpec, SpecError

    how = getattr(opts, "reduce", False)
    reduce: dict[str, str | float] | None = None
    if how:
        reduce = {"alpha_out": getattr(opts, "alpha_out", 0.1), "method": how if isinstance(how, str) else "backward",
                  "alpha_in": getattr(opts, "alpha_in", 0.1)}
        if getattr(opts, "criterion", None) is not None:
            reduce["criterion"] = opts.criterion
    if (order is None and getattr(opts, "model", None) is None and getattr(opts, "component", None)
            and getattr(opts, "terms", None) is not None):
        order = "mixture-quadratic"  # --terms names the Scheffé model; the order only starts a reduction
    mixture = str(order or getattr(opts, "model", None) or "quadratic") in MIXTURE_MODEL_NAMES
    if getattr(opts, "component", None) and not mixture:
        raise InputError("--model: mixture components (--component) need a Scheffé model: "
                         + "|".join(MIXTURE_MODEL_NAMES))
    if mixture and not getattr(opts, "component", None):
        raise InputError(f"--model {getattr(opts, 'model', order)}: a mixture model needs its components "
                         "(--component NAME, once per component)")
    check_terms_option(getattr(opts, "terms", None))
    try:
        return ModelSpec.build(order or getattr(opts, "model", None) or "quadratic", terms=getattr(opts, "terms", None),
                               intercept=not getattr(opts, "no_intercept", False),
                               transform=getattr(opts, "transform", None),
                               transform_constant=getattr(opts, "transform_constant", 0.0), reduce=reduce)
    except SpecError as exc:
        raise option_error(exc, opts) from None


#: The highest degree of a term given with ``--terms`` (``A^20``, ``A^10B^10``): far beyond any
#: response surface (Design-Expert stops at 6), and the exact conversion of the coefficients to
#: actual units costs time growing with the degree (``A^99999`` ran for ever).
MAX_TERM_DEGREE = 20


def check_terms_option(terms: Any) -> None:
    """Refuse a ``--terms`` list holding a term of degree above :data:`MAX_TERM_DEGREE` (its
    letters counted once each, plus their powers), naming the term.

    >>> check_terms_option("A B AB A^2 A^3B^2")
    >>> check_terms_option("A^99999")
    Traceback (most recent call last):
    ...
    rsm_lrg.io.InputError: --terms: the term 'A^99999' has degree 99999; at most 20 ...
    """
    import re

    if not isinstance(terms, str):
        return
    for tok in terms.replace(",", " ").split():
        if tok == "Intercept":
            continue
        degree = 0
        for m in re.finditer(r"[A-Z](?:\^(\d+))?", tok):
            power = m.group(1)
            degree += 1 if power is None else (int(power) if len(power) < 10 else 10**10)
        if degree > MAX_TERM_DEGREE:
            shown = degree if degree < 10**10 else "beyond 10^10"
            raise InputError(f"--terms: the term {quote_user_value(tok)} has degree {shown}; at most "
                             f"{MAX_TERM_DEGREE} (a polynomial of such degree fits noise, and its actual-unit "
                             "coefficients would take for ever)")


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


def check_transform_option(opts: argparse.Namespace) -> None:
    """The model options are checked (and a bad one named) before any data is read."""
    model_spec(opts)


def add_boxcox_rule_option(parser: argparse.ArgumentParser) -> None:
    """``--boxcox-rule likelihood|design-expert`` for a command that prints Box–Cox (pass
    ``boxcox_rule=args.boxcox_rule`` to ``FitResult.diagnostics``)."""
    parser.add_argument("--boxcox-rule", default="likelihood", choices=["likelihood", "design-expert"],
                        help="Box-Cox lambda and interval: maximum likelihood with the chi-square(1) "
                             "interval (default), or Design-Expert's rule (grid minimum, ln SS_min + t^2/df)")
