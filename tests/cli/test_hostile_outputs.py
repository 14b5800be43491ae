"""Output paths under attack (issues 26 and 36): a path that is not a regular file is written
as a stream (standard output exactly as ``-``; another open descriptor on a terminal, device
or pipe) or refused, never replaced; ``--force`` replaces the named path only (a symbolic link
itself, never the file it leads to); the all-or-nothing commit of several outputs keeps a
real backup when a hard link is refused and puts every file back when it fails; every file a
glob or a directory matches is an input no output may name; a closed standard output is an
ordinary condition.

Cases that need root (a private mount namespace, dropped capabilities) skip without it.
"""

from __future__ import annotations

import json
import os
import shutil
import socket
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from _cli_process import cli_env, one_error_line, run_cli

from rsm_lrg.cli import main
from rsm_lrg.datasets import data_path
from rsm_lrg.io import InputError, output_stream, output_transaction, write_output

TABLE4 = Path(data_path("table4.csv"))
RESPONSE = "tcr_c_per_min"
DESIGN = ["design", "box-behnken", "--factor", "a=1:2", "--factor", "b=1:2", "--factor", "c=1:2", "--seed", "1"]
ROOT = hasattr(os, "geteuid") and os.geteuid() == 0


def test_output_stream_names_open_descriptors(tmp_path):
    assert output_stream("/dev/stdout") == 1
    assert output_stream("/dev/stderr") == 2
    assert output_stream("/dev/fd/7") == 7
    assert output_stream(f"/proc/{os.getpid()}/fd/3") == 3
    assert output_stream("/dev/null") is None
    link = tmp_path / "to-stdout"
    link.symlink_to("/dev/stdout")
    chain = tmp_path / "chain"
    chain.symlink_to(link)
    assert output_stream(link) == 1 and output_stream(chain) == 1
    assert output_stream(tmp_path / "plain.json") is None


@pytest.mark.parametrize("force", [False, True])
def test_a_link_to_standard_output_is_written_through_never_replaced(force, tmp_path):
    # `design -o LINK` where LINK -> /dev/stdout -> /proc/self/fd/1 and stdout is a file:
    # the CSV goes into that file, the link stays a link
    link = tmp_path / "out.csv"
    link.symlink_to("/dev/stdout")
    with open(tmp_path / "res.txt", "w") as res:
        proc = run_cli([*DESIGN, "-o", link, *(["--force"] if force else [])], tmp_path, stdout=res,
                    stderr=subprocess.PIPE)
    assert proc.returncode == 0, proc.stderr
    assert link.is_symlink() and os.readlink(link) == "/dev/stdout"
    text = (tmp_path / "res.txt").read_text()
    assert "std_order,run_order,coded_A" in text and text.count("\n") > 15


@pytest.mark.skipif(not ROOT or shutil.which("unshare") is None, reason="needs root and unshare (a private mount namespace)")
def test_json_to_dev_stdout_with_force_keeps_dev_stdout(tmp_path):
    # the reported case itself, in a private mount namespace whose /dev is a fresh tmpfs (so a
    # failure cannot damage this machine's /dev): `fit ... --json /dev/stdout --force > res.json`
    old = tmp_path / "olddev"
    old.mkdir()
    script = f"""
set -e
mount --make-rprivate / 2>/dev/null || true
mount --bind /dev {old}
mount -t tmpfs tmpfs /dev
for n in null zero urandom random; do touch /dev/$n; mount --bind {old}/$n /dev/$n; done
ln -s /proc/self/fd /dev/fd; ln -s /proc/self/fd/1 /dev/stdout; ln -s /proc/self/fd/2 /dev/stderr
set +e
{sys.executable} -m rsm_lrg fit {TABLE4} --response {RESPONSE} --json /dev/stdout --force > {tmp_path}/res.json
echo "rc=$?" >&2
[ -L /dev/stdout ] && echo "stdout-is-a-link" >&2
{sys.executable} -m rsm_lrg {' '.join(DESIGN)} -o /dev/stdout --force > {tmp_path}/d.csv
echo "rc=$?" >&2
[ -L /dev/stdout ] && echo "stdout-still-a-link" >&2
"""
    proc = subprocess.run(["unshare", "-m", "sh", "-c", script], env=cli_env(), text=True, capture_output=True,
                          timeout=300)
    if "mount:" in proc.stderr and "rc=" not in proc.stderr:
        pytest.skip(f"no private mount namespace here: {proc.stderr.strip()[:200]}")
    assert proc.stderr.count("rc=0") == 2, proc.stderr
    assert "stdout-is-a-link" in proc.stderr and "stdout-still-a-link" in proc.stderr, proc.stderr
    res = (tmp_path / "res.json").read_text()
    assert json.loads(res)["response"] == "tcr_c_per_min"  # the JSON alone, as with --json - (issue 36)
    assert (tmp_path / "d.csv").read_text().startswith("std_order,run_order")


def _fifo(tmp_path):
    p = tmp_path / "fifo"
    os.mkfifo(p)
    return p


def _socket(tmp_path):
    p = tmp_path / "sock"
    s = socket.socket(socket.AF_UNIX)
    s.bind(str(p))
    s.close()
    return p


def _link_to(target):
    def make(tmp_path):
        p = tmp_path / "link"
        p.symlink_to(target(tmp_path) if callable(target) else target)
        return p
    return make


SPECIAL = {
    "fifo": (_fifo, "named pipe"),
    "socket": (_socket, "socket"),
    "link-to-device": (_link_to("/dev/null"), "device"),
    "link-to-fifo": (_link_to(_fifo), "named pipe"),
    "device": (lambda tmp_path: Path("/dev/null"), "device"),
}


@pytest.mark.parametrize("force", [False, True])
@pytest.mark.parametrize("kind", sorted(SPECIAL))
@pytest.mark.parametrize("cmd", ["design", "fit"])
def test_a_special_file_is_never_replaced(cmd, kind, force, tmp_path, capsys):
    make, word = SPECIAL[kind]
    path = make(tmp_path)
    before = os.lstat(path)
    argv = [*DESIGN, "-o", str(path)] if cmd == "design" else \
        ["fit", str(TABLE4), "--response", RESPONSE, "--json", str(path)]
    assert main(argv + (["--force"] if force else [])) == 2
    line = one_error_line(capsys.readouterr().err, word, "-o" if cmd == "design" else "--json")
    assert "never replaced" in line
    after = os.lstat(path)
    assert stat.S_IFMT(after.st_mode) == stat.S_IFMT(before.st_mode) and after.st_ino == before.st_ino
    assert sorted(p.name for p in tmp_path.iterdir() if p.name.startswith(".")) == []


def _victim_inside(tmp_path):
    return tmp_path / "victim.txt"


def _victim_outside(tmp_path):
    other = tmp_path.parent / f"{tmp_path.name}-elsewhere"
    other.mkdir(exist_ok=True)
    return other / "victim.txt"


@pytest.mark.parametrize("where", ["inside", "outside", "relative"])
@pytest.mark.parametrize("cmd", ["design", "fit"])
def test_force_replaces_a_link_never_the_file_it_leads_to(cmd, where, tmp_path, monkeypatch, capsys):
    # issue 36: `fit ... --json link.json --force`, link.json -> victim.txt, rewrote victim.txt;
    # --force replaces the named path (the link itself, atomically), never the file it leads to
    monkeypatch.chdir(tmp_path)
    victim = _victim_outside(tmp_path) if where == "outside" else _victim_inside(tmp_path)
    victim.write_text("precious\n")
    os.chmod(victim, 0o600)
    link = tmp_path / "out" / "link.json"
    link.parent.mkdir()
    link.symlink_to(os.path.relpath(victim, link.parent) if where == "relative" else victim)
    argv = [*DESIGN, "-o", str(link)] if cmd == "design" else \
        ["fit", str(TABLE4), "--response", RESPONSE, "--json", str(link)]
    assert main(argv) == 2  # without --force: the link is an existing file
    one_error_line(capsys.readouterr().err, "already exists")
    assert main(argv + ["--force"]) == 0, capsys.readouterr().err
    capsys.readouterr()
    assert victim.read_text() == "precious\n" and stat.S_IMODE(victim.stat().st_mode) == 0o600
    assert not link.is_symlink() and link.is_file()
    assert link.read_text().startswith("std_order," if cmd == "design" else "{")
    assert sorted(p.name for p in link.parent.iterdir()) == ["link.json"]


@pytest.mark.parametrize("force", [False, True])
def test_force_replaces_a_dangling_link(force, tmp_path, capsys):
    link = tmp_path / "d.csv"
    link.symlink_to(tmp_path / "nowhere" / "gone.csv")
    rc = main([*DESIGN, "-o", str(link), *(["--force"] if force else [])])
    err = capsys.readouterr().err
    if not force:
        assert rc == 2
        one_error_line(err, "already exists", "symbolic link")
        assert link.is_symlink()
    else:
        assert rc == 0, err
        assert not link.is_symlink() and link.read_text().startswith("std_order,")
    assert not (tmp_path / "nowhere").exists()


@pytest.mark.parametrize("force", [False, True])
def test_a_link_to_a_directory_is_refused(force, tmp_path, capsys):
    target = tmp_path / "dir"
    target.mkdir()
    (target / "keep.txt").write_text("kept\n")
    link = tmp_path / "d.csv"
    link.symlink_to(target)
    assert main([*DESIGN, "-o", str(link), *(["--force"] if force else [])]) == 2
    one_error_line(capsys.readouterr().err, "-o", "directory")
    assert link.is_symlink() and sorted(p.name for p in target.iterdir()) == ["keep.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.csv", "dir"]


def test_a_failed_commit_puts_back_a_link_it_replaced(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.symlink_to(victim.name)
    with pytest.raises(InputError, match="b.json"):
        with output_transaction():
            write_output(a, "new a\n", force=True)
            write_output(b, "new b\n", force=True)
            b.mkdir()
    assert a.is_symlink() and os.readlink(a) == "victim.txt" and victim.read_text() == "precious\n"


def test_a_failed_commit_puts_back_every_file_it_replaced(tmp_path):
    # the second output's target turns into a directory between the checks and the commit
    # (a concurrent writer): the first output, already placed, is put back as it was
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    a.write_text("first, kept\n")
    ino = a.stat().st_ino
    with pytest.raises(InputError, match="b.json"):
        with output_transaction():
            write_output(a, "new a\n", force=True)
            write_output(b, "new b\n", force=True)
            b.mkdir()
            (b / "x").write_text("occupied")
    assert a.read_text() == "first, kept\n" and a.stat().st_ino == ino
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "b.json"]


@pytest.mark.skipif(not ROOT or shutil.which("setpriv") is None, reason="needs root and setpriv (drop capabilities)")
def test_backup_kept_when_hard_links_are_refused(tmp_path):
    # the reported case: the backup hard link of d1/out.json is refused (protected_hardlinks:
    # another user's file, no CAP_FOWNER), and d2/out.html cannot be replaced (a sticky
    # directory of another user): exit 2 and d1/out.json is still the very file it was
    if Path("/proc/sys/fs/protected_hardlinks").read_text().strip() != "1":
        pytest.skip("protected_hardlinks is off here")
    d1, d2 = tmp_path / "d1", tmp_path / "d2"
    d1.mkdir()
    d2.mkdir()
    (d1 / "out.json").write_text("keep me\n")
    (d2 / "out.html").write_text("theirs\n")
    nobody = 65534
    os.chown(d1 / "out.json", nobody, -1)
    os.chmod(d1 / "out.json", 0o600)
    os.chown(d2 / "out.html", nobody, -1)
    os.chown(d2, nobody, -1)
    os.chmod(d2, 0o1777)
    ino = (d1 / "out.json").stat().st_ino
    drop = "-fowner,-dac_override"
    proc = subprocess.run(["setpriv", f"--inh-caps={drop}", f"--bounding-set={drop}", sys.executable, "-m",
                           "rsm_lrg", "fit", str(TABLE4), "--response", RESPONSE, "--json", "d1/out.json",
                           "--report", "d2/out.html", "--force"], cwd=tmp_path, env=cli_env(), text=True,
                          capture_output=True, timeout=300)
    assert proc.returncode == 2, proc.stderr
    one_error_line(proc.stderr, "--report", "d2/out.html")
    st = (d1 / "out.json").stat()
    assert (d1 / "out.json").read_text() == "keep me\n" and st.st_ino == ino and st.st_uid == nobody
    assert (d2 / "out.html").read_text() == "theirs\n"
    assert sorted(p.name for p in d1.iterdir()) == ["out.json"] and sorted(p.name for p in d2.iterdir()) == ["out.html"]


@pytest.mark.parametrize("how", ["glob", "directory"])
def test_a_file_a_glob_or_directory_matches_is_never_an_output(how, tmp_path, capsys):
    parts = tmp_path / "parts"
    parts.mkdir()
    for n in ("a", "b"):
        shutil.copy(TABLE4, parts / f"{n}.csv")
    src = str(parts / "*.csv") if how == "glob" else str(parts)
    assert main(["fit", src, "--response", RESPONSE, "--json", str(parts / "a.csv"), "--force"]) == 2
    one_error_line(capsys.readouterr().err, "--json", "input")
    assert (parts / "a.csv").read_bytes() == TABLE4.read_bytes()


def _closed(*fds):
    def pre():
        for fd in fds:
            os.close(fd)
    return pre


def test_closed_standard_output_is_ordinary(tmp_path):
    # `rsm-lrg fit ... --json j.json --report r.html >&-`: files written, exit 0
    proc = run_cli(["fit", TABLE4, "--response", RESPONSE, "--json", "j.json", "--report", "r.html"], tmp_path,
                stderr=subprocess.PIPE, preexec_fn=_closed(1))
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert (tmp_path / "j.json").read_text().startswith("{")
    assert (tmp_path / "r.html").read_text().rstrip().endswith("</html>")
    # --json - and -o /dev/stdout into a closed standard output: dropped, as after `| head -0`
    proc = run_cli(["fit", TABLE4, "--response", RESPONSE, "--json", "-"], tmp_path, stderr=subprocess.PIPE,
                preexec_fn=_closed(1))
    assert proc.returncode == 0 and "error" not in proc.stderr  # the notes still go to stderr
    proc = run_cli([*DESIGN, "-o", "/dev/stdout"], tmp_path, stderr=subprocess.PIPE, preexec_fn=_closed(1))
    assert proc.returncode == 0 and "error" not in proc.stderr  # the summary goes to stderr, as with '-'
    # with standard error closed too, an error is still exit 2 and nothing lands in a file
    proc = run_cli(["fit", "missing.csv", "--response", RESPONSE, "--json", "j2.json"], tmp_path,
                preexec_fn=_closed(1, 2))
    assert proc.returncode == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["j.json", "r.html"]


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="no /dev/full here")
@pytest.mark.parametrize("json_to", ["file", "stdout"])
def test_a_full_standard_output_fails_cleanly(json_to, tmp_path):
    # `> /dev/full`: the printed result cannot be written; exit 2 with one line and no file
    # (once an internal error, exit 1)
    dest = "j.json" if json_to == "file" else "/dev/stdout"
    with open("/dev/full", "w") as full:
        proc = run_cli(["fit", TABLE4, "--response", RESPONSE, "--json", dest, "--report", "r.html"], tmp_path,
                    stdout=full, stderr=subprocess.PIPE)
    assert proc.returncode == 2, proc.stderr
    err = "".join(line for line in proc.stderr.splitlines(True) if not line.startswith("note: "))  # as with '-'
    one_error_line(err, "standard output", "No space left")
    assert list(tmp_path.iterdir()) == []


def _design_bytes(tmp_path) -> bytes:
    ref = tmp_path / "ref.csv"
    assert main([*DESIGN, "-o", str(ref)]) == 0
    data = ref.read_bytes()
    ref.unlink()
    return data


@pytest.mark.parametrize("stdout_is", ["file", "pipe"])
def test_dev_stdout_is_written_as_dash(stdout_is, tmp_path, capsys):
    # issue 36: `fit --json /dev/stdout --force > res.json` held the text summary, and
    # `design -o /dev/stdout > d.csv` the design's summary: now the data alone goes to
    # standard output, the summary to standard error, exactly as '-' does
    expected_csv = _design_bytes(tmp_path)
    capsys.readouterr()
    runs = {"fit": ["fit", TABLE4, "--response", RESPONSE, "--json", "/dev/stdout", "--force"],
            "fit-dash": ["fit", TABLE4, "--response", RESPONSE, "--json", "-"],
            "design": [*DESIGN, "-o", "/dev/stdout", "--force"],
            "design-fd": [*DESIGN, "-o", "/dev/fd/1"]}
    got = {}
    for name, argv in runs.items():
        if stdout_is == "file":
            with open(tmp_path / f"{name}.out", "w") as out:
                proc = run_cli(argv, tmp_path, stdout=out, stderr=subprocess.PIPE)
            got[name] = (tmp_path / f"{name}.out").read_bytes()
        else:
            proc = subprocess.run([sys.executable, "-m", "rsm_lrg", *map(str, argv)], cwd=tmp_path, env=cli_env(),
                                  capture_output=True, timeout=300)
            got[name] = proc.stdout
        assert proc.returncode == 0, proc.stderr
    assert json.loads(got["fit"]) == json.loads(got["fit-dash"])
    assert got["design"] == expected_csv and got["design-fd"] == expected_csv


def test_standard_output_named_twice_is_refused(tmp_path, capsys):
    assert main(["fit", str(TABLE4), "--response", RESPONSE, "--json", "-", "--report", "/dev/stdout"]) == 2
    one_error_line(capsys.readouterr().err, "--report", "--json", "standard output")
    assert list(tmp_path.iterdir()) == []


def test_a_descriptor_on_a_regular_file_is_not_written_through(tmp_path):
    # /dev/stderr (or /dev/fd/N) open on a regular file is no terminal, device or pipe:
    # refused, and the file is left as it was; a pipe is written through
    with open(tmp_path / "err.txt", "w") as err:
        proc = run_cli([*DESIGN, "-o", "/dev/stderr"], tmp_path, stdout=subprocess.PIPE, stderr=err)
    assert proc.returncode == 2
    one_error_line((tmp_path / "err.txt").read_text(), "/dev/stderr", "regular file")
    proc = run_cli([*DESIGN, "-o", "/dev/stderr"], tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.returncode == 0 and "std_order,run_order" in proc.stderr, proc.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["err.txt"]
