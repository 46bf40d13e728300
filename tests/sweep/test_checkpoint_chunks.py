"""A checkpoint chunk that a crash left empty or truncated is reported and computed again, from the command line."""

import os
import pathlib
import subprocess
import sys

import numpy as np
import xarray as xr

import kreisel as kr
from kreisel.sweep import load_sweep_file, sweep
from kreisel.sweep.models import MODELS

SRC = pathlib.Path(kr.__file__).resolve().parents[1]

SWEEP = """\
title = "small apex map"
model = "lagrange_apex"
chunk_size = 2
[grid.phi_dot]
start = -1.0
stop = 1.0
num = 3
[grid.psi_dot]
start = 4.0
stop = 8.0
num = 2
[constants]
I1 = 1.0
I3 = 0.5
mgl = 1.0
theta0_deg = 60.0
"""


def test_empty_and_truncated_chunks_are_recomputed(tmp_path):
    spec_file = tmp_path / "apex.toml"
    spec_file.write_text(SWEEP)
    spec = load_sweep_file(spec_file)
    chunks = tmp_path / "apex.nc.chunks"   # where `kreisel sweep apex.toml -o apex.nc` keeps its checkpoint
    reference = sweep(MODELS[spec.model].function, spec.grid, constants=spec.constants, chunk_size=spec.chunk_size,
                      scheduler="serial", checkpoint=chunks, keep_checkpoint=True)
    (chunks / "chunk-000000.npz").write_bytes(b"")
    half = chunks / "chunk-000002.npz"
    half.write_bytes(half.read_bytes()[: half.stat().st_size // 2])
    env = dict(os.environ, PYTHONPATH=str(SRC), COLUMNS="200")
    process = subprocess.run([sys.executable, "-m", "kreisel", "sweep", "apex.toml", "-o", "apex.nc",
                              "--scheduler", "serial"], cwd=tmp_path, env=env, capture_output=True, text=True,
                             timeout=600)
    assert process.returncode == 0, process.stderr
    assert "Traceback" not in process.stderr and "Aborted" not in process.stderr
    text = " ".join(process.stderr.split())
    assert "chunk 0: discarded" in text and "chunk-000000.npz (0 bytes) is unreadable" in text
    assert "chunk 2: discarded" in text and "computing the chunk again" in text
    result = xr.open_dataset(tmp_path / "apex.nc").load()
    for name in reference.data_vars:
        np.testing.assert_array_equal(result[name].values, reference[name].values)
    assert not chunks.exists()
