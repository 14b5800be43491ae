"""The README is a test: every fenced shell and Python block, in order, in a fresh copy of the
repository, as printed (issue 25).

Each ```bash / ```sh / ```python block runs in one directory, the copy's root, after the ones
before it: a file is written once (an existing output is refused without ``--force``) and a
block can only use what the copy holds or an earlier block made. ``rsm-lrg`` runs the copy's
code. Two kinds of commands of the quick start are not run, and only those (each one is
checked to be there, as printed): ``python -m pip install ...`` (this environment is that
install) and ``python -m pytest`` (this test is part of that suite).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
SHELLS = ("bash", "sh", "shell")
FENCE = re.compile(r"^```([A-Za-z0-9_+-]*)[^\n]*\n(.*?)^```[ \t]*$", re.M | re.S)
NOT_RUN = (re.compile(r"^python -m pip install\b"), re.compile(r"^python -m pytest\b"))


def readme_blocks(text: str) -> list[tuple[str, str]]:
    """``(language, code)`` of every fenced shell and Python block, in order."""
    return [(lang, code) for lang, code in FENCE.findall(text) if lang in SHELLS + ("python",)]


def runnable(code: str) -> tuple[str, list[str]]:
    """A shell block as run: each ``&&``-part of a line that is a :data:`NOT_RUN` command is
    left out (and returned, as printed); everything else is kept verbatim."""
    kept, skipped = [], []
    for line in code.replace("\\\n", " ").splitlines():
        parts = [p.strip() for p in line.split("&&")]
        left = []
        for part in parts:
            if any(rx.match(part) for rx in NOT_RUN):
                skipped.append(part)
            else:
                left.append(part)
        if left:
            kept.append(" && ".join(left))
    return "\n".join(kept) + "\n", skipped


def test_blocks_are_found_and_only_install_and_test_lines_are_left_out():
    blocks = readme_blocks(README.read_text(encoding="utf-8"))
    assert sum(lang in SHELLS for lang, _ in blocks) >= 5 and any(lang == "python" for lang, _ in blocks)
    skipped = [s for lang, code in blocks if lang in SHELLS for s in runnable(code)[1]]
    assert skipped and all(any(rx.match(s) for rx in NOT_RUN) for s in skipped)
    assert runnable("python -m pip install -e . && rsm-lrg reproduce\n") == (
        "rsm-lrg reproduce\n", ["python -m pip install -e ."])


def _fresh_copy(dest: Path) -> Path:
    """The repository's tracked files (``git ls-files``; without git, the tree less caches and
    outputs) copied to ``dest``, with nothing the README's commands write."""
    try:
        files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True,
                               timeout=60).stdout.decode().split("\0")
    except (OSError, subprocess.SubprocessError):
        files = None
    if files is None:
        shutil.copytree(ROOT, dest, ignore=shutil.ignore_patterns(".git", "__pycache__", "*.pyc", ".pytest_cache"))
        return dest
    for f in filter(None, files):
        src = ROOT / f
        if src.is_file():
            (dest / f).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / f)
    return dest


@pytest.mark.slow
def test_every_readme_block_runs_in_order_as_printed(tmp_path):
    copy = _fresh_copy(tmp_path / "repo")
    bindir = tmp_path / "bin"
    bindir.mkdir()
    shim = bindir / "rsm-lrg"  # the console script of this copy
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m rsm_lrg "$@"\n')
    shim.chmod(0o755)
    env = dict(os.environ, PYTHONPATH=str(copy), PATH=f"{bindir}{os.pathsep}{os.environ.get('PATH', '')}",
               MPLBACKEND="Agg")
    env.pop("PYTHONSTARTUP", None)
    blocks = readme_blocks((copy / "README.md").read_text(encoding="utf-8"))
    for i, (lang, code) in enumerate(blocks, 1):
        if lang == "python":
            script = tmp_path / f"readme_block_{i}.py"
            script.write_text(code)
            argv = [sys.executable, str(script)]
        else:
            script = tmp_path / f"readme_block_{i}.sh"
            script.write_text("set -euo pipefail\n" + runnable(code)[0])
            argv = ["bash", str(script)]
        out = subprocess.run(argv, cwd=copy, env=env, capture_output=True, text=True, timeout=900)
        assert out.returncode == 0, f"README block {i} ({lang}) failed:\n{code}\n--- stderr ---\n{out.stderr[-3000:]}"
        assert "Traceback" not in out.stderr, (i, out.stderr[-2000:])
