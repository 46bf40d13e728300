"""kreisel.sweep with stream=True: chunks written into the Zarr output as they arrive, memory bounded."""

import tracemalloc

import numpy as np
import pytest
import xarray as xr

import kreisel as kr
import kreisel.sweep as ks
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


HISTORIES = """
model = "tennis_racket"
chunk_size = 2
output = "histories.zarr"
stream = true

[grid.middle_moment]
values = [1.2, 1.5, 1.8]

[grid.tilt_deg]
values = [2.0, 20.0]

[constants]
t_end = 20.0
n_samples = 201
store_omega = true
every = 10
"""


def test_sweep_file_streams_decimated_histories_chunk_by_chunk(tmp_path):
    import zarr

    path = tmp_path / "histories.toml"
    path.write_text(HISTORIES, encoding="utf-8")
    streamed = ks.run_sweep_file(path, scheduler="serial")
    assert streamed.omega.chunks is not None  # lazy: read from the store on demand
    assert streamed.omega.dims == ("middle_moment", "tilt_deg", "omega_dim_0", "omega_dim_1")
    assert streamed.omega.shape == (3, 2, 21, 3)  # 201 samples, every 10th kept
    # the store holds one Zarr chunk per sweep chunk of 2 points: writing one touched no other
    omega = zarr.open_group(tmp_path / "histories.zarr", mode="r")["omega"]
    assert omega.chunks == (1, 2, 21, 3) and omega.nchunks_initialized == 3
    memory = ks.run_sweep_file(path, scheduler="serial", output=tmp_path / "memory.zarr", stream=False)
    xr.testing.assert_identical(streamed.load(), memory)
    # the kept samples are those of a decimated batch run; the flip time still uses every sample
    t = np.linspace(0.0, 20.0, 201)
    tilt = np.radians(20.0)
    direct = kr.simulate_batch([1.0, 1.5, 2.0], t, [np.sin(tilt), np.cos(tilt), 0.0], every=10)
    np.testing.assert_array_equal(memory.omega.values[1, 1], direct.omega)
    flips = ks.tennis_racket_flip(np.array([1.5]), np.array([20.0]), t_end=20.0, n_samples=201)
    assert memory.flip_time.values[1, 1] == flips["flip_time"][0]


@pytest.mark.parametrize("edit, match", [
    (lambda s: s.replace("store_omega = true", "store_omega = false"), "set store_omega = true"),
    (lambda s: s.replace("every = 10", "every = 7"), "every must divide n_samples - 1 = 200"),
    (lambda s: s.replace("every = 10", "every = 0"), "every must be a positive integer"),
    (lambda s: s.replace('"histories.zarr"', '"histories.nc"'), r"h\.toml:5: stream: streams into a \.zarr output"),
])
def test_bad_history_files_refused(edit, match):
    with pytest.raises(ks.SweepFileError, match=match):
        ks.parse_sweep_file(edit(HISTORIES), "h.toml")
