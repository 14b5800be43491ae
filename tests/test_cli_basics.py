"""The command line as a whole: help is fast and light, errors are one line."""

import subprocess
import sys


def run(*args, **kw):
    return subprocess.run([sys.executable, "-m", "rsm_lrg", *args], capture_output=True, text=True, **kw)


def test_help_lists_commands_without_heavy_imports():
    code = (
        "import sys, io, contextlib\n"
        "from rsm_lrg.cli import main\n"
        "buf = io.StringIO()\n"
        "with contextlib.redirect_stdout(buf):\n"
        "    rc = main(['--help'])\n"
        "heavy = [m for m in ('statsmodels', 'scipy', 'matplotlib', 'pandas') if m in sys.modules]\n"
        "print(rc, heavy)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "0 []"


def test_help_works_from_python_m():
    out = run("--help")
    assert out.returncode == 0
    assert "rsm-lrg" in out.stdout


def test_unknown_command_is_one_error_line():
    out = run("no-such-command")
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:")
