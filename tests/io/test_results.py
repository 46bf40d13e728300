"""Result files round-trip and are written atomically."""

from unittest import mock

import numpy as np
import pytest

import kreisel as kr
from kreisel.io import ResultError, load_trajectory, save_result


@pytest.fixture(scope="module")
def trajectory():
    return kr.EulerTop(1.0, 2.0, 3.0).solve(np.linspace(0.0, 2.0, 21), [0.3, 1.0, 0.2])


@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_round_trip(tmp_path, trajectory, suffix):
    path = save_result(trajectory, tmp_path / f"traj{suffix}")
    back = load_trajectory(path)
    np.testing.assert_array_equal(back.t, trajectory.t)
    np.testing.assert_allclose(back.q, trajectory.q, rtol=0, atol=1e-16)
    np.testing.assert_allclose(back.omega, trajectory.omega, rtol=0, atol=1e-16)
    np.testing.assert_array_equal(back.inertia, trajectory.inertia)
    # no temporary file left; a CSV keeps its inertia and metadata in a sidecar
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"traj{suffix}"] + ([f"traj{suffix}.json"] if suffix == ".csv" else [])


def test_failed_write_keeps_the_old_file(tmp_path, trajectory):
    target = tmp_path / "keep.nc"
    target.write_text("precious")

    import xarray as xr

    def broken(*args, **kwargs):
        raise RuntimeError("disk full")

    dataset = xr.Dataset({"x": ("i", [1.0])})
    with pytest.raises(RuntimeError), mock.patch.object(xr.Dataset, "to_netcdf", broken):
        save_result(dataset, target)
    assert target.read_text() == "precious"
    assert [p.name for p in tmp_path.iterdir()] == ["keep.nc"]


def test_unreadable_files_give_one_line_errors(tmp_path):
    with pytest.raises(ResultError, match="no such file"):
        load_trajectory(tmp_path / "absent.nc")
    junk = tmp_path / "junk.csv"
    junk.write_text("a,b\n1,2\n")
    with pytest.raises(ResultError, match="junk.csv: its sidecar file junk.csv.json .* is missing"):
        load_trajectory(junk)
    other = tmp_path / "x.txt"
    other.write_text("")
    with pytest.raises(ResultError, match="unknown trajectory format"):
        load_trajectory(other)
    with pytest.raises(ValueError, match="path must end in one of"):
        save_result(None, tmp_path / "x.txt")


def test_netcdf_variables_carry_cf_units_and_long_names(tmp_path):
    import xarray as xr

    from kreisel.io import load_scenario, run_scenario, save_result

    for name, variables in (("tennis_racket", ("time", "q", "omega", "energy", "angular_momentum")),
                            ("foucault", ("time", "swing_azimuth", "tilt"))):
        path = save_result(run_scenario(load_scenario(name)), tmp_path / f"{name}.nc")
        with xr.open_dataset(path) as ds:
            for variable in variables:
                assert ds[variable].attrs["units"] and ds[variable].attrs["long_name"], (name, variable)
            assert ds["time"].attrs["units"] == "s"
