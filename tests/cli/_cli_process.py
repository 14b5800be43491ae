"""Running ``python -m rsm_lrg`` as a child process, and watching its own children, for the
hostile-input tests that need a real process (signals, workers, file descriptors)."""

import os
import subprocess
import sys
from pathlib import Path


def cli_env() -> dict:
    """The environment of a child that imports this checkout's ``rsm_lrg``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(__file__).resolve().parents[2]) + os.pathsep + env.get("PYTHONPATH", "")
    return env


def run_cli(args, cwd, **kw):
    """``python -m rsm_lrg ARGS`` in ``cwd`` (text mode, at most 300 s)."""
    return subprocess.run([sys.executable, "-m", "rsm_lrg", *map(str, args)], cwd=cwd, env=cli_env(), timeout=300,
                          text=True, **kw)


def one_error_line(err: str, *words: str) -> str:
    """The one ``error:`` line of ``err``, holding every one of ``words``."""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:"), err[-800:]
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def child_pids(pid: int) -> list[int]:
    """The child processes of ``pid`` (Linux /proc), [] if it is gone."""
    try:
        return [int(x) for x in Path(f"/proc/{pid}/task/{pid}/children").read_text().split()]
    except OSError:
        return []


def is_alive(pid: int) -> bool:
    """Running (not gone, not a zombie waiting to be reaped)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[1].split()[0] != "Z"
