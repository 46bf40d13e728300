"""``make demo`` needs no Node.js: neither its recipe nor any recipe it depends on runs node, npm or npx."""

import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.mark.skipif(shutil.which("make") is None or not (ROOT / "Makefile").is_file(),
                    reason="needs make and the repository's Makefile")
def test_make_demo_runs_the_tour_without_node():
    # -n prints the recipes without running them; -B takes every prerequisite as out of date, so the recipes
    # of the whole chain are printed whatever the state of .venv
    recipes = subprocess.run(["make", "-n", "-B", "demo"], cwd=ROOT, capture_output=True, text=True, check=True,
                             timeout=60).stdout
    assert re.search(r"-m kreisel tour\b", recipes), recipes
    assert not re.search(r"\b(node|npm|npx)\b", recipes), recipes
