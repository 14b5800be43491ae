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


@contextmanager
def about_file(path):
    """Re-raise a ValueError from the library as InputError prefixed with the file name."""
    try:
        yield
    except InputError:
        raise
    except ValueError as exc:
        raise InputError(f"{path}: {exc}") from None
