"""The atomic writer: permissions that follow the umask, fsync, and no temporaries left by a killed write."""

import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

import kreisel as kr
from kreisel import _fileio
from kreisel._fileio import atomic_output, remove_stale_temporaries

SRC = pathlib.Path(kr.__file__).resolve().parents[1]


@pytest.mark.parametrize("umask, mode", [(0o022, 0o644), (0o077, 0o600), (0o002, 0o664)])
def test_a_simulated_trajectory_file_follows_the_umask(tmp_path, umask, mode):
    env = dict(os.environ, PYTHONPATH=str(SRC))
    process = subprocess.run([sys.executable, "-m", "kreisel", "simulate", "tennis_racket", "-o", "traj.csv"],
                             cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
                             preexec_fn=lambda: os.umask(umask))
    assert process.returncode == 0, process.stderr
    # the table and its sidecar of metadata, nothing else (no temporary file left behind)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["traj.csv", "traj.csv.json"]
    for name in ("traj.csv", "traj.csv.json"):
        assert (tmp_path / name).stat().st_mode & 0o777 == mode, name


def test_a_replaced_file_keeps_its_permissions(tmp_path):
    target = tmp_path / "report.html"
    target.write_text("old")
    target.chmod(0o640)
    with atomic_output(target) as tmp:
        tmp.write_text("new")
    assert target.read_text() == "new" and target.stat().st_mode & 0o777 == 0o640


def test_the_data_are_flushed_before_the_rename(tmp_path, monkeypatch):
    events = []
    monkeypatch.setattr(_fileio.os, "fsync", lambda fd: events.append("fsync"))
    real_replace = os.replace
    monkeypatch.setattr(_fileio.os, "replace", lambda a, b: (events.append("replace"), real_replace(a, b)))
    with atomic_output(tmp_path / "x.txt") as tmp:
        tmp.write_text("data")
    assert events[:2] == ["fsync", "replace"] and (tmp_path / "x.txt").read_text() == "data"


WRITER = """
import sys, time
from kreisel._fileio import atomic_output
with atomic_output(sys.argv[1]) as tmp:
    tmp.write_bytes(b"half a file")
    print(tmp, flush=True)
    time.sleep(600)
"""


def test_a_killed_write_leaves_a_temporary_that_the_next_write_removes(tmp_path):
    target = tmp_path / "map.png"
    env = dict(os.environ, PYTHONPATH=str(SRC))
    writer = subprocess.Popen([sys.executable, "-c", WRITER, str(target)], env=env, stdout=subprocess.PIPE, text=True)
    try:
        temporary = pathlib.Path(writer.stdout.readline().strip())
        assert temporary.exists() and temporary.name.startswith(".map.png.kreisel-")
        assert remove_stale_temporaries(target) == []          # still being written: kept
    finally:
        writer.send_signal(signal.SIGKILL)
        writer.wait(timeout=60)
        writer.stdout.close()
    assert temporary.exists() and not target.exists()
    with atomic_output(target) as tmp:
        tmp.write_bytes(b"whole")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["map.png"]


def test_old_temporaries_go_even_if_their_process_id_runs_again(tmp_path):
    target = tmp_path / "traj.nc"
    mine = tmp_path / f".traj.nc.kreisel-{os.getpid()}-abc.nc"
    mine.write_bytes(b"x")
    other = tmp_path / ".traj.nc.kreisel-1-abc.nc"   # another file's temporaries are never touched
    unrelated = tmp_path / ".other.nc.kreisel-1-abc.nc"
    other.write_bytes(b"x")
    unrelated.write_bytes(b"x")
    later = time.time() + _fileio.STALE_AFTER + 1
    removed = remove_stale_temporaries(target, now=later)
    assert sorted(p.name for p in removed) == sorted([mine.name, other.name]) and unrelated.exists()
