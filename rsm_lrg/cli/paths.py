"""The paths a command reads and writes: its input files (a glob, standard input), the outputs it
plans and claims (standard output as ``-``), reading the data with the reader options, and
printing the one-line summaries, the JSON and the notes."""

from __future__ import annotations

import argparse
import os

from ..io import STDIN_NAME, InputError, check_output, show_path

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


def read_input(args: argparse.Namespace, path=None, *, column_table: bool = False):
    """The table ``path`` (default ``args.data``) read with the command's ``--sep``,
    ``--decimal`` and ``--sheet``. Unless it was plain comma-separated CSV, what was read
    (format, separator and whether detected, decimal mark, sheet) is added to
    ``args.notes_at_end``: ``rsm-lrg`` prints them as ``note:`` lines on stderr when the command
    succeeds (after an error only the one ``error:`` line is printed). With ``column_table``
    a CSV file of plain numbers comes back as a :class:`rsm_lrg.table.ColumnTable`, read
    without pandas (:func:`rsm_lrg.io.read_table_as`); any other file as a DataFrame."""
    from ..io import read_table_as

    path = args.data if path is None else path
    df, how = read_table_as(path, sep=getattr(args, "sep", None), decimal=getattr(args, "decimal", "."),
                            sheet=getattr(args, "sheet", None), column_table=column_table)
    if how is not None and (not how.plain or str(path) == "-"):
        name = STDIN_NAME if str(path) == "-" else str(path)
        notes = getattr(args, "notes_at_end", None)
        if notes is None:
            notes = []
            args.notes_at_end = notes
        notes.append(f"read {name}: {how.describe()}")
    return df


def print_summary_or_json(args: argparse.Namespace, result, *, extra: dict | None = None,
                          header: tuple[str, ...] = (), source: str | None = None) -> None:
    """The output of an analysis command: ``--json FILE`` writes ``result.to_dict()`` updated
    with ``extra`` (and the text still prints), ``--json -`` prints it instead of the text; the
    text is ``Data: DATA.csv`` (or the ``source`` line, ``Design: D.csv``), the ``header``
    lines (``Model: ...``) and ``result.summary()`` (ending in one newline)."""
    from ..io import dump_json

    out = result.to_dict()
    out.update(extra or {})
    if args.json and args.json != "-":
        dump_json(out, args.json, force=args.force)
    if args.json == "-":
        dump_json(out, "-")
    else:
        print(source if source is not None else f"Data: {args.data}")
        for line in header:
            print(line)
        text = result.summary()
        print(text, end="" if text.endswith("\n") else "\n")


def print_notes(notes) -> None:
    """Print each note on the input (factors inferred, columns and runs left out) to stderr as
    ``note: ...``, so that nothing is left out silently even when stdout carries JSON."""
    import sys

    for n in notes or ():
        print(f"note: {n}", file=sys.stderr)
