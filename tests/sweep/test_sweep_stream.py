"""kreisel.sweep with stream=True: chunks written into the Zarr output as they arrive, memory bounded."""

import tracemalloc

import numpy as np
import pytest
import xarray as xr

import kreisel as kr
from kreisel.sweep import sweep

T = np.linspace(0.0, 2.0, 41)


def trajectories(spin, tilt, every=4):
    """Dense batch trajectories per grid point: the kind of result that outgrows memory in a large sweep."""
    omega0 = np.stack([np.sin(tilt), spin * np.cos(tilt), 0.1 + 0.0 * tilt], axis=-1)
    tr = kr.simulate_batch([1.0, 2.0, 2.8], T, omega0, method="rk4", dt=0.01, every=every)
    return {"omega": tr.omega, "q": tr.q, "energy": tr.energy[:, -1]}


GRID = {"spin": [0.5, 1.0, 2.0], "tilt": np.linspace(0.01, 0.5, 5)}


def test_streamed_sweep_equals_the_in_memory_sweep(tmp_path):
    # chunk_size 4 cuts the (3, 5) grid across its rows: every chunk is written as several blocks
    memory = sweep(trajectories, GRID, chunk_size=4, scheduler="serial")
    target = tmp_path / "traj.zarr"
    streamed = sweep(trajectories, GRID, chunk_size=4, scheduler="serial", output=target, stream=True,
                     keep_checkpoint=True)
    assert streamed.omega.chunks is not None  # lazy: read from the store on demand
    xr.testing.assert_identical(streamed.load(), memory)
    np.testing.assert_array_equal(memory.q.values[2, 4], trajectories(np.array([2.0]), np.array([0.5]))["q"][0])
    # resumed from the checkpoint: each stored chunk goes straight into the new store
    resumed = sweep(trajectories, GRID, chunk_size=4, scheduler="serial", output=target, stream=True)
    xr.testing.assert_identical(resumed.load(), memory)
    assert sorted(p.name for p in tmp_path.iterdir()) == [target.name]


def large(index, size):
    return {"x": np.broadcast_to(index[:, None], (index.size, size)) + np.arange(size)}


def test_streamed_sweep_holds_about_one_chunk_in_memory(tmp_path):
    # 32 chunks of 1 MB: the in-memory sweep holds all 32 MB (twice, while assembling), the stream a few MB
    grid, constants = {"index": np.arange(64.0)}, {"size": 2**16}
    chunk_bytes = 2 * 2**16 * 8
    peaks = {}
    for stream in (False, True):
        tracemalloc.start()
        ds = sweep(large, grid, constants=constants, chunk_size=2, scheduler="serial", stream=stream,
                   output=tmp_path / f"{stream}.zarr")
        peaks[stream] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        assert float(ds.x[63, 2**16 - 1]) == 63.0 + 2**16 - 1
        del ds
    assert peaks[False] > 32 * chunk_bytes
    assert peaks[True] < 6 * chunk_bytes, f"streamed sweep peaked at {peaks[True] / chunk_bytes:.1f} chunks"


def test_stream_needs_a_zarr_output(tmp_path):
    for output in (None, tmp_path / "a.nc"):
        with pytest.raises(ValueError, match="stream=True"):
            sweep(large, {"index": [1.0]}, constants={"size": 2}, scheduler="serial", stream=True, output=output)
    with pytest.raises(TypeError, match="stream must be"):
        sweep(large, {"index": [1.0]}, constants={"size": 2}, scheduler="serial", stream=1,
              output=tmp_path / "a.zarr")
