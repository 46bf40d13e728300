"""Start-up time of the command line and the package, against importing scipy's rotations.

Each command runs in a fresh interpreter, with the numba cache and the bytecode caches warm (one
unmeasured run of each command first, ``PYTHONDONTWRITEBYTECODE`` unset so that the sources are
compiled to ``__pycache__`` once, as ``pip install`` does). The commands run in alternation (a, b, c,
a, b, c, ...) so that they share the machine's conditions; the table gives the median and the best wall
time of the runs, and the median and the least CPU time (user + system) of the child process, which other
jobs on a shared machine inflate far less than the wall time. The peer is
``python -c "import scipy.spatial.transform"``; ``import numpy, typer, numba`` is listed because
``kreisel convert`` cannot start faster than that (it converts with the compiled functions of
:mod:`kreisel.so3`), and ``import numba`` to show that part of it.

Usage: ``python bench/bench_startup.py [repeats]`` (default 7).
"""

from __future__ import annotations

import os
import pathlib
import resource
import statistics
import subprocess
import sys

from _common import header, interleaved, load_average, markdown_table, write_results

SRC = pathlib.Path(__file__).resolve().parents[1] / "src"
PEER = "`python -c 'import scipy.spatial.transform'` (peer)"
COMMANDS = {
    PEER: ["-c", "import scipy.spatial.transform"],
    "`python -c 'import kreisel'`": ["-c", "import kreisel"],
    "`kreisel --help`": ["-m", "kreisel", "--help"],
    "`kreisel convert --from euler:ZXZ --to quat -30 45 60 --degrees`":
        ["-m", "kreisel", "convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degrees"],
    "`python -c 'import numpy, typer, numba'` (what convert cannot undercut)": ["-c", "import numpy, typer, numba"],
    "`python -c 'import numba'` (part of that floor)": ["-c", "import numba"],
    "`python -c 'pass'` (interpreter alone)": ["-c", "pass"],
}
GOALS = {"`python -c 'import kreisel'`": 0.4, "`kreisel --help`": 0.3,
         "`kreisel convert --from euler:ZXZ --to quat -30 45 60 --degrees`": 1.0}


def command(args, cpu):
    """A function running ``python ARGS`` with kreisel's sources first on the path; appends its CPU time to ``cpu``."""
    env = {key: value for key, value in os.environ.items() if key != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPATH"] = str(SRC)

    def run():
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, *args], env=env, capture_output=True, check=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)

    return run


def main(repeats=7):
    load_before = load_average()
    cpu = {name: [] for name in COMMANDS}
    runs = [command(args, cpu[name]) for name, args in COMMANDS.items()]
    timings = dict(zip(COMMANDS, interleaved(*runs, repeats=repeats)))
    peer_median_cpu = statistics.median(cpu[PEER])
    rows = [(name, f"{t.median:.3f}", f"{t.best:.3f}", f"{statistics.median(cpu[name]):.3f}", f"{min(cpu[name]):.3f}",
             f"{t.median / timings[PEER].median:.2f}", f"{statistics.median(cpu[name]) / peer_median_cpu:.2f}",
             GOALS.get(name, "")) for name, t in timings.items()]
    lines = header(
        "Start-up time (`bench/bench_startup.py`)",
        f"Fresh interpreters, numba and bytecode caches warm, {repeats} runs of each command in alternation: "
        "median and best wall time, median and least CPU time (user + system) of the child process. On a "
        "loaded machine the CPU time is the comparable number (a quiet machine's wall time is close to it); "
        "ratios are of the medians to the peer's.",
        load_before=load_before,
    )
    lines += markdown_table(["command", "median wall (s)", "best wall (s)", "median CPU (s)", "least CPU (s)",
                             "wall / peer", "CPU / peer", "goal (s)"], rows, align="lrrrrrrr")
    write_results("startup", "\n".join(lines))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
