"""SIGINT at every moment of a command's end (issue 36: "SIGINT during ``report`` can leave
``r.html`` behind, depending on timing"). The signal is sent by the process to itself at the
k-th line Python runs (in rsm_lrg and contextlib) from the end of the command's body — the
page staged in its temporary file — through the commit of the transaction, the command's
closing lines and ``main``'s return, for every k: the command ends 0 with its output whole, or 130 with one
``error:`` line and no output; never a temporary file, never an output behind an error.

Before, a signal that came just after the commit (or while it ran) ended the command 130 with
the output written, and one that came between the end of the body and the commit left the
temporary file."""

from __future__ import annotations

import os
import signal
import sys

import pytest

from rsm_lrg.cli import main
from rsm_lrg.cli.processes import handle_signals
from rsm_lrg.datasets import data_path
from rsm_lrg.io import output_transaction

TABLE = str(data_path("table4.csv"))
RSM = os.sep + "rsm_lrg" + os.sep
TRANSACTION = output_transaction.__wrapped__.__code__  # the generator's code
SIGNALS = handle_signals.__wrapped__.__code__


def _ours(frame) -> bool:
    name = frame.f_code.co_filename
    return RSM in name or name.endswith("contextlib.py")


def _run(argv: list[str], k: int | None) -> tuple[int, int]:
    """``main(argv)`` with SIGINT sent at the k-th line run in rsm_lrg's (and contextlib's)
    frames from the moment the command's body has ended (its output transaction resumed to
    commit) until ``main`` puts the caller's signal handlers back (None: never); returns (exit
    status, lines counted)."""
    state = {"armed": False, "resumed": 0, "n": 0, "over": 0}

    def local(frame, event, arg):
        if event == "line" and state["armed"] and state["over"] < 2 and _ours(frame):
            state["n"] += 1
            if state["n"] == k:
                os.kill(os.getpid(), signal.SIGINT)
        return local

    def calls(frame, event, arg):
        if frame.f_code is SIGNALS:  # its second call puts the caller's handlers back: the end
            state["over"] += 1
        if frame.f_code is TRANSACTION and not state["armed"]:
            state["resumed"] += 1
            if state["resumed"] == 2:  # started, then resumed at the end of the body
                state["armed"] = True
                f = frame.f_back
                while f is not None:  # the frames under way trace their lines from now on
                    f.f_trace = local
                    f = f.f_back
        return local if state["armed"] and _ours(frame) else None

    old = sys.gettrace()
    sys.settrace(calls)
    try:
        rc = main(argv)
    finally:
        sys.settrace(old)
    return rc, state["n"]


def _sweep(tmp_path, capsys, argv_of, name: str, points) -> None:
    for k in points:
        d = tmp_path / f"k{k}"
        d.mkdir()
        rc, _ = _run(argv_of(d), k)
        err = capsys.readouterr().err
        names = sorted(p.name for p in d.iterdir())
        if rc == 0:
            assert names == [name], (k, names)
        else:
            assert rc == 128 + signal.SIGINT, (k, rc, err)
            assert names == [], (k, names, err)  # nothing written, no temporary file
            errors = [ln for ln in err.splitlines() if ln.startswith("error:")]
            assert len(errors) == 1 and err.strip().splitlines()[-1] == errors[0], (k, err)


@pytest.mark.slow
def test_fit_json_interrupted_at_every_line(tmp_path, capsys):
    def argv(d):
        return ["fit", TABLE, "--response", "tcr_c_per_min", "--json", str(d / "o.json")]

    rc, total = _run(argv(tmp_path), None)  # how many lines the end of the command runs
    capsys.readouterr()
    assert rc == 0 and 20 < total < 400, total
    (tmp_path / "o.json").unlink()
    _sweep(tmp_path, capsys, argv, "o.json", range(1, total + 3))


@pytest.mark.slow
def test_report_interrupted_at_every_line(tmp_path, capsys):
    def argv(d):
        return ["report", TABLE, "--response", "tcr_c_per_min", "-o", str(d / "r.html")]

    rc, total = _run(argv(tmp_path), None)
    capsys.readouterr()
    assert rc == 0 and 20 < total < 400, total
    (tmp_path / "r.html").unlink()
    _sweep(tmp_path, capsys, argv, "r.html", range(1, total + 3, 3))
