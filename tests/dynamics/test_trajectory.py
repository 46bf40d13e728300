"""Trajectory: derived quantities, Euler angles, drift report, export and save/load round trips."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kreisel as kr
from kreisel.dynamics import ConstantForce, GravityTorque


@pytest.fixture(scope="module")
def trajectory():
    q0 = np.array([0.9, 0.1, -0.3, 0.3])
    return kr.simulate([1.0, 2.0, 3.0], np.linspace(0, 10, 21), [0.1, 1.0, 0.1], q0 / np.linalg.norm(q0))


def test_space_quantities(trajectory):
    R = Rotation.from_quat(trajectory.q, scalar_first=True)
    np.testing.assert_allclose(trajectory.omega_space, R.apply(trajectory.omega), atol=1e-15)
    j_body = trajectory.omega * [1.0, 2.0, 3.0]
    np.testing.assert_allclose(trajectory.angular_momentum(frame="body"), j_body, atol=1e-15)
    np.testing.assert_allclose(trajectory.angular_momentum(frame="space"), R.apply(j_body), atol=1e-15)
    np.testing.assert_allclose(trajectory.energy, 0.5 * np.sum(trajectory.omega * j_body, axis=-1))
    with pytest.raises(ValueError, match="frame"):
        trajectory.angular_momentum(frame="lab")


def test_euler_angles_match_scipy(trajectory):
    R = Rotation.from_quat(trajectory.q, scalar_first=True)
    for seq in ("ZXZ", "xyz"):
        ours = trajectory.euler(seq)
        np.testing.assert_allclose(Rotation.from_euler(seq, ours).as_matrix(), R.as_matrix(), atol=1e-12)
    np.testing.assert_allclose(trajectory.euler("ZXZ", degrees=True), np.degrees(trajectory.euler("ZXZ")))


def test_drift_report(trajectory):
    drift = trajectory.drift()
    assert set(drift) == {"energy", "angular_momentum", "direction", "quaternion_norm"}
    assert drift["energy"] < 1e-11 and drift["angular_momentum"] < 1e-11
    assert drift["direction"] < 1e-11 and drift["quaternion_norm"] < 1e-15
    # under a torque the report measures what the torque did
    top = kr.simulate([1.0, 1.0, 0.5], np.linspace(0, 2, 5), [0, 0, 10.0], [np.cos(0.2), np.sin(0.2), 0, 0],
                      torque=GravityTorque(5.0, [0, 0, 0.3]))
    assert top.drift()["direction"] > 1e-3


def test_xarray_and_pandas(trajectory):
    ds = trajectory.to_xarray()
    assert ds["q"].dims == ("time", "quaternion")
    np.testing.assert_array_equal(ds["omega"].values, trajectory.omega)
    np.testing.assert_array_equal(ds["time"].values, trajectory.t)
    df = trajectory.to_pandas()
    assert df.shape == (21, 14)
    np.testing.assert_array_equal(df["omega_2"].to_numpy(), trajectory.omega[:, 1])
    np.testing.assert_array_equal(df.index.to_numpy(), trajectory.t)


@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_save_load_round_trip(trajectory, tmp_path, suffix):
    path = tmp_path / f"traj{suffix}"
    trajectory.save(path)
    back = kr.Trajectory.load(path)
    np.testing.assert_array_equal(back.t, trajectory.t)
    np.testing.assert_array_equal(back.q, trajectory.q)
    np.testing.assert_array_equal(back.omega, trajectory.omega)
    np.testing.assert_array_equal(back.inertia, trajectory.inertia)
    assert back.meta == trajectory.meta


def test_six_dof_and_batch_round_trips(tmp_path):
    body = kr.RigidBody([1.0, 2.0, 3.0], mass=2.0)
    tr = kr.simulate_6dof(body, np.linspace(0, 1, 5), [0.1, 1.0, 0.1], velocity0=[1, 0, 0],
                          force=ConstantForce([0, 0, -19.62]))
    for suffix in (".nc", ".csv", ".parquet"):
        tr.save(tmp_path / f"six{suffix}")
        back = kr.Trajectory.load(tmp_path / f"six{suffix}")
        np.testing.assert_array_equal(back.position, tr.position)
        np.testing.assert_array_equal(back.velocity, tr.velocity)
    batch = kr.simulate_batch(np.array([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]]), np.linspace(0, 1, 4), [0.1, 1.0, 0.1])
    batch.save(tmp_path / "batch.nc")
    back = kr.Trajectory.load(tmp_path / "batch.nc")
    np.testing.assert_array_equal(back.omega, batch.omega)
    np.testing.assert_array_equal(back.inertia, batch.inertia)
    assert batch.to_pandas().index.names == ["body", "t"]
    with pytest.raises(ValueError, match="CSV holds one body"):
        batch.save(tmp_path / "batch.csv")
    with pytest.raises(ValueError, match="Parquet holds one body"):
        batch.save(tmp_path / "batch.parquet")
    with pytest.raises(ValueError, match="must end in one of .nc, .csv, .parquet"):
        batch.save(tmp_path / "batch.h5")


def test_files_written_before_the_formats_had_one_owner_still_load(tmp_path, trajectory):
    """Parquet headers used to name no extra arrays; NetCDF from Trajectory.save had no CF labels."""
    import json

    frame = trajectory.to_pandas()
    frame.attrs["kreisel"] = json.dumps({"inertia": trajectory.inertia.tolist(), "meta": trajectory.meta})
    frame.to_parquet(tmp_path / "old.parquet")
    trajectory.to_xarray().to_netcdf(tmp_path / "old.nc", engine="scipy")
    for name in ("old.parquet", "old.nc"):
        back = kr.Trajectory.load(tmp_path / name)
        np.testing.assert_array_equal(back.q, trajectory.q)
        np.testing.assert_array_equal(back.inertia, trajectory.inertia)
    trajectory.save(tmp_path / "new.nc")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.nc", "old.nc", "old.parquet"]  # written atomically


def test_a_truncated_csv_file_is_refused_not_read_with_nan(tmp_path, trajectory):
    path = tmp_path / "traj.csv"
    trajectory.save(path)
    text = path.read_bytes()
    rows = text.splitlines(keepends=True)
    path.write_bytes(text[:len(text) - len(rows[-1]) + 12])  # within the last row's quaternion
    with pytest.raises(ValueError, match="ends within a row"):
        kr.Trajectory.load(path)
    path.write_bytes(b"".join(rows[:-3]))  # whole rows lost
    with pytest.raises(ValueError, match="holds 18 of the 21 rows"):
        kr.Trajectory.load(path)
    with pytest.raises(kr.io.ResultError, match=r"traj\.csv: holds 18 of the 21 rows .*truncated"):
        kr.io.load_trajectory(path)


def _edited(tmp_path, trajectory, line, edit):
    """A saved CSV trajectory with line ``line`` (1-based; 0: the sidecar's JSON) passed through ``edit``."""
    path = tmp_path / "traj.csv"
    trajectory.save(path)
    if line == 0:
        side = tmp_path / "traj.csv.json"
        side.write_text(edit(side.read_text(encoding="utf-8").strip()), encoding="utf-8")
        return path
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[line - 1] = edit(lines[line - 1])
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _cell(index, value):
    return lambda line: ",".join(value if i == index else cell for i, cell in enumerate(line.split(",")))


@pytest.mark.parametrize(("line", "edit", "match"), [
    (5, _cell(1, "0.5"), r"traj.csv: columns q0..q3, line 5: quaternion of length 0.7\d+, not a unit quaternion"),
    (5, _cell(6, "abc"), r"traj.csv: column 'omega_2', line 5: not a number: 'abc'"),
    (7, _cell(0, "x"), r"traj.csv: column 't', line 7: not a number: 'x'"),
    (7, _cell(5, "0.25"), r"traj.csv: the data do not match the SHA-256 checksum in traj.csv.json"),
    (0, lambda line: line[:-3], r"traj.csv.json: the kreisel header is not valid JSON"),
    (0, lambda line: line.replace("[[1.0, 0.0, 0.0]", "[[1.0, 0.5, 0.0]"), r"traj.csv.json: header: inertia must be symmetric"),
    (0, lambda line: line.replace("[[1.0, 0.0, 0.0]", "[[-1.0, 0.0, 0.0]"), r"traj.csv.json: header: inertia: principal moments"),
])
def test_a_hand_edited_csv_file_is_refused_naming_file_column_and_line(tmp_path, trajectory, line, edit, match):
    with pytest.raises(ValueError, match=match):
        kr.Trajectory.load(_edited(tmp_path, trajectory, line, edit))


def test_a_csv_file_saved_again_with_semicolons_is_refused_with_a_hint(tmp_path, trajectory):
    path = tmp_path / "traj.csv"
    trajectory.save(path)
    table = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join(row.replace(",", ";") for row in table) + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match=r"column\(s\) q0, q1, q2, q3 not found; .*another separator"):
        kr.Trajectory.load(path)


def test_what_a_trajectory_holds_still_loads_from_csv(tmp_path):
    # NaN samples, times in any order (an exact solution takes them so) and a body outside the triangle
    # inequalities (allow_unphysical) are what a Trajectory holds: they round-trip
    t = np.array([0.0, -1.0, 0.5])
    omega = np.array([[0.1, 1.0, 0.1], [np.nan, 1.0, 0.1], [0.1, 1.0, 0.1]])
    tr = kr.Trajectory(t, [[1.0, 0.0, 0.0, 0.0]] * 3, omega, [2.0, 1.0, 2.0 / 3.0])
    tr.save(tmp_path / "odd.csv")
    back = kr.Trajectory.load(tmp_path / "odd.csv")
    np.testing.assert_array_equal(back.t, t)
    np.testing.assert_array_equal(back.omega, omega)
    np.testing.assert_array_equal(back.inertia, tr.inertia)


def test_space_vectors_are_nan_only_at_nan_samples(trajectory, tmp_path):
    omega = trajectory.omega.copy()
    omega[5, 1] = np.nan
    tr = kr.Trajectory(trajectory.t, trajectory.q, omega, trajectory.inertia)
    R = Rotation.from_quat(trajectory.q, scalar_first=True)
    for got, body in ((tr.omega_space, omega), (tr.angular_momentum_space, omega * [1.0, 2.0, 3.0])):
        assert np.isnan(got[5]).all() and np.isfinite(np.delete(got, 5, axis=0)).all()
        np.testing.assert_allclose(np.delete(got, 5, axis=0), np.delete(R.apply(np.nan_to_num(body)), 5, axis=0),
                                   atol=1e-14)
    tr.save(tmp_path / "gap.nc")   # was "v must be finite (no NaN or inf)"
    np.testing.assert_array_equal(kr.Trajectory.load(tmp_path / "gap.nc").omega, omega)


def test_extra_arrays_may_not_hide_trajectory_attributes():
    args = ([0.0, 1.0], [[1, 0, 0, 0]] * 2, [[0, 0, 1]] * 2, [1, 2, 3])
    for name in ("euler", "energy", "drift", "omega_space"):
        with pytest.raises(ValueError, match=f"extra array '{name}' would hide"):
            kr.Trajectory(*args, **{name: [[0.0] * 3] * 2})


def test_a_trajectory_slices_by_sample_and_by_time(trajectory):
    part = trajectory[10:20]
    assert isinstance(part, kr.Trajectory) and len(part) == 10 and part.meta == trajectory.meta
    np.testing.assert_array_equal(part.t, trajectory.t[10:20])
    np.testing.assert_array_equal(part.q, trajectory.q[10:20])
    np.testing.assert_array_equal(part.omega_space, trajectory.omega_space[10:20])
    np.testing.assert_array_equal(trajectory[::5].t, trajectory.t[::5])
    np.testing.assert_array_equal(trajectory[[3, 1]].omega, trajectory.omega[[3, 1]])
    window = trajectory.between(2.5, 5.0)
    np.testing.assert_array_equal(window.t, [2.5, 3.0, 3.5, 4.0, 4.5, 5.0])
    np.testing.assert_array_equal(window.q, trajectory.q[5:11])
    with pytest.raises(TypeError, match=r"traj\[3:3 \+ 1\]"):
        trajectory[3]
    with pytest.raises(IndexError, match="picks no sample"):
        trajectory[30:]
    with pytest.raises(ValueError, match="no sample lies in"):
        trajectory.between(20.0, 30.0)
    with pytest.raises(ValueError, match="t0 must be at most t1"):
        trajectory.between(5.0, 2.0)
    with pytest.raises(ValueError, match="t1"):
        trajectory.between(0.0, np.nan)


def test_a_sliced_batch_keeps_its_bodies_and_extra_arrays():
    t = np.linspace(0.0, 1.0, 6)
    batch = kr.simulate_batch([[1.0, 2.0, 3.0], [2.0, 2.0, 3.0]], t, [0.1, 1.0, 0.2])
    part = batch[2:5]
    assert part.batch_shape == (2,) and part.q.shape == (2, 3, 4)
    np.testing.assert_array_equal(part.omega, batch.omega[:, 2:5])
    six = kr.Trajectory(t, [[1, 0, 0, 0]] * 6, [[0, 0, 1.0]] * 6, [1, 2, 3], position=np.arange(18.0).reshape(6, 3),
                        angle=np.arange(6.0))
    np.testing.assert_array_equal(six[1:3].position, [[3, 4, 5], [6, 7, 8]])
    np.testing.assert_array_equal(six[1:3].angle, [1.0, 2.0])


def test_rotation_is_the_attitude_as_a_rotation(trajectory):
    r = trajectory.rotation
    assert isinstance(r, kr.Rotation) and len(r) == len(trajectory)
    ref = Rotation.from_quat(trajectory.q, scalar_first=True)
    np.testing.assert_allclose(r.apply(trajectory.omega), ref.apply(trajectory.omega), rtol=0, atol=1e-15)
    np.testing.assert_allclose(r.as_matrix(), ref.as_matrix(), rtol=0, atol=1e-15)
