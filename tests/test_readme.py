"""The README's usage example must run as printed."""

import pathlib
import re

import pytest

README = pathlib.Path(__file__).resolve().parents[1] / "README.md"


def python_blocks():
    return re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), flags=re.S)


@pytest.mark.parametrize("code", python_blocks())
def test_readme_example_runs(code, capsys):
    exec(compile(code, str(README), "exec"), {})
    assert capsys.readouterr().out.strip()


def _claims(code):
    """The number each ``print(...)  # claim`` line promises: ``~1e-15`` (order of magnitude) or ``0.0186`` (rounded)."""
    found = []
    for line in code.splitlines():
        match = re.match(r"print\(.*\)\s*#\s*(~?)([-+0-9.eE]+)", line.strip())
        if match:
            found.append((match[1] == "~", match[2]))
    return found


@pytest.mark.parametrize("code", python_blocks())
def test_readme_prints_what_its_comments_say(code, capsys):
    exec(compile(code, str(README), "exec"), {})
    printed = [float(line) for line in capsys.readouterr().out.split()]
    claims = _claims(code)
    assert len(claims) == len(printed)
    for value, (order, text) in zip(printed, claims):
        if order:  # "~1e-15": within a factor of 3 either way
            assert float(text) / 3 <= abs(value) <= 3 * float(text), (value, text)
        else:  # "0.0186": the printed value rounded to the claim's digits
            decimals = len(text.split(".")[1]) if "." in text else 0
            assert round(value, decimals) == float(text), (value, text)
