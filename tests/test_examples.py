"""Every gallery script in examples/ runs to completion in quick mode (KREISEL_QUICK=1)."""

import os
import pathlib
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent / "examples"
SCRIPTS = sorted(EXAMPLES.glob("plot_*.py"))


def test_gallery_is_not_empty():
    assert len(SCRIPTS) >= 10


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_example_runs(script, tmp_path):
    env = {**os.environ, "KREISEL_QUICK": "1", "MPLBACKEND": "Agg"}
    result = subprocess.run([sys.executable, script.name], cwd=EXAMPLES, env=env, capture_output=True,
                            text=True, timeout=600)
    assert result.returncode == 0, result.stderr[-3000:]
    assert result.stdout.strip(), "an example should print at least one result"
