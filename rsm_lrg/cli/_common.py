"""Small helpers shared by the command modules (no heavy imports here)."""

from __future__ import annotations

import argparse
from contextlib import contextmanager

from ..io import InputError


def add_force(p: argparse.ArgumentParser) -> None:
    p.add_argument("--force", action="store_true", help="overwrite existing output files")


def add_json(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", metavar="PATH|-", help="also write the result as JSON ('-' for stdout)")


def add_factor_options(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--factor", action="append", metavar="NAME[=LOW:HIGH]", default=None,
        help="a factor column, optionally with the levels coded -1 and +1 (repeatable; "
             "default: every numeric column except the response, block and bookkeeping columns)",
    )


def add_model_inputs(parser: argparse.ArgumentParser) -> None:
    """DATA.csv, --response, --factor, --block and --model: the inputs of a fitted model."""
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each")
    parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    add_factor_options(parser)
    parser.add_argument("--block", metavar="COL", default=None, help="block column (effects sum to zero)")
    parser.add_argument("--model", default="quadratic", choices=["linear", "2fi", "quadratic", "cubic"],
                        help="model order (default quadratic)")


@contextmanager
def about_file(path):
    """Re-raise a ValueError from the library as InputError prefixed with the file name."""
    try:
        yield
    except InputError:
        raise
    except ValueError as exc:
        raise InputError(f"{path}: {exc}") from None
