"""Issue 31, item 4: errors by attribute.

The library raises :class:`rsm_lrg.errors.ParameterError` naming the argument at fault, and
the command line chooses the option from that ``parameter`` alone: no table of message
prefixes (the old ``OPTION_MESSAGES``/``option_of_message``) and no ``startswith``/``in``
test on a library message to pick an option. The source check below keeps them from coming
back; the calls check that the library names its parameters and the CLI prints the option.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest
from _cli_errors import error_line

from rsm_lrg.cli import main
from rsm_lrg.errors import ParameterError

CLI = Path(__file__).resolve().parents[2] / "rsm_lrg" / "cli"

#: ``(file, function)`` where a library message is still read, for another purpose than
#: choosing an option: a multi-response fit's error that names its response already is not
#: named twice; on the many-file path an empty-cell error is located in its file.
READS_MESSAGE_NOT_OPTION = frozenset({("errors.py", "about_response"), ("cmd_fit.py", "_about_files")})


def _message_tests(path: Path) -> list[str]:
    """``function:line`` of every test on an exception's text inside an ``except`` block:
    ``str(exc).startswith(...)``, ``"..." in str(exc)``, ``msg == ...`` where ``msg`` was
    bound to ``str(exc)``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []

    def is_text(node, exc, names):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "str" \
                and len(node.args) == 1 and isinstance(node.args[0], ast.Name) and node.args[0].id == exc:
            return True
        return isinstance(node, ast.Name) and node.id in names

    for func in ast.walk(tree):
        if not isinstance(func, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for handler in ast.walk(func):
            if not isinstance(handler, ast.ExceptHandler) or handler.name is None:
                continue
            exc = handler.name
            names = {t.id for node in ast.walk(handler) if isinstance(node, ast.Assign)
                     and is_text(node.value, exc, set()) for t in node.targets if isinstance(t, ast.Name)}
            for node in ast.walk(handler):
                hit = False
                if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                        and node.func.attr in ("startswith", "endswith", "find", "index", "split") \
                        and is_text(node.func.value, exc, names):
                    hit = node.func.attr in ("startswith", "endswith", "find", "index")
                elif isinstance(node, ast.Compare):
                    sides = [node.left, *node.comparators]
                    hit = any(is_text(s, exc, names) for s in sides) and any(
                        isinstance(op, (ast.In, ast.NotIn, ast.Eq, ast.NotEq)) for op in node.ops)
                if hit and (path.name, func.name) not in READS_MESSAGE_NOT_OPTION:
                    found.append(f"{path.name}:{func.name}:{node.lineno}")
    return found


def test_no_message_table_in_the_cli():
    for path in sorted(CLI.glob("*.py")):
        text = path.read_text(encoding="utf-8")
        for gone in ("OPTION_MESSAGES", "option_of_message"):
            assert gone not in text, f"{path.name} uses {gone}: name the option from exc.parameter"


def test_no_string_test_on_a_library_message_in_the_cli():
    found = [hit for path in sorted(CLI.glob("*.py")) for hit in _message_tests(path)]
    assert not found, f"string tests on exception messages (use ParameterError.parameter): {found}"


def test_the_source_check_sees_the_old_mechanisms(tmp_path):
    old = tmp_path / "cmd_old.py"
    old.write_text("def f():\n    try:\n        g()\n    except ValueError as exc:\n        msg = str(exc)\n"
                   "        if msg.startswith('runs'):\n            pass\n        if 'model term' in str(exc):\n"
                   "            pass\n", encoding="utf-8")
    assert _message_tests(old) == ["cmd_old.py:f:6", "cmd_old.py:f:8"]


@pytest.mark.parametrize("call, parameter", [
    (lambda: __import__("rsm_lrg.design.split_plot", fromlist=["x"]).split_plot(
        ["A=0:1", "B=0:1"], ["C"], 4, 12), "hard_to_change"),
    (lambda: __import__("rsm_lrg.design.split_plot", fromlist=["x"]).split_plot(
        ["A=0:1", "B=0:1"], ["A"], 4, 10 ** 9), "runs"),
    (lambda: __import__("rsm_lrg.design.mixture", fromlist=["x"]).simplex_lattice(["a", "b", "c"], 0), "degree"),
    (lambda: __import__("rsm_lrg.design.mixture", fromlist=["x"]).extreme_vertices(
        {"a": (0.5, 1), "b": (0.6, 1)}), "bounds"),
    (lambda: __import__("rsm_lrg.design.screening", fromlist=["x"]).fractional_factorial(
        ["A=0:1", "B=0:1", "C=0:1"], generators="A B Q"), "generators"),
    (lambda: __import__("rsm_lrg.design.constraints", fromlist=["x"]).Constraints.parse(
        [""], __import__("rsm_lrg.design", fromlist=["x"]).as_factor_space(["A=0:1"])), "constraints"),
    (lambda: __import__("rsm_lrg.terms", fromlist=["x"]).parse_term("AQ", "AB"), "terms"),
    (lambda: __import__("rsm_lrg.terms", fromlist=["x"]).model_terms("AB", "quartic"), "model"),
])
def test_the_library_names_the_parameter(call, parameter):
    with pytest.raises(ParameterError) as info:
        call()
    assert info.value.parameter == parameter
    assert not str(info.value).startswith(f"{parameter}: ")  # the CLI puts the option in front


@pytest.mark.parametrize("argv, line", [
    (["design", "split-plot", "--factor", "A=0:1", "--factor", "B=0:1", "--hard-to-change", "C",
      "--whole-plots", "4", "--runs", "12"], "error: --hard-to-change: 'C' is not among the factors (A, B)"),
    (["design", "fractional-factorial", "--factor", "A=0:1", "--factor", "B=0:1", "--factor", "C=0:1",
      "--generator", "A B Q"], "error: --generator: generators 'A B Q': 'Q' in 'Q' is not a factor letter (A, B, C)"),
    # the prefix the CLI used to strip, or to repeat, is gone from the message
    (["design", "optimal", "--factor", "A=0:1", "--factor", "B=0:1", "--constraint", ""],
     "error: --constraint: empty expression; expected e.g. '0.5*A + B <= 1.2'"),
    (["design", "augment", "BASE", "--method", "foldover", "--fold", "Z"],
     "error: --fold: 'Z' is not a factor of the design"),
])
def test_the_cli_names_the_option(argv, line, tmp_path, capsys):
    if "BASE" in argv:
        base = tmp_path / "base.csv"
        assert main(["design", "full-factorial", "--factor", "A=0:1", "--factor", "B=0:1", "--factor", "C=0:1",
                     "-o", str(base)]) == 0
        capsys.readouterr()
        argv = [str(base) if a == "BASE" else a for a in argv]
    rc = main([*argv, "-o", str(tmp_path / "d.csv")])
    assert error_line(capsys, rc) == line
