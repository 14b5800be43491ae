"""Small helpers shared by the command modules (no heavy imports here)."""

from __future__ import annotations

import argparse
from contextlib import contextmanager

from ..io import InputError


def whole_number(minimum: int | None = None):
    """An argparse ``type`` for a whole number, at least ``minimum`` when given (argparse
    turns the ArgumentTypeError into a usage error naming the option)."""

    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
        if minimum is not None and v < minimum:
            raise argparse.ArgumentTypeError(f"expected a whole number >= {minimum}, got {text!r}")
        return v

    return parse


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


#: The model orders a command can fit (rsm_lrg.model.terms).
MODEL_ORDERS = ("linear", "2fi", "quadratic", "cubic")


def add_model_option(p: argparse.ArgumentParser, orders=MODEL_ORDERS, what: str = "model order") -> None:
    """``--model ORDER`` (default quadratic)."""
    p.add_argument("--model", default="quadratic", choices=list(orders), help=f"{what} (default quadratic)")


def add_block_option(p: argparse.ArgumentParser, role: str = "effects sum to zero") -> None:
    """``--block COL``; ``role`` says what the command does with the blocks."""
    p.add_argument("--block", metavar="COL", default=None, help=f"block column ({role})")


def add_model_inputs(parser: argparse.ArgumentParser) -> None:
    """DATA.csv, --response, --factor, --block and --model: the inputs of a fitted model."""
    parser.add_argument("data", metavar="DATA.csv", help="the runs, one row each")
    parser.add_argument("--response", required=True, metavar="COL", help="the response column")
    add_factor_options(parser)
    add_block_option(parser)
    add_model_option(parser)


@contextmanager
def about_file(path):
    """Re-raise a ValueError from the library as InputError prefixed with the file name."""
    try:
        yield
    except InputError:
        raise
    except ValueError as exc:
        raise InputError(f"{path}: {exc}") from None
