"""Hostile cases of issue 26's families that its list did not name, found by an attacker who
had not seen the fixes: each failed before the change it tests.

- outputs: standard input or standard output that is an input file (``fit - < a.csv --json
  a.csv --force`` replaced the input; ``fit a.csv >> a.csv`` appended to it); ``-`` given to
  an output other than ``--json`` (it made a file named ``-``);
- many-file inputs: a set of ``;`` or tab separated CSV files ("its columns changed while it
  was read"), ``--sep``/``--decimal``/``--sheet`` ignored on that path, a directory that cannot
  be listed ("no CSV files");
- processes and clusters: a pool worker killed mid-run (exit 1, "internal error"); an empty
  ``--scheduler`` (ran locally, silently); a bad port, a host that does not resolve, a port
  where nothing listens (a minute of retries, then "no answer"); a server that is not Dask;
- configuration: a ``unit`` beside a value that is not the parameter's unit (ignored: 270 "g"
  taken as 270 kg);
- names: a control character in a column name or a cell (printed raw: a terminal obeys it).

Real processes, files, sockets and readers; no mocks.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pandas as pd
import pytest
from _cli_process import child_pids, cli_env, is_alive, one_error_line, run_cli

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path
from rsm_lrg.io import InputError

TABLE4 = Path(data_path("table4.csv"))
RESPONSE = "tcr_c_per_min"
FACTORS = ["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2"]
ROOT = hasattr(os, "geteuid") and os.geteuid() == 0


# --- outputs -----------------------------------------------------------------------------------

def test_standard_input_that_is_a_file_is_never_an_output(tmp_path):
    data = tmp_path / "a.csv"
    shutil.copy(TABLE4, data)
    before = data.read_bytes()
    with open(data, "rb") as stdin:
        proc = run_cli(["fit", "-", "--response", RESPONSE, "--json", "a.csv", "--force"], tmp_path, stdin=stdin,
                    capture_output=True)
    assert proc.returncode == 2
    one_error_line(proc.stderr, "--json", "a.csv", "standard input", "never overwritten")
    assert data.read_bytes() == before
    # a pipe on standard input is no file: the output is written
    proc = run_cli(["fit", "-", "--response", RESPONSE, "--json", "o.json"], tmp_path, input=before.decode(),
                capture_output=True)
    assert proc.returncode == 0, proc.stderr
    assert json.loads((tmp_path / "o.json").read_text())["n"] == 27


@pytest.mark.parametrize("stdin_too", [False, True])
def test_standard_output_that_is_an_input_is_refused(tmp_path, stdin_too):
    data = tmp_path / "a.csv"
    shutil.copy(TABLE4, data)
    before = data.read_bytes()
    with open(data, "ab") as out, open(data if stdin_too else os.devnull, "rb") as stdin:
        proc = run_cli(["fit", "-" if stdin_too else "a.csv", "--response", RESPONSE, "--json", "-"], tmp_path,
                    stdout=out, stdin=stdin, stderr=subprocess.PIPE)
    assert proc.returncode == 2
    one_error_line(proc.stderr, "standard output is the input file")
    assert data.read_bytes() == before
    # standard output on another file is as usual
    with open(tmp_path / "out.txt", "wb") as out:
        proc = run_cli(["fit", "a.csv", "--response", RESPONSE, "--json", "-"], tmp_path, stdout=out,
                    stderr=subprocess.PIPE)
    assert proc.returncode == 0, proc.stderr
    assert json.loads((tmp_path / "out.txt").read_text())["n"] == 27


@pytest.mark.parametrize("args", [
    ["fit", str(TABLE4), "--response", RESPONSE, "--report", "-"],
    ["design", "box-behnken", "--factor", "a=1:2", "--factor", "b=1:2", "--factor", "c=1:2", "-o", "-"],
])
def test_dash_for_a_file_output_is_refused_not_a_file_named_dash(tmp_path, monkeypatch, capsys, args):
    monkeypatch.chdir(tmp_path)
    assert main(args) == 2
    one_error_line(capsys.readouterr().err, "'-'", "--json only")
    assert list(tmp_path.iterdir()) == []
    assert main([*args[:-1], "./-"]) == 0  # a file named '-', spelled so
    assert (tmp_path / "-").is_file()


# --- many-file inputs ----------------------------------------------------------------------------

def _parts(tmp_path: Path, sep: str = ",", name: str = "parts") -> Path:
    d = tmp_path / name
    d.mkdir()
    df = pd.read_csv(TABLE4)
    for i in range(3):
        df.iloc[i * 9:(i + 1) * 9].to_csv(d / f"p{i}.csv", index=False, sep=sep)
    return d


def _same_fit(a, b) -> bool:
    ca, cb = a["coefficients"]["coded"], b["coefficients"]["coded"]
    return sorted(ca) == sorted(cb) and all(abs(ca[k] - cb[k]) <= 1e-12 for k in ca)


def _fit(capsys, path, *extra):
    status = main(["fit", str(path), "--response", RESPONSE, "--json", "-", *extra])
    cap = capsys.readouterr()
    return status, (json.loads(cap.out) if status == 0 else None), cap.err


@pytest.mark.parametrize("sep, said", [(";", "separator ';' (detected)"), ("\t", "separator tab (detected)"),
                                       ("|", "separator '|' (detected)")])
def test_a_file_set_is_read_as_each_file_alone(tmp_path, capsys, sep, said):
    status, ref, _ = _fit(capsys, TABLE4)
    assert status == 0
    d = _parts(tmp_path, sep)
    status, got, err = _fit(capsys, d)
    assert status == 0, err
    assert got["n"] == 27 and _same_fit(got, ref)
    assert said in err and "3 file(s)" in err
    # --sep is applied to every file (and stated, not "detected")
    status, got, err = _fit(capsys, d, "--sep", sep)
    assert status == 0 and _same_fit(got, ref), err
    # one file of the set written with another separator reads alike
    mixed = _parts(tmp_path, ",", "mixed")
    pd.read_csv(TABLE4).iloc[9:18].to_csv(mixed / "p1.csv", index=False, sep=sep)
    status, got, err = _fit(capsys, mixed)
    assert status == 0 and _same_fit(got, ref), err
    assert "1 file(s)" in err and "p1.csv" in err


def test_reader_options_on_a_file_set_are_applied_or_refused_never_ignored(tmp_path, capsys):
    d = _parts(tmp_path)
    status, _, err = _fit(capsys, d, "--sep", ";")  # wrong separator: the file says so, as alone
    assert status == 2
    one_error_line(err, "p0.csv", "single column")
    status, _, err = _fit(capsys, d, "--sheet", "Runs")
    assert status == 2
    one_error_line(err, "--sheet", "Excel")
    pq = tmp_path / "pq"
    pq.mkdir()
    pd.read_csv(TABLE4).to_parquet(pq / "a.parquet")
    status, _, err = _fit(capsys, pq, "--decimal", ",")
    assert status == 2
    one_error_line(err, "--sep and --decimal", "PARQUET")
    # names are kept as written, file by file: a header with a blank after a name differs
    (d / "p1.csv").write_text((d / "p1.csv").read_text().replace("order,", "order ,", 1))
    status, _, err = _fit(capsys, d)
    assert status == 2
    one_error_line(err, "p1.csv", "missing 'order'", "extra 'order '")


def test_a_quoted_cell_across_the_sniffed_lines_is_read_whole(tmp_path, capsys):
    # the header check reads the first lines only; a quoted cell spanning the cut falls back to
    # the whole file, which reads
    d = _parts(tmp_path)
    df = pd.read_csv(TABLE4)
    df["note"] = ""
    df.loc[0, "note"] = "\n" * 250
    for i in range(3):
        df.iloc[i * 9:(i + 1) * 9].to_csv(d / f"p{i}.csv", index=False)
    status, got, err = _fit(capsys, d)
    assert status == 0, err
    assert got["n"] == 27


@pytest.mark.skipif(not ROOT or shutil.which("setpriv") is None, reason="needs root and setpriv (drop capabilities)")
@pytest.mark.parametrize("mode", [0o000, 0o311])
def test_a_directory_that_cannot_be_listed_is_named_with_its_error(tmp_path, mode):
    d = _parts(tmp_path)
    os.chown(d, 65534, -1)
    os.chmod(d, mode)
    drop = "-dac_override,-dac_read_search"
    for arg in (str(d), str(d / "*.csv")):
        proc = subprocess.run(["setpriv", f"--inh-caps={drop}", f"--bounding-set={drop}", sys.executable, "-m",
                               "rsm_lrg", "fit", arg, "--response", RESPONSE], env=cli_env(), text=True,
                              capture_output=True, timeout=300)
        assert proc.returncode == 2
        one_error_line(proc.stderr, str(d), "cannot be read", "Permission denied")
    os.chmod(d, 0o755)


# --- processes and clusters ----------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="needs Linux /proc to find the workers")
@pytest.mark.parametrize("streamed", [False, True])
def test_a_worker_killed_mid_run_is_one_error_naming_workers(tmp_path, streamed):
    d = pd.read_csv(TABLE4)[FACTORS]
    big = pd.concat([d] * 4000, ignore_index=True)
    design = tmp_path / ("design.parquet" if streamed else "design.csv")
    big.to_parquet(design, index=False) if streamed else big.to_csv(design, index=False)
    out = "o.parquet" if streamed else "o.csv"
    extra = ["--chunk-rows", "1000"] if streamed else []
    proc = subprocess.Popen([sys.executable, "-m", "rsm_lrg", "simulate", design.name, "-o", out, "--seed", "1",
                             "--no-progress", "--workers", "2", *extra], cwd=tmp_path, env=cli_env(), text=True,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    end = time.monotonic() + 120
    kids: list[int] = []
    while time.monotonic() < end and proc.poll() is None:
        kids = child_pids(proc.pid)
        if len(kids) >= 2:
            break
        time.sleep(0.1)
    assert len(kids) >= 2, proc.communicate()[1][-500:]
    time.sleep(1.0)
    os.kill(kids[0], signal.SIGKILL)  # as the out-of-memory killer would
    try:
        err = proc.communicate(timeout=120)[1]
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("the command hung after a worker was killed")
    assert proc.returncode == 2, err
    one_error_line(err, "--workers 2", "worker process ended abruptly", "no output written")
    time.sleep(0.5)
    assert not [k for k in kids if is_alive(k)]
    assert sorted(p.name for p in tmp_path.iterdir()) == [design.name]


class _Server:
    """A TCP listener that answers each connection with ``reply`` (or closes it at once)."""

    def __init__(self, reply: bytes | None):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.reply = reply
        self.conns: list[socket.socket] = []
        threading.Thread(target=self._serve, daemon=True).start()

    def _serve(self):
        while True:
            try:
                c, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(c)
            try:
                if self.reply is None:
                    c.close()
                else:
                    c.sendall(self.reply)
            except OSError:
                pass

    def close(self):
        self.sock.close()
        for c in self.conns:
            c.close()


def _closed_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def test_scheduler_addresses_are_checked_at_once(tmp_path):
    pytest.importorskip("distributed")
    from rsm_lrg.cli.processes import connect_scheduler

    cases = [
        ("", "an empty address"),
        ("   ", "an empty address"),
        ("tcp://127.0.0.1", "not a scheduler address"),
        ("tcp://:8786", "no host name"),
        ("tcp://127.0.0.1:99999", "port must be a whole number from 1 to 65535"),
        ("tcp://127.0.0.1:-1", "port must be a whole number from 1 to 65535"),
        (f"tcp://127.0.0.1:{_closed_port()}", "nothing listens there (connection refused)"),
        ("tcp://no-such-host.invalid:8786", "does not resolve"),
        ("tcp://" + "a" * 300 + ":8786", "does not resolve"),
    ]
    for address, words in cases:
        t0 = time.monotonic()
        with pytest.raises(InputError) as err:
            connect_scheduler(address, timeout=30)
        assert words in str(err.value), (address, str(err.value))
        assert time.monotonic() - t0 < 20, address  # said at once, not after the timeout's retries


@pytest.mark.parametrize("reply", [None, b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\n\r\nhi",
                                   (1).to_bytes(8, "little") + (2**62).to_bytes(8, "little")])
def test_a_server_that_is_not_dask_is_named_as_such(reply):
    pytest.importorskip("distributed")
    from rsm_lrg.cli.processes import connect_scheduler

    srv = _Server(reply)
    try:
        with pytest.raises(InputError) as err:
            connect_scheduler(f"tcp://127.0.0.1:{srv.port}", timeout=5)
    finally:
        srv.close()
    msg = str(err.value)
    assert f"127.0.0.1:{srv.port}" in msg
    assert "not a Dask scheduler" in msg or "no answer within 5 s" in msg, msg


def test_a_scheduler_is_probed_from_inside_a_running_event_loop():
    # a notebook runs its cells inside an event loop, where asyncio.run refuses: the probe runs
    # from a thread of its own there, so a silent server is named for what it does (it was
    # "... (RuntimeError: asyncio.run() cannot be called from a running event loop)")
    pytest.importorskip("distributed")
    import asyncio

    from rsm_lrg.cli.processes import connect_scheduler

    srv = _Server(None)

    async def cell() -> str:
        with pytest.raises(InputError) as err:
            connect_scheduler(f"tcp://127.0.0.1:{srv.port}", timeout=2)
        return str(err.value)

    try:
        msg = asyncio.run(cell())
    finally:
        srv.close()
    assert "RuntimeError" not in msg, msg
    assert "no answer within 2 s" in msg or "does not speak Dask's protocol" in msg, msg


def test_an_empty_scheduler_is_refused_not_run_locally(tmp_path):
    pytest.importorskip("distributed")
    d = pd.read_csv(TABLE4)[FACTORS]
    d.to_csv(tmp_path / "design.csv", index=False)
    proc = run_cli(["simulate", "design.csv", "-o", "o.csv", "--seed", "1", "--scheduler", ""], tmp_path,
                capture_output=True)
    assert proc.returncode == 2
    one_error_line(proc.stderr, "--scheduler", "empty address")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.csv"]


# --- configuration values --------------------------------------------------------------------------

@pytest.mark.parametrize("text, ok", [
    ('[stage_mass_kg]\nvalue = 270\nunit = "g"\n', False),
    ('[mu_k]\nvalue = 0.02\nunit = "%"\n', False),
    ('[mu_k]\nvalue = 0.02\nunit = 1\n', False),
    ('[stage_mass_kg]\nvalue = 0.27\nunit = "kg"\n', True),
    ('[mu_k]\nvalue = 0.02\nunit = "1"\n', True),
    ('[mu_k]\nvalue = 0.02\n', True),
])
def test_a_unit_beside_a_parameter_value_must_be_its_unit(tmp_path, capsys, text, ok):
    p = tmp_path / "p.toml"
    p.write_text(text)
    status = main(["physics", "--params-file", str(p)])
    err = capsys.readouterr().err
    if ok:
        assert status == 0, err
    else:
        assert status == 2
        one_error_line(err, "p.toml", "is not the unit of", "never converted")


@pytest.mark.parametrize("text, kind", [
    ('mu_k = "0.02"\n', "number"),
    ('[mu_k]\nvalue = "0.02"\n', "number"),
    ('hinge_membrane = "true"\n', "boolean"),
])
def test_text_is_never_read_as_a_number_in_a_params_file(tmp_path, capsys, text, kind):
    p = tmp_path / "p.toml"
    p.write_text(text)
    assert main(["physics", "--params-file", str(p)]) == 2
    one_error_line(capsys.readouterr().err, "p.toml", f"is text, not a {kind}")


def test_a_unit_beside_a_calibrated_value_must_be_its_unit(tmp_path):
    from rsm_lrg.surrogate.calibrate import load_calibration

    shipped = Path(data_path("calibration.toml")).read_text()
    assert 'unit = "N s/m"' in shipped
    p = tmp_path / "cal.toml"
    p.write_text(shipped.replace('unit = "N s/m"', 'unit = "N s/mm"', 1))
    with pytest.raises(ValueError) as err:
        load_calibration(p)
    assert "cal.toml" in str(err.value) and "'N s/mm' is not the unit of" in str(err.value)
    p.write_text(shipped)
    assert load_calibration(p).parameter_values()


# --- names ---------------------------------------------------------------------------------------

def test_control_characters_in_names_and_cells_are_refused(tmp_path, capsys):
    df = pd.read_csv(TABLE4)
    name = tmp_path / "name.csv"
    df.rename(columns={"thickness_m": "th\x1b[31mRED\x1b]0;title\x07"}).to_csv(name, index=False)
    assert main(["fit", str(name), "--response", RESPONSE]) == 2
    cap = capsys.readouterr()
    assert "\x1b" not in cap.out + cap.err
    one_error_line(cap.err, "name.csv", "control character", "'\\x1b'")
    cell = tmp_path / "cell.csv"
    lot = df.assign(lot=["a\x1b[2J" if i == 4 else "a" for i in range(len(df))])
    lot.to_csv(cell, index=False)
    assert main(["fit", str(cell), "--response", RESPONSE]) == 2
    cap = capsys.readouterr()
    assert "\x1b" not in cap.out + cap.err
    one_error_line(cap.err, "cell.csv", "column 'lot', row 5", "control character")
    # the same in a Parquet file of a file set
    pq = tmp_path / "pq"
    pq.mkdir()
    lot.to_parquet(pq / "a.parquet")
    lot.assign(lot="a").to_parquet(pq / "b.parquet")
    assert main(["fit", str(pq), "--response", RESPONSE, "--factor", "thickness_m", "--factor", "lot=cat"]) == 2
    one_error_line(capsys.readouterr().err, "a.parquet", "column 'lot', row 5", "control character")
    # a line break inside a quoted text cell (a note) is text, read as before
    note = tmp_path / "note.csv"
    df.assign(note=["two\nlines" if i == 2 else "" for i in range(len(df))]).to_csv(note, index=False)
    assert main(["fit", str(note), "--response", RESPONSE, "--json", "-"]) == 0
    assert json.loads(capsys.readouterr().out)["n"] == 27


def test_a_data_file_the_package_reads_is_never_an_output(tmp_path):
    # physics reads data/lrg_shs15v.toml when it is imported, simulate data/calibration.toml, reproduce
    # the paper's tables: none named on the command line; `physics --json .../lrg_shs15v.toml --force`
    # replaced the defaults. Run on a copy of the package, so that a failure cannot harm this one.
    import rsm_lrg

    pkg = tmp_path / "copy" / "rsm_lrg"
    shutil.copytree(Path(rsm_lrg.__file__).parent, pkg, ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, PYTHONPATH=str(pkg.parent))
    shipped = {p.name: p.read_bytes() for p in (pkg / "data").iterdir() if p.is_file()}
    link = tmp_path / "link.toml"
    link.symlink_to(pkg / "data" / "lrg_shs15v.toml")
    for args in (["physics", "--json", str(pkg / "data" / "lrg_shs15v.toml"), "--force"],
                 ["physics", "--json", str(link), "--force"],
                 ["simulate", str(pkg / "data" / "table4.csv"), "-o", str(pkg / "data" / "calibration.toml"), "--force"],
                 ["fit", str(TABLE4), "--response", RESPONSE, "--json", str(pkg / "data" / "table5_anova.csv"),
                  "--force"]):
        proc = subprocess.run([sys.executable, "-m", "rsm_lrg", *args], cwd=tmp_path, env=env, text=True,
                              capture_output=True, timeout=300)
        assert proc.returncode == 2, (args, proc.stderr)
        one_error_line(proc.stderr, "shipped with rsm-lrg", "never overwritten")
    assert {p.name: p.read_bytes() for p in (pkg / "data").iterdir() if p.is_file()} == shipped
    # a new file beside them is no shipped file
    proc = subprocess.run([sys.executable, "-m", "rsm_lrg", "physics", "--json", str(pkg / "data" / "new.json")],
                          cwd=tmp_path, env=env, text=True, capture_output=True, timeout=300)
    assert proc.returncode == 0, proc.stderr


def test_an_output_keeps_the_permissions_of_the_file_it_replaces_and_the_umask(tmp_path):
    # --force made a private 0600 file world-readable (0644), and a new file ignored the umask
    private = tmp_path / "private.json"
    private.write_text("{}")
    private.chmod(0o600)
    shared = tmp_path / "shared.json"
    shared.write_text("{}")
    shared.chmod(0o664)
    for out in (private, shared):
        proc = run_cli(["fit", str(TABLE4), "--response", RESPONSE, "--json", out.name, "--force"], tmp_path,
                    capture_output=True)
        assert proc.returncode == 0, proc.stderr
        assert json.loads(out.read_text())["n"] == 27
    assert (private.stat().st_mode & 0o777, shared.stat().st_mode & 0o777) == (0o600, 0o664)
    proc = subprocess.run(f"umask 077 && exec {sys.executable} -m rsm_lrg fit {TABLE4} --response {RESPONSE} "
                          f"--json new.json", shell=True, cwd=tmp_path, env=cli_env(), text=True, capture_output=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "new.json").stat().st_mode & 0o777 == 0o600
    if ROOT:  # root replacing another user's file leaves it theirs
        os.chown(private, 65534, 65534)
        proc = run_cli(["fit", str(TABLE4), "--response", RESPONSE, "--json", private.name, "--force"], tmp_path,
                    capture_output=True)
        assert proc.returncode == 0, proc.stderr
        assert (private.stat().st_uid, private.stat().st_mode & 0o777) == (65534, 0o600)


@pytest.mark.parametrize("terms, degree", [("A^99999", "99999"), ("A" * 5000, "5000"), ("A^10B^11", "21"),
                                           ("B A^123456789012345", "beyond 10^10")])
def test_a_term_of_absurd_degree_is_refused_not_computed_for_ever(capsys, terms, degree):
    # fit --terms "A^99999" ran for ever (exact actual-unit coefficients of degree 99999)
    t0 = time.monotonic()
    assert main(["fit", str(TABLE4), "--response", RESPONSE, "--terms", terms]) == 2
    one_error_line(capsys.readouterr().err, "--terms", f"degree {degree}", "at most 20")
    assert time.monotonic() - t0 < 30


def test_a_term_of_degree_twenty_still_fits(capsys):
    assert main(["fit", str(TABLE4), "--response", RESPONSE, "--terms", "A^20 B", "--json", "-"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert "A^20" in out["coefficients"]["coded"]
