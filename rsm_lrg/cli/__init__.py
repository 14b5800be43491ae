"""The ``rsm-lrg`` command line: argument parsing, and the contract every command keeps (option
checks, atomic outputs, signals, exit status); the work is the library's.

Each sub-command lives in a module ``rsm_lrg/cli/cmd_<name>.py`` that defines

``NAME``       the sub-command (``"fit"``),
``HELP``       one line for ``rsm-lrg --help``,
``add_arguments(parser)``  its options, and
``run(args) -> int``       the thin call into the library (imports it lazily).

Modules are found by name, so adding a command touches no shared file. Nothing heavy
(statsmodels, scipy, matplotlib, pandas) is imported before a command runs, which keeps
``rsm-lrg --help`` fast.

Before a command runs, :func:`main` checks its option values (finite numbers and ranges in the
argparse types of ``options``; ``--factor``/``--bound`` specs; an empty file name) and every
output it will write (``paths.planned_outputs``: the values of ``-o/--output``, ``--json``,
``--report`` and options marked by ``paths.output_option``, or what the command's optional
``outputs(args) -> [(option, path)]`` returns): not empty, not a directory or device, absent
unless ``--force``, never one of the input files (also through links, ``--force`` or not), no
two the same, the directory writable. The command then runs inside
:func:`rsm_lrg.io.output_transaction`, so its outputs appear together at the end or not at all.
A single-valued option given twice is an error (nothing is dropped silently).

A reader that closes standard output early (``| head``) does not stop the command: the rest
of what it prints is dropped, its output files are written, and it exits 0; so with a standard
output closed from the start (``>&-``).

SIGINT, SIGTERM and SIGHUP end a command cleanly (:mod:`rsm_lrg.cli.processes`): its worker
processes are stopped, its temporary files removed, no output is half-written, and it exits
``128 + signal`` (130, 143, 129) after one ``error:`` line.

Exit status: 0 success; 2 bad usage or bad input, reported as one ``error:`` line on stderr
of under 300 characters (``--debug`` adds the traceback), including numbers or sizes beyond
computing (OverflowError, FloatingPointError, MemoryError); 1 an internal fault. Library
warnings are shown as one ``warning:`` line each after a success and not after an error.
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import importlib
import os
import signal
import sys
import warnings

from .paths import claim_standard_output, input_paths, mark_outputs, planned_outputs
from .processes import Terminated, ask_one_blas_thread, handle_signals, pending_signal, settle, stop_children
from .specs import check_option_specs

__all__ = ["main", "build_parser", "UsageError"]

#: Order in which commands are listed in ``--help`` (others follow alphabetically).
ORDER = [
    "design", "simulate", "fit", "optimize", "physics", "report", "reproduce",
    "calibrate", "fit-summary", "ridge", "confirm", "evaluate", "datasets",
]


class UsageError(Exception):
    """Raised by argument parsing: printed as one ``error:`` line, exit status 2."""


class _StoreOnce(argparse._StoreAction):
    """``store`` that refuses a second value: ``--json a --json b`` would otherwise drop ``a``
    without a word (options meant to repeat use ``append`` or ``extend``)."""

    def __call__(self, parser, namespace, values, option_string=None):
        seen = namespace.__dict__.setdefault("_given_once", set())
        if self.option_strings and self.dest in seen:
            raise argparse.ArgumentError(self, "given more than once; give it once")
        seen.add(self.dest)
        setattr(namespace, self.dest, values)


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def error(self, message: str):  # one line, no usage dump
        raise UsageError(f"{self.prog}: {message}")


def _command_module_names() -> list[str]:
    """``cmd_*`` module names in this package's directory (a directory listing: no import,
    and not :mod:`pkgutil`, which imports :mod:`inspect`)."""
    names: set[str] = set()
    for here in __path__:
        try:
            entries = os.listdir(here)
        except OSError:
            continue
        names.update(f[:-3] for f in entries if f.startswith("cmd_") and f.endswith(".py"))
    return sorted(names)


def _command_modules():
    mods = [importlib.import_module(f"{__name__}.{name}") for name in _command_module_names()]
    rank = {n: i for i, n in enumerate(ORDER)}
    mods.sort(key=lambda m: (rank.get(m.NAME, len(ORDER)), m.NAME))
    return mods


def _chosen_command(argv: list[str]) -> str:
    """The command named on the command line: the first word that is not an option (the
    top-level options take no value); ``""`` when there is none (``rsm-lrg --help``)."""
    for word in argv:
        if word == "--":
            break
        if not word.startswith("-"):
            return word
    return ""


def _accept_negative_values(p: argparse.ArgumentParser) -> None:
    """Values that begin with '-' (``--observed -2.5e-1``, ``--constraint "-A+B<=1"``) for
    ``p`` and the sub-commands under it (``design optimal``, ...)."""
    from .options import accept_negative_values

    accept_negative_values(p)
    for action in p._actions:
        if isinstance(action, argparse._SubParsersAction):
            for child in action.choices.values():
                _accept_negative_values(child)


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The ``rsm-lrg`` parser. With ``argv``, only the command it names gets its options
    (the others are listed with their one-line help), which keeps ``rsm-lrg --help`` and
    every command's start-up short; without, every command gets its options."""
    from .. import __version__

    parser = _Parser(
        prog="rsm-lrg",
        description=(
            "Design of experiments and response-surface methodology for the linear rolling "
            "guide study of Su, Zhang & Yang (2023)."
        ),
    )
    parser.add_argument("--version", action="version", version=f"rsm-lrg {__version__}")
    parser.add_argument("--debug", action="store_true", help="show a traceback on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    chosen = None if argv is None else _chosen_command(argv)
    for mod in _command_modules():
        p = sub.add_parser(mod.NAME, help=mod.HELP, description=getattr(mod, "DESCRIPTION", mod.HELP))
        p.add_argument("--debug", action="store_true", default=argparse.SUPPRESS, help="show a traceback on errors")
        if chosen is None or mod.NAME == chosen:
            mod.add_arguments(p)
            _accept_negative_values(p)
            p.set_defaults(_run=mod.run, _module=mod)
            mark_outputs(p)
    return parser


#: An error line is cut to this many characters (under 300), as a last resort (messages quote
#: user values shortened by rsm_lrg.io.quote_user_value already).
MAX_ERROR_LINE = 299


def _error_line(msg: str) -> str:
    """``error: MSG`` as one line (newlines and runs of blanks collapsed) of at most
    :data:`MAX_ERROR_LINE` characters."""
    import re

    # a library hint in Python syntax ("use method='optimal'") in the command line's ("use --method optimal")
    msg = re.sub(r"\buse ([a-z][a-z_]*)='([^'\s]*)'", lambda m: f"use --{m.group(1).replace('_', '-')} {m.group(2)}",
                 str(msg))
    words = []
    for w in str(msg).split():  # a 300-digit number or a 10 MB token quoted by a library message
        if len(w) > 60:
            w = re.sub(r"\d{25,}", lambda m: m.group()[:12] + f"\u2026({len(m.group())} digits)", w)
        if len(w) > 120:  # keep both ends: a long path still shows its file name
            w = w[:59] + "\u2026" + w[-60:]
        words.append(w)
    text = "error: " + " ".join(words)
    if len(text) > MAX_ERROR_LINE:
        text = text[: MAX_ERROR_LINE - 1] + "\u2026"
    return text


def _input_name(args) -> str:
    for dest in ("data", "design", "params_file", "calibration"):
        v = getattr(args, dest, None)
        if isinstance(v, str) and v:
            return v
    return ""


class _PipeGuard:
    """Standard output that a closed pipe (``rsm-lrg ... | head -2``) cannot break: once the
    reader has gone, what is printed is dropped (and the stream is pointed at the null
    device, so the interpreter's last flush is quiet), and the command finishes its work and
    writes its output files as without the pipe."""

    def __init__(self, stream):
        self.stream = stream
        self.broken = False

    def _closed(self) -> None:
        import os

        self.broken = True
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, self.stream.fileno())
            os.close(devnull)
        except (OSError, ValueError, AttributeError):  # not a real file (captured in-process)
            pass

    def _failed(self, exc: OSError):
        """Standard output that cannot take the text (a full disk, ``> /dev/full``): the command
        fails (its outputs discarded) with one line, and the stream is closed off so that the
        interpreter's last flush is quiet."""
        from ..io import InputError

        self._closed()
        return InputError(f"cannot write standard output: {exc.strerror or type(exc).__name__}")

    def write(self, text):
        if not self.broken:
            try:
                return self.stream.write(text)
            except BrokenPipeError:
                self._closed()
            except OSError as exc:
                raise self._failed(exc) from None
        return len(text)

    def flush(self):
        if not self.broken:
            try:
                self.stream.flush()
            except BrokenPipeError:
                self._closed()
            except OSError as exc:
                raise self._failed(exc) from None

    def __getattr__(self, name):
        return getattr(self.stream, name)


def _open_closed_standard_streams() -> None:
    """A standard stream closed by the caller (``rsm-lrg ... >&-``) is an ordinary condition:
    its descriptor is pointed at the null device (so that no file the command opens takes
    descriptor 1 and receives printed text) and what is printed to it is dropped, as after a
    closed pipe; output files are written as usual."""
    for fd, name, mode in ((0, "stdin", "r"), (1, "stdout", "w"), (2, "stderr", "w")):
        try:
            os.fstat(fd)
            continue
        except OSError:
            pass
        try:
            null = os.open(os.devnull, os.O_RDWR)
        except OSError:
            continue
        if null != fd:
            os.dup2(null, fd)
            os.close(null)
        if getattr(sys, name, None) is None:
            setattr(sys, name, open(fd, mode, encoding="utf-8", closefd=False))


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``rsm-lrg`` and ``python -m rsm_lrg``; returns the exit status."""
    _open_closed_standard_streams()
    guard = _PipeGuard(sys.stdout)
    sys.stdout = guard
    try:
        with handle_signals(restore=argv is not None):  # SIGTERM and SIGHUP unwind the command like an error
            try:
                status = _main(argv)
                settle(status, leave=argv is None)  # a later signal finds the command ended
            except (KeyboardInterrupt, Terminated) as exc:  # one that came as _main returned
                signum = exc.signum if isinstance(exc, Terminated) else signal.SIGINT
                settle(128 + signum, leave=argv is None)
                status = _stopped(signum)
    finally:
        if sys.stdout is guard:
            sys.stdout = guard.stream
    signalled = pending_signal()
    if argv is None and signalled is not None and status == 128 + signalled:
        _leave(status)
    return status


def _leave(status: int) -> None:
    """End the program at once after a signal, its line printed, its children reaped and its
    files removed: no thread a library left behind (a process pool's manager waiting on workers
    that are gone) may hold the interpreter's exit, which joins such threads without a limit."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
    os._exit(status)


#: Commands that choose their BLAS thread count themselves (``fit`` keeps the threads for a
#: large input, see ``cmd_fit``).
OWN_THREADS = ("fit",)


def _one_blas_thread(argv: list[str]) -> None:
    """Ask for one BLAS thread before NumPy is loaded (:func:`~.processes.ask_one_blas_thread`),
    for every command but those of :data:`OWN_THREADS`: their matrices are small (a design
    search's are p x p, p <= 120; R's reference BLAS is single-threaded too), and OpenBLAS's
    threads cost CPU time at start-up and spin between the many small products of an
    exchange. Processes started by a command (``simulate --workers``) inherit it."""
    if _chosen_command(argv) not in OWN_THREADS:
        ask_one_blas_thread()


def _main(argv: list[str] | None) -> int:
    from ..io import CommitAborted, output_transaction

    argv = sys.argv[1:] if argv is None else list(argv)
    _one_blas_thread(argv)
    if "pyarrow" not in sys.modules:  # Arrow's allocator: no purging thread of its own, which near a
        # memory limit fails and says so on standard error itself ("<jemalloc>: ... failed"), a
        # second line beside the command's one error line
        os.environ.setdefault("JE_ARROW_MALLOC_CONF", "background_thread:false")
    debug = "--debug" in argv
    args = None
    try:
        parser = build_parser(argv)
        args = parser.parse_args(argv)
        if not getattr(args, "command", None):
            parser.print_help(sys.stderr)
            print(_error_line("no command given; choose one of the commands above "
                              "(rsm-lrg COMMAND --help for its options)"), file=sys.stderr)
            return 2
        # every output is checked before any work, so a bad second output cannot leave the
        # first one written; then all outputs are renamed into place together at the end
        check_option_specs(args)
        outputs = planned_outputs(args, getattr(args, "_module", None))
        # an output to /dev/stdout is written as '-' is: the data alone, the printed text on stderr
        printed = contextlib.redirect_stdout(sys.stderr) if claim_standard_output(args, outputs) \
            else contextlib.nullcontext()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("default")
            with output_transaction(inputs=input_paths(args), labels={path: label for label, path in outputs}):
                with printed:
                    status = args._run(args)
                sys.stdout.flush()  # text that cannot be written fails the command before its files appear
                if pending_signal() is not None:  # its exception was swallowed on the way: still no output
                    raise Terminated(pending_signal() or 0)
        late = pending_signal()  # a signal that came while the outputs were placed: they are whole
        if late is not None:
            print(f"error: terminated by {Terminated(late).name} after its outputs were written", file=sys.stderr)
            return 128 + late
        for note in getattr(args, "notes_at_end", None) or ():  # what was read (paths.read_input)
            print(f"note: {note}", file=sys.stderr)
        # a library warning is one line after a success; after an error only the error line shows
        for msg in dict.fromkeys(" ".join(str(w.message).split()) for w in caught
                                 if not issubclass(w.category, (DeprecationWarning, PendingDeprecationWarning))):
            print(f"warning: {msg}"[:MAX_ERROR_LINE], file=sys.stderr)
        return int(status or 0)
    except SystemExit as exc:  # --help, --version
        return int(exc.code or 0) if isinstance(exc.code, int) else 0
    except KeyboardInterrupt:
        return _stopped(signal.SIGINT)
    except CommitAborted:  # a signal came while the outputs were placed: they were taken back
        return _stopped(pending_signal() or signal.SIGINT)
    except Terminated as exc:  # the outputs were discarded on the way out; no worker is left
        return _stopped(exc.signum)
    except Exception as exc:
        signalled = pending_signal()
        if signalled is not None and not isinstance(exc, UsageError):
            # the signal's own exception met a library that swallowed it, and the command then
            # failed for want of its workers (killed by the handler): it is the signal that ended it
            return _stopped(signalled)
        return _failed(exc, args, debug)


def _stopped(signum: int) -> int:
    """After SIGINT, SIGTERM or SIGHUP: every child process killed and reaped, one line, and
    ``128 + signal``."""
    stop_children()
    if signum == signal.SIGINT:
        print("error: interrupted", file=sys.stderr)
    else:
        print(f"error: terminated by {Terminated(signum).name}; no output written", file=sys.stderr)
    return 128 + signum


def _failed(exc: Exception, args, debug: bool) -> int:
    """The exit status and the one ``error:`` line of a command that raised ``exc``."""
    try:
        raise exc
    except BrokenPipeError:
        return 0
    except (UsageError, ValueError, TypeError, FileNotFoundError, KeyError) as exc:
        # Bad input: the library raises ValueError/TypeError with a sentence for the user
        # (rsm_lrg.io.InputError is a ValueError that already names the file).
        if debug:
            import traceback

            traceback.print_exc()
        msg = str(exc).strip() or type(exc).__name__
        if isinstance(exc, KeyError):
            msg = f"not found: {msg}"
        print(_error_line(msg), file=sys.stderr)
        return 2
    except (OverflowError, FloatingPointError, MemoryError) as exc:
        # numbers or sizes far beyond any experiment, from the input or the options
        if debug:
            import traceback

            traceback.print_exc()
        where = _input_name(args) if args is not None else ""
        what = ("memory ran out: the input or options ask for more memory than there is (or than the "
                "address-space limit, ulimit -v, allows)" if isinstance(exc, MemoryError)
                else "a number is too large to compute with")
        detail = str(exc).strip()
        print(_error_line(f"{where + ': ' if where else ''}{what}"
                          f" ({type(exc).__name__}{': ' + detail if detail else ''})"), file=sys.stderr)
        return 2
    except ImportError as exc:
        # a library's shared object that cannot be mapped: the address-space limit (ulimit -v)
        # or the machine's memory ran out while it loaded (the system's loader says so in words)
        text = str(exc).lower()
        if not any(m in text for m in ("failed to map segment", "cannot allocate memory", "cannot map zero-fill")):
            return _internal(exc, debug)
        if debug:
            import traceback

            traceback.print_exc()
        print(_error_line(f"{_OUT_OF_MEMORY} (a library could not be loaded)"), file=sys.stderr)
        return 2
    except OSError as exc:
        if exc.errno not in _SYSTEM_LIMITS:
            return _internal(exc, debug)
        if debug:
            import traceback

            traceback.print_exc()
        print(_error_line("a system limit was reached "
                          f"({exc.strerror or type(exc).__name__}: {_SYSTEM_LIMITS[exc.errno]}); no output written"),
              file=sys.stderr)
        return 2
    except Exception as exc:
        return _internal(exc, debug)


#: The resource limits of the system or of the process (``ulimit``), by errno: met, they end a
#: command with one line and exit 2 (the transaction has removed its files), not an internal error.
_SYSTEM_LIMITS = {errno.EMFILE: "the open-file limit, ulimit -n", errno.ENFILE: "the system's open-file table",
                  errno.EFBIG: "the file-size limit, ulimit -f", errno.ENOSPC: "the disk is full",
                  errno.EDQUOT: "the disk quota", errno.ENOMEM: "memory", errno.EAGAIN: "the process limit, ulimit -u"}


def _near_memory_limit() -> bool:
    """The process has come near its address-space limit (``ulimit -v``, RLIMIT_AS): its peak
    virtual size (``VmPeak``, /proc/self/status) is within a quarter of the limit. A library
    whose allocation failed there may say so only as a SystemError or an ImportError (a shared
    object that could not be mapped)."""
    try:
        import resource

        limit = resource.getrlimit(resource.RLIMIT_AS)[0]
        if limit == resource.RLIM_INFINITY or limit <= 0:
            return False
        with open("/proc/self/status", encoding="ascii", errors="replace") as fh:
            for line in fh:
                if line.startswith("VmPeak:"):
                    return int(line.split()[1]) * 1024 >= 0.75 * limit
    except (OSError, ValueError, ImportError):
        return False
    return False


#: The line of a command that ran out of memory (MemoryError, or a library failing near the limit).
_OUT_OF_MEMORY = ("memory ran out (the process's address-space limit, ulimit -v, or the machine's memory is too "
                  "small for this input and these options); no output written")


def _internal(exc: BaseException, debug: bool) -> int:
    """An internal fault: one line naming the exception, exit 1 (near the address-space limit:
    the memory line and exit 2, since the fault is then the memory a library could not get)."""
    if debug:
        import traceback

        traceback.print_exc()
    if _near_memory_limit():
        print(_error_line(f"{_OUT_OF_MEMORY} ({type(exc).__name__})"), file=sys.stderr)
        return 2
    msg = str(exc).strip()
    print(_error_line(f"internal error ({type(exc).__name__}: {msg[:150]}); rerun with --debug for details"),
          file=sys.stderr)
    return 1
