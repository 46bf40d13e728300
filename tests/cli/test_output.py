"""What ``kreisel`` prints, as a user sees it (a subprocess): user text as typed, no doubled or blank lines, whole help."""

import functools
import re

import pytest
from typer.main import get_command

from kreisel.cli import app
from kreisel.cli._output import COMPILING


@pytest.fixture
def kreisel(kreisel):
    """The command in an 80-column terminal, where wrapping would cut or double what it prints."""
    return functools.partial(kreisel, env={"COLUMNS": "80"})


def test_an_euler_sequence_is_printed_as_typed_not_as_an_emoji(kreisel):
    done = kreisel("convert", "--from", "euler:ZZZ", "--to", "quat", "1", "2", "3")
    assert done.returncode == 2
    assert "--from euler:ZZZ: seq must not repeat" in done.stderr and "💤" not in done.stderr, done.stderr


@pytest.mark.parametrize("name", ["[bold]top[/bold].toml", "a:zzz:b.toml", "x [red]y.toml"])
def test_file_names_are_printed_as_typed(kreisel, tmp_path, name):
    done = kreisel("simulate", name, cwd=tmp_path)
    assert done.returncode == 2 and f"{name}: no such file" in done.stderr, done.stderr


def test_a_scenario_title_with_markup_runs_and_its_output_starts_with_the_result(kreisel, tmp_path, racket_toml):
    scenario = tmp_path / "s.toml"
    scenario.write_text(racket_toml.replace('"short tennis racket"', '"[bold]racket[/] :zzz:"'))
    done = kreisel("simulate", scenario)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("101 samples, t = 0 … 10 s"), done.stdout[:200]
    assert done.stderr in ("", COMPILING + "\n"), repr(done.stderr)  # no empty line where a bar was


def test_fit_json_says_wrote_once(kreisel, tmp_path):
    done = kreisel("fit", "phone_toss", "--json", tmp_path / "f.json")
    assert done.returncode == 0, done.stderr
    assert done.stdout.count(f"wrote {tmp_path / 'f.json'}") == 1, done.stdout


def test_help_gives_every_command_summary_whole(kreisel):
    done = kreisel("--help")
    commands = done.stdout.split("Commands:")[1]
    assert done.returncode == 0 and "..." not in commands, done.stdout
    text = " ".join(done.stdout.split())
    for name, command in get_command(app).commands.items():
        summary = " ".join(command.get_short_help_str(limit=10**6).split())
        assert f"{name} {summary}" in text, (name, summary)


def test_plot_euler_takes_the_sequence(kreisel, tmp_path, racket_toml):
    scenario, traj = tmp_path / "s.toml", tmp_path / "t.nc"
    scenario.write_text(racket_toml)
    assert kreisel("simulate", scenario, "-o", traj).returncode == 0
    figures = {}
    for seq in ("ZXZ", "zyx"):
        figures[seq] = tmp_path / f"{seq}.png"
        done = kreisel("plot", traj, "--kind", "euler", "--seq", seq, "-o", figures[seq])
        assert done.returncode == 0 and done.stdout.strip() == f"wrote {figures[seq]}", done.stderr
    assert figures["ZXZ"].read_bytes() != figures["zyx"].read_bytes()
    done = kreisel("plot", traj, "--kind", "euler", "--seq", "ZZX", "-o", tmp_path / "bad.png")
    assert done.returncode == 2 and re.search(r"--seq ZZX: .*repeat", done.stderr), done.stderr
    done = kreisel("plot", traj, "--seq", "ZXZ", "-o", tmp_path / "bad.png")
    assert done.returncode == 2 and "--seq: the axis sequence of --kind euler" in done.stderr, done.stderr
