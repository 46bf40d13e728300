"""``kreisel tour --quick`` writes a self-contained report in which every section passes."""

import re

from typer.testing import CliRunner

from kreisel.cli import app
from kreisel.tour import SECTIONS


def test_quick_tour_passes_and_is_self_contained(tmp_path):
    result = CliRunner().invoke(app, ["tour", "--quick", "--out", str(tmp_path / "out")])
    assert result.exit_code == 0, result.output
    assert "FAIL" not in result.output
    html = (tmp_path / "out" / "index.html").read_text(encoding="utf-8")
    assert f"{len(SECTIONS)} of {len(SECTIONS)} sections pass" in html
    assert "FAIL" not in html
    assert html.count("data:image/png;base64,") >= len(SECTIONS)
    assert not re.search(r"(src|href)=['\"]https?://", html)  # nothing fetched from the network
