"""The quick tour writes a self-contained report in which every section passes."""

import re

from rich.console import Console

from kreisel.tour import SECTIONS, run_tour


def test_quick_tour_passes_and_is_self_contained(tmp_path):
    console = Console(file=open(tmp_path / "log.txt", "w"), width=120)
    assert run_tour(tmp_path / "out", quick=True, console=console)
    html = (tmp_path / "out" / "index.html").read_text(encoding="utf-8")
    assert f"{len(SECTIONS)} of {len(SECTIONS)} sections pass" in html
    assert "FAIL" not in html
    assert html.count("data:image/png;base64,") >= len(SECTIONS)
    assert not re.search(r"(src|href)=['\"]https?://", html)  # nothing fetched from the network
