"""Getting started, read top to bottom, tells of the first run's compilation as the command prints it."""

from kreisel.cli._output import COMPILING
from kreisel.cli.app import app

from .conftest import DOCS


def test_the_page_shows_the_notice_the_command_prints_and_kreisel_compile():
    text = (DOCS / "getting_started.rst").read_text(encoding="utf-8")
    install = text.split("A ten-minute tour")[0]
    assert "kreisel compile" in install
    assert f"   {COMPILING}\n" in text and "\n   kreisel compile\n" in text
    assert "compile" in {command.name for command in app.registered_commands}
