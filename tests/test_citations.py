"""Every citation in the repository points into its own theory pages.

kreisel's course lives in docs/theory/ (Theory §1–8 and §A). Text anywhere in
the repository — code, docstrings, comments, tests, docs, README, example and
scenario files — must not refer to files outside it (the lecture notes the
course was written from, developer notes), and every "Theory §N.M" citation must
name a section, subsection or numbered paragraph that the theory pages define.
"""

from __future__ import annotations

import importlib.util
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
THEORY = ROOT / "docs" / "theory"
TEXT_SUFFIXES = {".py", ".pyi", ".rst", ".md", ".txt", ".toml", ".cfg", ".ini", ".yml", ".yaml", ".json",
                 ".js", ".mjs", ".html", ".css", ".ipynb", ".csv"}
TEXT_NAMES = {"Makefile", "README", "LICENSE"}


def _load_extension():
    spec = importlib.util.spec_from_file_location("theory_citations", ROOT / "docs" / "_ext" / "theory_citations.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def repository_text_files():
    """The text files git tracks (or, outside a git checkout, the files on disk)."""
    try:
        listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=ROOT,
                                capture_output=True, check=True).stdout.decode().split("\0")
        paths = [ROOT / p for p in listed if p]
    except (OSError, subprocess.CalledProcessError):
        skip = {".git", "node_modules", "_build", ".venv", "build", "dist", "__pycache__"}
        paths = [p for p in ROOT.rglob("*") if not skip.intersection(p.relative_to(ROOT).parts)]
    return sorted(p for p in paths if p.is_file() and (p.suffix in TEXT_SUFFIXES or p.name in TEXT_NAMES)
                  and p != Path(__file__).resolve() and "node_modules" not in p.parts)


def _lines(path):
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return []
    return text.splitlines()


# Names of files outside the repository (assembled so that this file does not match itself).
OUTSIDE = re.compile("|".join(re.escape(s) for s in ("MATH" + ".md", "../" + "shared", "/work/" + "shared")))

# "seed" meaning the lecture notes, as opposed to the seed of a random generator: names built on it
# (seed_R, SEED_OMEGA, test_seed_…), "the seed", "(seed: …)", "seed/", "seed" with a section numeral, "seed §3",
# "seed series", "…, seed" as a source, and the like.
LECTURE = re.compile(
    r"""(?ix)
      (?<![a-z])seed_(?=[a-z])
    | (?<![a-z])the[\s_]seeds?\b(?![\s_]+(?:of|for|value|that|used|makes)\b)
    | \bseed\s*/
    | \(\s*seed\s*:
    | <th>\s*seed\s*</th>
    | ,\s*seed\s*["']
    | \bseed(?:'s)?[\s_-]*(?:§|[\u4e00-\u9fff]|\d+\.\d|chapter|section|series|mechanics|formula|says|uses|counts|
                            closed|products|quantit|scale|notes|text|lecture|appendix|eq\b|equation|figure|value\b)
    """)


def _offenders(pattern):
    found = []
    for path in repository_text_files():
        for number, line in enumerate(_lines(path), 1):
            if pattern.search(line):
                found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:120]}")
    return found


def test_no_text_refers_to_files_outside_the_repository():
    assert _offenders(OUTSIDE) == []


def test_no_text_cites_the_lecture_notes_as_seed():
    assert _offenders(LECTURE) == []


def test_the_seed_pattern_tells_lecture_citations_from_random_seeds():
    lecture = ["after the chapter in ``seed/``", "The seed uses 7.27221e-5", "(seed: φ̇)", "seed \u4e94.4",
               "source=\"m g l/(I3 ω3), seed\"", "seed_R = R", "SEED_OMEGA = 7.27e-5", "def _seed_zxz(",
               "test_zxz_matrices_are_the_seeds", "the seed series", "seed §3.5"]
    random = ["rate_error(5, 0.01, seed=7)", "seed : int, numpy.random.Generator or None",
              "a seed makes the white noise reproducible", "seed = 2024", "Seed or generator, for draws.",
              "drawn from a seed derived from (``seed``, index)", "The same seed gives the same rotations",
              "seeds = st.integers(0, 2**32 - 1)", "def test_draws_are_seeded_and_shaped():"]
    assert [s for s in lecture if not LECTURE.search(s)] == []
    assert [s for s in random if LECTURE.search(s)] == []


def theory_labels():
    labels = set()
    for page in THEORY.glob("*.rst"):
        labels.update(m.lower() for m in re.findall(r"^\.\. _(theory-[\w.-]+):", page.read_text(encoding="utf-8"),
                                                    re.MULTILINE))
    return labels


def test_every_theory_citation_names_a_section_the_theory_pages_have():
    extension = _load_extension()
    labels = theory_labels()
    missing = []
    for path in repository_text_files():
        for number, line in enumerate(_lines(path), 1):
            for match in extension.CITATION.finditer(line):
                if extension.citation_label(match).lower() not in labels:
                    missing.append(f"{path.relative_to(ROOT)}:{number}: {match.group(0)}")
    assert missing == []


# The chapter's sections and how many numbered subsections each has (§7 has none).
CHAPTER = {"1": 3, "2": 4, "3": 9, "4": 7, "5": 7, "6": 8, "7": 0, "8": 3}


def test_theory_pages_follow_the_chapters_numbering():
    labels = theory_labels()
    for section, count in CHAPTER.items():
        assert f"theory-{section}" in labels
        subsections = {label for label in labels if re.fullmatch(rf"theory-{section}\.\d+", label)}
        assert subsections == {f"theory-{section}.{k}" for k in range(1, count + 1)}, section
    assert {"theory-a", "theory-a-1", "theory-a-2", "theory-a-3", "theory-a-4"} <= labels


@pytest.mark.parametrize("text, label", [
    ("Theory §5.3", "theory-5.3"), ("Theory §2.2 (3)", "theory-2.2-3"), ("Theory §A (2)", "theory-A-2"),
    ("Theory §7", "theory-7"), ("Theory §5.1–§5.4", "theory-5.1"), ("Theory §2.4(2)", "theory-2.4-2")])
def test_citation_labels(text, label):
    extension = _load_extension()
    assert extension.citation_label(extension.CITATION.search(text)) == label


def test_a_citation_of_a_missing_section_is_caught():
    extension = _load_extension()
    labels = theory_labels()
    for text in ("Theory §9.1", "Theory §5.8", "Theory §2.2 (6)", "Theory §7.1", "Theory §A (5)"):
        assert extension.citation_label(extension.CITATION.search(text)).lower() not in labels, text
