"""Start-up time of the command line and the package, against importing scipy's rotations.

Each command runs in a fresh interpreter (the median of several runs, wall time), with the numba cache
warm: one unmeasured run of each command first. The peer is ``python -c "import scipy.spatial.transform"``,
measured the same way, so the ratios hold on a loaded machine too.
"""

from __future__ import annotations

import os
import pathlib
import statistics
import subprocess
import sys
import time

SRC = pathlib.Path(__file__).resolve().parents[1] / "src"
COMMANDS = {
    "python -c 'import scipy.spatial.transform' (peer)": ["-c", "import scipy.spatial.transform"],
    "python -c 'import kreisel'": ["-c", "import kreisel"],
    "kreisel --help": ["-m", "kreisel", "--help"],
    "kreisel convert --from euler:ZXZ --to quat -30 45 60 --degrees":
        ["-m", "kreisel", "convert", "--from", "euler:ZXZ", "--to", "quat", "-30", "45", "60", "--degrees"],
    "python -c 'pass' (interpreter alone)": ["-c", "pass"],
}
GOALS = {"python -c 'import kreisel'": 0.4, "kreisel --help": 0.3,
         "kreisel convert --from euler:ZXZ --to quat -30 45 60 --degrees": 1.0}


def seconds(args, repeat):
    env = dict(os.environ, PYTHONPATH=str(SRC))
    subprocess.run([sys.executable, *args], env=env, capture_output=True, check=True)   # warm caches
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, *args], env=env, capture_output=True, check=True)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main(repeat=7):
    results = {name: seconds(args, repeat) for name, args in COMMANDS.items()}
    peer = results["python -c 'import scipy.spatial.transform' (peer)"]
    print("| command | median wall time (s) | / scipy import | goal (s) |")
    print("|---|---|---|---|")
    for name, value in results.items():
        goal = GOALS.get(name)
        print(f"| `{name}` | {value:.3f} | {value / peer:.2f} | {goal if goal else ''} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 7)
