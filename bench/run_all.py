"""Run every ``bench/bench_*.py`` and assemble ``bench/RESULTS.md``.

Each benchmark compares kreisel with its peer (scipy, solve_ivp, a numpy
expression, Dask vs in-process) in one process and writes its own table to
``bench/results/<topic>.md``; this script runs them one after another (so
they do not compete for the two cores) and concatenates the tables under a
header naming the machine and its load.

Usage: ``python bench/run_all.py [topic ...]`` (default: all);
``python bench/run_all.py --assemble`` only rebuilds RESULTS.md from the tables
already in ``bench/results``.
"""

from __future__ import annotations

import datetime
import subprocess
import sys

from _common import HERE, RESULTS, atomic_write, header, load_average

ORDER = ("so3", "kinematics", "se3", "dynamics", "batch", "tops", "earth", "nav", "sweep")


def topics():
    found = {p.stem.removeprefix("bench_") for p in HERE.glob("bench_*.py")}
    return [t for t in ORDER if t in found] + sorted(found - set(ORDER))


def main(selected):
    load_before = load_average() if selected else None
    for topic in selected:
        print(f"== bench_{topic}.py", flush=True)
        subprocess.run([sys.executable, str(HERE / f"bench_{topic}.py")], check=True)
    lines = header(
        "Benchmark results",
        f"Assembled {datetime.date.today().isoformat()} by `bench/run_all.py` (`make bench`). Each table is "
        "written by its own script; times are medians of several runs, peers measured in the same process. "
        "The machine is shared, so absolute times are noisy: the ratios are what to compare.",
        load_before=load_before,
    )
    parts = [(RESULTS / f"{t}.md").read_text(encoding="utf-8").strip() for t in topics()
             if (RESULTS / f"{t}.md").is_file()]
    out = atomic_write(HERE / "RESULTS.md", "\n".join(lines) + "\n" + "\n\n".join(parts) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    args = sys.argv[1:]
    main([] if args == ["--assemble"] else args or topics())
