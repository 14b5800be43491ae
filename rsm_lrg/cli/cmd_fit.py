"""``rsm-lrg fit``: fit a response-surface model, print the ANOVA (Table 5 layout) and equation."""

from __future__ import annotations

import argparse
from contextlib import contextmanager

from .errors import about_file
from .glm_fit import add_glm_options, run_glm, wants_glm
from .gp_fit import GP_MODELS, add_gp_options, check_gp_options, run_gp
from .options import (
    FIT_MODELS,
    add_boxcox_rule_option,
    add_force,
    add_json,
    add_model_inputs,
    add_model_refinements,
    add_random_effect_options,
)
from .paths import print_notes
from .processes import ask_one_blas_thread
from .specs import model_spec

NAME = "fit"
HELP = "fit a response-surface model (or a Gaussian process); print the ANOVA, statistics and equation"
DESCRIPTION = (
    "Fit a model in coded units (--model linear, 2fi, quadratic or cubic; a Scheffe mixture model "
    "with --component: mixture-linear, mixture-quadratic, special-cubic or mixture-cubic; any term "
    "list with --terms), by least squares or, with --whole-plot/--random-block, by REML, and print the "
    "Design-Expert style ANOVA (partial sums of squares, lack of fit, pure error), the fit "
    "statistics, the coefficients, the equation in coded and actual terms and the canonical "
    "analysis. With --model gp a Gaussian process (kriging) is fitted instead: --kernel, --trend, "
    "--nugget, --seed. With --json - the JSON goes to standard output instead of the text."
)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_model_inputs(parser, FIT_MODELS + GP_MODELS)
    add_random_effect_options(parser)
    add_model_refinements(parser)
    parser.add_argument("--diagnostics", action="store_true",
                        help="also print per-run diagnostics and the Box-Cox recommendation (JSON key 'diagnostics')")
    add_boxcox_rule_option(parser)
    add_dispersion_options(parser)
    add_gp_options(parser)
    add_json(parser)
    parser.add_argument("--report", metavar="PATH", default=None, help="also write a self-contained HTML report")
    add_force(parser)
    add_glm_options(parser)


#: The options of a spread model (``fit``, ``optimize``) mapped from the library's parameters.
DISPERSION_OPTIONS = {"response": "--dispersion", "factors": "--dispersion", "dispersion_model": "--dispersion-model"}


def add_dispersion_options(parser: argparse.ArgumentParser, *, optimise: bool = False) -> None:
    """``--dispersion`` and ``--dispersion-model`` (:mod:`rsm_lrg.model.dispersion`)."""
    what = ("also minimise the predicted spread of each response: the standard deviation s of its replicated "
            "settings, modelled as ln s, enters the desirability beside the response's own goal"
            if optimise else
            "also model the spread: ln s of the replicates at each distinct setting (settings run at least twice; "
            "the unreplicated ones are named), fitted by least squares beside the mean (JSON key 'dispersion')")
    parser.add_argument("--dispersion", action="store_true", help=what)
    parser.add_argument("--dispersion-model", default="linear", choices=["linear", "2fi", "quadratic", "cubic"],
                        help="the model of ln s (default linear)")


def fit_spread(data, response: str, space, args: argparse.Namespace):
    """The :class:`~rsm_lrg.model.dispersion.DispersionFit` of ``response`` coded as ``space``;
    an error names ``--dispersion`` or ``--dispersion-model``."""
    from ..model.dispersion import fit_dispersion
    from .errors import option_error

    try:
        return fit_dispersion(data, response, factors=space, model=args.dispersion_model)
    except ValueError as exc:
        if getattr(exc, "parameter", None) is None:
            raise
        raise option_error(exc, options=DISPERSION_OPTIONS) from None


def _write_report(result, path, force: bool) -> None:
    import importlib

    try:
        mod = importlib.import_module("rsm_lrg.report")
    except ImportError:
        mod = None
    writer = getattr(mod, "write_report", None) if mod is not None else None
    if writer is None:
        raise ValueError(f"{path}: --report is not available yet in this version (no HTML report writer)")
    from ..optimize import optimize

    writer(result, path, force=force, optimum=optimize(result, goal="minimize"))  # found here, presented there


def _many_files(path: str, args: argparse.Namespace):
    """A Dask DataFrame of the CSV or Parquet files of a directory or glob pattern (one
    partition per file, :mod:`rsm_lrg.cli.file_sets`), the files and the notes on the files
    skipped (printed after a success), or None for one file
    (read as usual; a file that exists is one file, glob characters and all)."""
    from .file_sets import expand_data_path, read_file_set

    files = expand_data_path(path)
    if files is None:
        return None
    ddf, notes = read_file_set(path, files, sep=getattr(args, "sep", None), decimal=getattr(args, "decimal", "."),
                               sheet=getattr(args, "sheet", None))
    return ddf, files, notes


#: A single input file up to this size [bytes] is fitted with one BLAS thread (see
#: :func:`one_blas_thread_if_small`).
SMALL_INPUT_BYTES = 4_000_000


def one_blas_thread_if_small(path: str) -> None:
    """Ask for one BLAS thread before NumPy is loaded when the input is one small file
    (:func:`~.processes.ask_one_blas_thread`: nothing changes when the user set a thread count
    or NumPy is already loaded, as for ``main()`` called in-process).

    OpenBLAS starts a thread per core when NumPy is imported, and those threads cost about
    0.2 s of CPU time in a process that lives for one second, while a fit of a few thousand
    runs gains nothing from them (its matrices are too small for threaded BLAS; R's own BLAS
    is single-threaded). Even a Gaussian process on 2,000 runs, whose n x n factorisations are
    the largest a fit makes, was no quicker with two threads on the shared 2-core machine (the
    README's speed of the Gaussian process). Large inputs keep the threads.
    """
    import os

    try:
        small = os.path.isfile(path) and os.path.getsize(path) <= SMALL_INPUT_BYTES
    except OSError:
        return
    if small:
        ask_one_blas_thread()


@contextmanager
def _about_files(many, args: argparse.Namespace):
    """On the many-file path, a fit's "a cell is empty" names the file, row and column."""
    try:
        yield
    except ValueError as exc:
        if many is None or "empty" not in str(exc):
            raise
        from ..io import InputError
        from .file_sets import locate_empty_cell

        if args.factor:
            names = [str(f).split("=", 1)[0].strip() for f in args.factor]
        else:
            names = [str(c) for c in many[0].columns if str(c) != args.response]
        found = locate_empty_cell(many[1], names + ([args.block] if args.block else []), sep=getattr(args, "sep", None),
                                  decimal=getattr(args, "decimal", "."))
        if found is None:
            raise
        where, what = found
        raise InputError(f"{where}: {exc}" if "row" in str(exc) else f"{where}: {what}: {exc}") from None


def run(args: argparse.Namespace) -> int:
    one_blas_thread_if_small(str(args.data))
    check_gp_options(args)
    if args.dispersion and (args.model in GP_MODELS or wants_glm(args)):
        from ..io import InputError

        raise InputError("--dispersion: the spread model (ln s) goes beside a least-squares or REML fit, "
                         "not a Gaussian process or a GLM")
    if args.model in GP_MODELS:
        return run_gp(args)
    from ..io import dump_json
    from ..model import fit
    from .paths import read_input
    from .specs import random_effect

    if wants_glm(args):  # --family: a generalised linear model (rsm_lrg.cli.glm_fit)
        return run_glm(args)
    model_spec(args)  # a bad --model/--terms/--transform is named before any data is read
    many = _many_files(str(args.data), args)  # a directory or glob: fitted partition by partition (Dask)
    if many is not None:
        unsupported = [o for o in ("reduce", "transform", "diagnostics", "report", "whole_plot", "random_block",
                                   "random_effect", "dispersion") if getattr(args, o, None)]
        if unsupported:
            raise ValueError(f"{args.data}: --{unsupported[0].replace('_', '-')} is not available when fitting several files")
    # a plain CSV file is read into a ColumnTable, without pandas (rsm_lrg.table), when nothing
    # after the fit reads the runs as a DataFrame (per-run diagnostics, the report, the spread model)
    data = many[0] if many is not None else read_input(
        args, column_table=not (args.diagnostics or args.report or args.dispersion))
    with about_file(args.data), _about_files(many, args):
        result = fit(data, args.response, factors=args.factor, block=args.block, model=model_spec(args),
                     components=args.component, **random_effect(args))
        extra: dict = {}
        if args.diagnostics:
            diag = result.diagnostics(boxcox_rule=args.boxcox_rule)
            extra["diagnostics"] = diag.to_dict()
    spread = fit_spread(data, args.response, result.space, args) if args.dispersion else None
    if spread is not None:
        extra["dispersion"] = spread.to_dict()
    out = dict(result.to_dict(), **extra)
    if many is not None:
        print_notes(many[2])  # the files of the directory or pattern that were skipped
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.report:
        _write_report(result, args.report, args.force)
    if args.json == "-":
        print_notes(result.input_notes)  # the text output carries them otherwise
        dump_json(out, "-")
    else:
        print(f"Data: {args.data}")
        if result.reduction is not None:
            print(result.reduction.describe())
        print(result.summary(), end="")
        if args.diagnostics:
            print()
            print(diag.summary(), end="")
        if spread is not None:
            print()
            print(spread.summary(), end="")
    return 0
