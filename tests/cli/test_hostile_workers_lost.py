"""A Dask scheduler that stays up while every worker dies mid-run (issue 26, processes and
clusters): ``simulate --scheduler`` ends with one error line naming the scheduler within about
``--scheduler-timeout`` seconds, writes nothing and leaves no process behind; it used to wait
for ever. A real scheduler and a real worker (``dask scheduler``, ``dask worker --no-nanny``),
the worker killed with SIGKILL."""

from __future__ import annotations

import shutil
import signal
import socket
import subprocess
import sys
import time

import pytest
from _cli_process import cli_env

pytestmark = [pytest.mark.slow, pytest.mark.cluster]


def _wait_on_scheduler(address: str, condition: str, timeout: float = 120.0) -> None:
    """Wait (in a child process, with a Dask client of its own) until ``condition`` holds on
    the scheduler: ``"workers"`` (a worker has joined) or ``"tasks"`` (work was submitted)."""
    code = (
        "import sys, time\n"
        "from distributed import Client\n"
        f"c = Client({address!r}, timeout='60s')\n"
        f"end = time.monotonic() + {timeout}\n"
        f"if {condition!r} == 'workers':\n"
        f"    c.wait_for_workers(1, timeout={timeout})\n"
        "else:\n"
        "    while not c.run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.tasks)):\n"
        "        if time.monotonic() > end:\n"
        "            sys.exit(1)\n"
        "        time.sleep(0.2)\n"
        "c.close()\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=cli_env(),
                          timeout=timeout + 60)
    assert done.returncode == 0, done.stderr[-2000:]


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


@pytest.mark.skipif(shutil.which("dask") is None, reason="the dask command (dask[distributed]) is not installed")
def test_every_worker_lost_mid_run_is_one_error_not_a_hang(tmp_path):
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "env": cli_env()}
    sched = subprocess.Popen(["dask", "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
                             **quiet)
    worker = None
    try:
        time.sleep(2.0)
        worker = subprocess.Popen(["dask", "worker", address, "--nthreads", "1", "--no-nanny", "--no-dashboard"],
                                  **quiet)
        _wait_on_scheduler(address, "workers")  # joined before simulate asks (a busy machine starts it slowly)
        design = tmp_path / "design.csv"
        made = subprocess.run([sys.executable, "-m", "rsm_lrg", "design", "latin-hypercube", "--runs", "40000",
                               "--factor", "thickness_m=0.0001:0.0005", "--factor", "stroke_m=0.04:0.06",
                               "--factor", "velocity_m_s=0.4:0.6", "--factor", "acceleration_m_s2=20:40",
                               "--seed", "1", "-o", str(design)], capture_output=True, text=True, env=cli_env())
        assert made.returncode == 0, made.stderr
        out = tmp_path / "runs.csv"
        run = subprocess.Popen([sys.executable, "-m", "rsm_lrg", "simulate", str(design), "--scheduler", address,
                                "--scheduler-timeout", "5", "--no-progress", "-o", str(out)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=cli_env())
        _wait_on_scheduler(address, "tasks")  # connected, batches submitted (the worker runs for longer than this)
        assert run.poll() is None, run.communicate()
        worker.send_signal(signal.SIGKILL)
        worker.wait(timeout=10)
        t0 = time.monotonic()
        try:
            _, err = run.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            run.kill()
            run.communicate()
            pytest.fail("simulate still waits a minute after its only worker died")
        waited = time.monotonic() - t0
        lines = err.strip().splitlines()
        assert run.returncode == 2, err
        assert len(lines) == 1 and lines[0].startswith("error: --scheduler") and "no worker left" in lines[0], err
        assert address.split("//")[1] in lines[0]
        assert waited < 30.0
        assert not out.exists() and not list(tmp_path.glob(".runs.csv.*"))
    finally:
        for p in (worker, sched):
            if p is not None and p.poll() is None:
                p.kill()
                p.wait(timeout=10)
