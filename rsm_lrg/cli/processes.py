"""Signals, worker processes and clusters: every command ends cleanly and leaves nothing running.

- :func:`handle_signals`: inside it, SIGTERM and SIGHUP raise :class:`Terminated` (SIGINT
  raises KeyboardInterrupt as usual), so the command unwinds like after an error: its pool
  stopped, its temporary files removed (:func:`rsm_lrg.io.output_transaction`), no output
  half-written; ``main`` then exits ``128 + signal``.
- :func:`process_pool`: a ``ProcessPoolExecutor`` whose workers die with their parent
  (``PR_SET_PDEATHSIG``: even a parent killed with SIGKILL takes them along) and leave
  SIGINT and SIGTERM to it; :func:`close_pool` waits for them after a success and kills them
  at once otherwise.
- :func:`connect_scheduler`: a Dask scheduler that accepts the connection and never answers
  is an error after ``timeout`` seconds (the client's own timeout does not cover the
  handshake); :func:`scheduler_lost` turns the failure of a run whose scheduler went away
  into one line naming it.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
import time
from collections.abc import Callable, Coroutine, Iterator
from typing import Any

__all__ = ["Terminated", "handle_signals", "pending_signal", "settle", "process_pool", "close_pool", "stop_children",
           "child_processes", "kill_children", "connect_scheduler",
           "scheduler_lost", "pool_lost", "DEFAULT_SCHEDULER_TIMEOUT", "THREAD_VARIABLES", "ask_one_blas_thread"]

#: Seconds a Dask scheduler has to answer (``--scheduler-timeout``).
DEFAULT_SCHEDULER_TIMEOUT = 60.0

#: The environment variables by which a user chooses the BLAS libraries' thread counts.
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS")


def ask_one_blas_thread() -> bool:
    """Ask OpenBLAS for one thread (``OPENBLAS_NUM_THREADS=1``), which takes effect only before
    NumPy is loaded: nothing is changed, and False returned, when NumPy is already loaded or the
    user set one of :data:`THREAD_VARIABLES`. Processes started later inherit it."""
    if "numpy" in sys.modules or any(v in os.environ for v in THREAD_VARIABLES):
        return False
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    return True


_HANDLED = ("SIGTERM", "SIGHUP")


class Terminated(BaseException):
    """The command was asked to stop by a signal (SIGTERM, SIGHUP); ``signum`` is its number.

    A BaseException, like KeyboardInterrupt, so that no ``except Exception`` on the way
    swallows it."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = int(signum)

    @property
    def name(self) -> str:
        try:
            return signal.Signals(self.signum).name
        except ValueError:
            return f"signal {self.signum}"


_PENDING: list[int] = []


def _raise(signum: int, frame: Any) -> None:
    """The handler: raise :class:`Terminated` (KeyboardInterrupt for SIGINT), once. While the
    outputs are being placed (:func:`rsm_lrg.io.committing`), or once the command is already
    unwinding, the signal is only recorded (:func:`pending_signal`), so that no commit, roll-back
    or clean-up is cut half-way; a commit under way is asked to take its outputs back
    (:func:`rsm_lrg.io.abort_commit`), so a command that reports a signal has written nothing.
    Once the outputs are all in place (:func:`rsm_lrg.io.committed`) the command has done its
    work and the signal is let go: it ends as it would have a moment later, with its outputs."""
    from ..io import abort_commit, committed, committing

    if _SETTLED:  # the command has ended: the program leaves now with its status (in-process: let go)
        if _SETTLED[1]:
            os._exit(_SETTLED[0])
        return
    if committed():  # every output is in place: the command has done its work, and ends so
        return
    if committing() or _PENDING:
        if signum not in _PENDING:
            _PENDING.append(signum)
        if committing():  # the outputs placed so far are taken back when the commit ends
            abort_commit()
        return
    _PENDING.append(signum)
    # the workers go at once, whatever the exception raised here meets on its way out (a library
    # that swallows it, a finalizer that runs it): a pool whose workers are gone fails at once,
    # so no wait on them can last, and main() still reports the signal (pending_signal())
    kill_children()
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    raise Terminated(signum)


_SETTLED: list[Any] = []  # [status, leave]: the command has ended (see settle)


def settle(status: int, leave: bool) -> None:
    """The command has ended with ``status``: a signal from now on no longer stops anything;
    with ``leave`` (the program, not ``main()`` called in-process) it ends the program at once
    with that status (no traceback, and no hang on a standard output nobody reads)."""
    _SETTLED[:] = [int(status), bool(leave)]


def pending_signal() -> int | None:
    """The signal that arrived while the outputs were being placed (the command then ends
    with ``128 + signal`` after its outputs were written), or None."""
    return _PENDING[0] if _PENDING else None


@contextlib.contextmanager
def handle_signals(restore: bool = True) -> Iterator[None]:
    """SIGTERM and SIGHUP raise :class:`Terminated` and SIGINT KeyboardInterrupt inside the
    block, once (see :func:`_raise`; main thread only; the previous handlers are put back
    after it, unless not ``restore``: the program's own run keeps them to its exit, where a
    signal after :func:`settle` ends it with the command's status)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    from ..io import reset_commit_state

    old = {}
    _PENDING.clear()
    _SETTLED.clear()
    reset_commit_state()
    for name in (*_HANDLED, "SIGINT"):
        sig = getattr(signal, name, None)
        if sig is None:
            continue
        try:
            old[sig] = signal.signal(sig, _raise)
        except (OSError, ValueError):
            pass
    hook = sys.unraisablehook
    sys.unraisablehook = _quiet_signal_exceptions(hook)
    try:
        yield
    finally:
        if restore:  # the program's own run keeps it to its exit, as it keeps the handlers
            sys.unraisablehook = hook
        for sig, handler in old.items() if restore else ():
            try:
                signal.signal(sig, handler)
            except (OSError, ValueError, TypeError):
                pass


def _quiet_signal_exceptions(hook: Any) -> Any:
    """An ``unraisablehook`` that says nothing once a signal has come: the exception its handler
    raised where Python cannot raise it (an at-fork callback, a finalizer), or one that the cut
    left behind (a ``multiprocessing`` finalizer interrupted half-built, whose call then fails
    with ``AttributeError: '_key'``), is an echo of the signal, which ``main`` reports in its
    one line, its workers gone. Without a signal, anything goes to ``hook``."""

    def quiet(unraisable: Any) -> None:
        if _PENDING:
            return
        hook(unraisable)

    return quiet


def _die_with_parent(parent: int) -> None:
    """Worker initializer: die when ``parent`` dies (Linux ``PR_SET_PDEATHSIG``), leave SIGINT
    to the parent (it stops the pool) and take SIGTERM and SIGHUP as the default (die)."""
    for name in _HANDLED:
        sig = getattr(signal, name, None)
        if sig is not None:
            signal.signal(sig, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(1, int(signal.SIGKILL), 0, 0, 0)  # PR_SET_PDEATHSIG = 1
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:  # the parent died before prctl took effect
        os._exit(1)


def process_pool(workers: int):
    """A ``ProcessPoolExecutor`` of ``workers`` processes that die with this one."""
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(max_workers=workers, initializer=_die_with_parent, initargs=(os.getpid(),))


def child_processes() -> list[int]:
    """The process ids of this process's children (Linux ``/proc``: every child, also one forked
    by a pool that a signal interrupted before it could record it); [] where ``/proc`` has none."""
    pids: list[int] = []
    try:
        tasks = os.listdir(f"/proc/{os.getpid()}/task")
    except OSError:
        return pids
    for tid in tasks:
        try:
            with open(f"/proc/{os.getpid()}/task/{tid}/children", encoding="ascii") as fh:
                pids.extend(int(x) for x in fh.read().split())
        except (OSError, ValueError):
            continue
    return sorted(set(pids))


def kill_children() -> list[int]:
    """Send SIGKILL to every child process of this one (:func:`child_processes` and those
    ``multiprocessing`` knows); they are reaped by :func:`stop_children`. Returns their ids."""
    import multiprocessing

    pids = set(child_processes())
    with contextlib.suppress(Exception):
        pids.update(p.pid for p in multiprocessing.active_children() if p.pid)
    for pid in pids:
        with contextlib.suppress(OSError):
            os.kill(pid, signal.SIGKILL)
    return sorted(pids)


def stop_children(timeout: float = 5.0) -> None:
    """Kill every child process of this one (the workers of a pool, and any other) and reap
    them, waiting at most ``timeout`` seconds in all."""
    import multiprocessing

    end = time.monotonic() + timeout
    children = multiprocessing.active_children()
    for p in children:
        with contextlib.suppress(Exception):
            p.kill()
    others = [pid for pid in kill_children() if pid not in {p.pid for p in children}]
    for p in children:
        with contextlib.suppress(Exception):
            p.join(max(0.0, end - time.monotonic()))
    for pid in others:  # children multiprocessing does not know of: reaped here
        while True:
            try:
                done, _ = os.waitpid(pid, os.WNOHANG)
            except ChildProcessError:
                break
            if done or time.monotonic() >= end:
                break
            time.sleep(0.01)


def close_pool(executor, ok: bool) -> None:
    """Shut a pool down: after a success wait for its workers; otherwise (an error, a signal)
    drop the queued work and kill the workers at once, so that nothing keeps running."""
    if ok:
        executor.shutdown(wait=True)
        return
    with contextlib.suppress(Exception):
        executor.shutdown(wait=False, cancel_futures=True)
    stop_children()
    # let the pool's manager thread see its dead workers and end (it closes its wake-up pipe):
    # at interpreter exit Python 3.11 would otherwise write to that pipe while the thread closes
    # it, and print a traceback (EBADF) after our one error line. Bounded: never a hang.
    joiner = threading.Thread(target=lambda: executor.shutdown(wait=True), daemon=True)
    joiner.start()
    joiner.join(10.0)


def _show(address: str) -> str:
    from ..io import quote_user_value

    return quote_user_value(address, 80)


def connect_scheduler(address: str, timeout: float = DEFAULT_SCHEDULER_TIMEOUT):
    """A ``distributed.Client`` of the scheduler at ``address``, or :class:`rsm_lrg.io.InputError`
    naming it: the scheduler must answer (its identity) within ``timeout`` seconds, so one
    that accepts the connection and stays silent is an error, not a hang, and it must have a
    worker (or gain one) within ``timeout`` seconds."""
    import asyncio

    from ..io import InputError

    try:
        from distributed import Client
        from distributed.core import rpc
    except ImportError:
        raise InputError("--scheduler needs dask.distributed: pip install 'rsm-lrg[parallel]'") from None
    import logging

    # their failures end as one error line of ours: no log records (distributed gives several
    # of its loggers their own stderr handler)
    names = [n for n in logging.root.manager.loggerDict if n.split(".")[0] in ("distributed", "tornado", "bokeh")]
    for name in ["distributed", "tornado", "asyncio", *names]:
        log = logging.getLogger(name)
        log.handlers = [logging.NullHandler()]
        log.propagate = False

    connected = _reachable(address, timeout)

    async def probe() -> None:
        r = rpc(address, timeout=timeout)
        try:
            await asyncio.wait_for(r.identity(), timeout)
        finally:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(r.close_rpc(), 5)

    try:
        _run_coroutine(probe)
    except TimeoutError:
        raise InputError(f"--scheduler {_show(address)}: no answer within {timeout:g} s "
                         f"(--scheduler-timeout); is a Dask scheduler listening there?") from None
    except Exception as exc:  # a bad address, nothing listening, garbage from whatever answered
        if connected or isinstance(exc, (MemoryError, OverflowError)):  # MemoryError: a header claiming exabytes
            raise InputError(f"--scheduler {_show(address)}: what answers there is not a Dask scheduler (it does "
                             f"not speak Dask's protocol: {type(exc).__name__}: {str(exc)[:80]})") from None
        raise InputError(f"--scheduler {_show(address)}: cannot connect "
                         f"({type(exc).__name__}: {str(exc)[:120]})") from None
    try:
        client = Client(address, timeout=f"{timeout}s")
    except Exception as exc:
        raise InputError(f"--scheduler {_show(address)}: cannot connect "
                         f"({type(exc).__name__}: {str(exc)[:120]})") from None
    try:  # a scheduler without a worker would hold the batches for ever
        client.wait_for_workers(1, timeout=timeout)
    except Exception as exc:
        with contextlib.suppress(Exception):
            client.close(timeout=5)
        raise InputError(f"--scheduler {_show(address)}: no worker joined within {timeout:g} s "
                         f"(--scheduler-timeout; {type(exc).__name__})") from None
    return client


def _run_coroutine(make: Callable[[], Coroutine[Any, Any, None]]) -> None:
    """Run the coroutine ``make()`` to its end, from a thread of its own when this thread already
    runs an event loop (a notebook's cell, an async caller), where ``asyncio.run`` refuses;
    whatever it raises is raised here."""
    import asyncio

    try:
        asyncio.get_running_loop()
    except RuntimeError:
        asyncio.run(make())
        return
    failed: list[BaseException] = []

    def target() -> None:
        try:
            asyncio.run(make())
        except BaseException as exc:  # handed to the caller's thread
            failed.append(exc)

    worker = threading.Thread(target=target, name="rsm-lrg-scheduler-probe", daemon=True)
    worker.start()
    worker.join()
    if failed:
        raise failed[0]


def _reachable(address: str, timeout: float) -> bool:
    """Check a scheduler address before Dask tries it, so that what is wrong is said at once
    and by name rather than after ``timeout`` seconds of retries: an empty or malformed
    address, a port outside 1..65535, a host name that does not resolve, a TCP port where
    nothing listens (connection refused). Resolving and connecting are bounded by ``timeout``
    (a resolver that does not answer is left to the probe that follows). True when a TCP
    connection was made (then whatever fails next is the protocol)."""
    import socket

    from ..io import InputError

    if not address.strip():
        raise InputError("--scheduler: an empty address was given (e.g. tcp://10.0.0.5:8786)")
    from distributed.comm.addressing import parse_address, parse_host_port

    try:
        scheme, loc = parse_address(address)
        if scheme not in ("tcp", "tls", "ws", "wss"):
            return False
        host, port = parse_host_port(loc)
    except (ValueError, TypeError) as exc:
        raise InputError(f"--scheduler {_show(address)}: not a scheduler address such as tcp://HOST:PORT "
                         f"({str(exc)[:100]})") from None
    if not isinstance(port, int) or not 1 <= port <= 65535:
        raise InputError(f"--scheduler {_show(address)}: the port must be a whole number from 1 to 65535")
    if not host:
        raise InputError(f"--scheduler {_show(address)}: no host name (e.g. tcp://10.0.0.5:8786)")
    found: list[Any] = []

    def resolve() -> None:
        try:
            found.append(socket.getaddrinfo(host, port, type=socket.SOCK_STREAM))
        except (OSError, UnicodeError) as exc:
            found.append(exc)

    worker = threading.Thread(target=resolve, name="rsm-lrg-resolve", daemon=True)
    worker.start()
    worker.join(timeout)
    if not found:
        return False  # the resolver is slow: the probe says what happens within the timeout
    if isinstance(found[0], BaseException):
        err = found[0]
        why = getattr(err, "strerror", None) or str(err)[:80] or type(err).__name__
        raise InputError(f"--scheduler {_show(address)}: the host name {_show(host)} does not resolve ({why})")
    refused: OSError | None = None
    for family, kind, proto, _, sockaddr in found[0]:
        sock = socket.socket(family, kind, proto)
        sock.settimeout(timeout)
        try:
            sock.connect(sockaddr)
            return True
        except ConnectionRefusedError as exc:
            refused = exc
        except OSError:
            return False  # unreachable, filtered, slow: the probe reports it within the timeout
        finally:
            sock.close()
    if refused is not None:
        raise InputError(f"--scheduler {_show(address)}: nothing listens there (connection refused); "
                         "is the Dask scheduler running?")
    return False


@contextlib.contextmanager
def watch_workers(client: Any, address: str, timeout: float, poll: float = 0.5) -> Iterator[None]:
    """Inside the block, a scheduler left without a worker for ``timeout`` seconds (every
    worker died mid-run while the scheduler stays up: it would hold the batches for ever) ends
    the command with one error naming the scheduler. A thread polls the scheduler's workers
    every ``poll`` seconds and, when they have been gone that long, signals the main thread
    (SIGUSR1), whose handler raises the error where the command waits. Main thread only; a
    scheduler that stops answering is left to the run's own error (:func:`scheduler_lost`)."""
    from ..io import InputError

    if threading.current_thread() is not threading.main_thread() or not hasattr(signal, "SIGUSR1"):
        yield
        return
    stop = threading.Event()
    fired = threading.Event()

    def lost(signum: int, frame: Any) -> None:
        if fired.is_set() and not stop.is_set():
            stop.set()
            raise InputError(f"--scheduler {_show(address)}: no worker left for {timeout:g} s "
                             "(--scheduler-timeout): every worker was lost during the run; no output written")

    def watch() -> None:
        since: float | None = None
        while not stop.wait(poll):
            try:
                n = len(client.nthreads())
            except Exception:  # the scheduler itself is gone: the run fails and says so
                return
            if n:
                since = None
                continue
            now = time.monotonic()
            since = now if since is None else since
            if now - since >= timeout:
                fired.set()
                os.kill(os.getpid(), signal.SIGUSR1)
                return

    old = signal.signal(signal.SIGUSR1, lost)
    thread = threading.Thread(target=watch, name="rsm-lrg-worker-watch", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        thread.join(timeout=5)
        signal.signal(signal.SIGUSR1, old)


@contextlib.contextmanager
def cluster_failures(address: str | None, workers: int | None = None) -> Iterator[None]:
    """With a ``--scheduler``, a failure of the cluster itself (a CancelledError, lost
    communications: the scheduler killed mid-run) is one error naming the scheduler; with
    ``--workers``, a worker process that died (killed by a signal, by the out-of-memory
    killer) is one error naming the option. Errors of the input (``ValueError``,
    ``TypeError``) and signals pass through."""
    from concurrent.futures.process import BrokenProcessPool

    try:
        yield
    except (ValueError, TypeError, KeyboardInterrupt, SystemExit, Terminated):
        raise
    except BrokenProcessPool as exc:
        if address is not None or not workers:
            raise
        raise pool_lost(workers, exc) from None
    except BaseException as exc:
        if address is None:
            raise
        raise scheduler_lost(address, exc) from None


def scheduler_lost(address: str, exc: BaseException):
    """The error for a run whose scheduler stopped answering or went away mid-run."""
    from ..io import InputError

    detail = str(exc).strip().splitlines()[0][:100] if str(exc).strip() else ""
    return InputError(f"--scheduler {_show(address)}: the scheduler was lost during the run "
                      f"({type(exc).__name__}{': ' + detail if detail else ''}); no output written")


def pool_lost(workers: int, exc: BaseException):
    """The error for a run whose local pool broke: one of its worker processes died (killed
    by a signal, by the out-of-memory killer); the other workers are then stopped by
    :func:`close_pool`."""
    from ..io import InputError

    return InputError(f"--workers {workers}: a worker process ended abruptly during the run (killed by a signal "
                      f"or for lack of memory; {type(exc).__name__}); no output written")
