"""Trajectory files damaged every way a copy or a disk damages them: one clear error naming the file, or the
very data that were saved; never other numbers, never a raw backend exception."""

import json

import numpy as np
import pytest

import kreisel as kr
from kreisel.dynamics._trajectory_files import TrajectoryFileError, checksum, sidecar


@pytest.fixture(scope="module")
def trajectory():
    t = np.linspace(0.0, 2.0, 41)
    return kr.EulerTop(1.0, 2.0, 3.0).solve(t, [0.3, 1.0, 0.2])


def _same(back, trajectory):
    return (np.array_equal(back.t, trajectory.t) and np.array_equal(back.q, trajectory.q)
            and np.array_equal(back.omega, trajectory.omega, equal_nan=True)
            and np.array_equal(back.inertia, trajectory.inertia)
            and back.meta == json.loads(json.dumps(trajectory.meta)))  # a tuple comes back a list


def _loads_the_same_or_refuses(path, trajectory):
    """'loaded' (the saved data exactly) or 'refused' (one error line naming the file); anything else fails."""
    try:
        back = kr.Trajectory.load(path)
    except TrajectoryFileError as exc:
        message = str(exc)
        assert "\n" not in message and (message.startswith(str(path)) or message.startswith(str(sidecar(path)))), message
        return "refused"
    assert _same(back, trajectory), f"{path.name} loaded other data"
    return "loaded"


def _positions(size, count):
    return sorted(set(np.linspace(0, size - 1, count).astype(int).tolist()) | {1, size - 1})


def _saved_bytes_and_a_copy_path(tmp_path, trajectory, name, suffix):
    """The bytes of ``trajectory`` saved as ``suffix``, and a path beside it (with the CSV's sidecar) to damage."""
    saved = tmp_path / f"saved{suffix}"
    trajectory.save(saved)
    path = tmp_path / f"{name}{suffix}"
    if suffix == ".csv":
        sidecar(path).write_bytes(sidecar(saved).read_bytes())
    return saved.read_bytes(), path


@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_every_truncation_is_refused_naming_the_file(tmp_path, trajectory, suffix):
    data, path = _saved_bytes_and_a_copy_path(tmp_path, trajectory, "cut", suffix)
    outcomes = []
    for end in _positions(len(data), 60) + [0]:
        path.write_bytes(data[:end])
        outcomes.append(_loads_the_same_or_refuses(path, trajectory))
    # only the last bytes may be padding that no reader needs
    assert outcomes.count("refused") >= len(outcomes) - 2, outcomes


@pytest.mark.parametrize("suffix", [".nc", ".csv", ".parquet"])
def test_a_single_damaged_byte_is_refused_or_harmless(tmp_path, trajectory, suffix):
    data, path = _saved_bytes_and_a_copy_path(tmp_path, trajectory, "bad", suffix)
    outcomes = []
    for at in _positions(len(data), 80):
        for change in (1, 0x40):
            damaged = bytearray(data)
            damaged[at] ^= change
            path.write_bytes(bytes(damaged))
            outcomes.append(_loads_the_same_or_refuses(path, trajectory))
    # the checksum refuses what still parses; bytes that no reader uses (padding, labels, statistics) may change
    assert outcomes.count("refused") > 0.3 * len(outcomes), outcomes.count("refused")


def test_csv_in_another_encoding_or_cut_after_its_header_is_one_clear_error(tmp_path, trajectory):
    path = tmp_path / "traj.csv"
    trajectory.save(path)
    text = path.read_text(encoding="utf-8")
    cases = {
        "UTF-16 text": text.encode("utf-16"),
        r"not UTF-8 text \(byte 7\)": text.encode()[:7] + b"\xff\xfe\x00" + text.encode()[7:],
        "holds no table": b"",
        "holds 0 of the 41 rows": text.splitlines(keepends=True)[0].encode(),
    }
    for expected, data in cases.items():
        path.write_bytes(data)
        with pytest.raises(TrajectoryFileError, match=rf"^{path}: .*{expected}"):
            kr.Trajectory.load(path)
        with pytest.raises(kr.io.ResultError, match=rf"^{path}: .*{expected}"):
            kr.io.load_trajectory(path)


def test_the_checksum_covers_data_meta_and_extra_arrays(trajectory):
    base = checksum(trajectory)
    assert checksum(kr.Trajectory(trajectory.t, trajectory.q, trajectory.omega, trajectory.inertia,
                                  meta=trajectory.meta)) == base
    q = trajectory.q.copy()
    q[3, 1] = np.nextafter(q[3, 1], 1.0)
    variants = [kr.Trajectory(trajectory.t, q, trajectory.omega, trajectory.inertia, meta=trajectory.meta),
                kr.Trajectory(trajectory.t, trajectory.q, trajectory.omega, trajectory.inertia, meta={"method": "x"}),
                kr.Trajectory(trajectory.t, trajectory.q, trajectory.omega, trajectory.inertia, meta=trajectory.meta,
                              angle=np.zeros(len(trajectory)))]
    assert len({base, *map(checksum, variants)}) == 4


def test_files_without_a_checksum_still_load(tmp_path, trajectory):
    """Files written before checksums: the old CSV layout (header in a comment line), NetCDF and Parquet."""
    header = {"inertia": trajectory.inertia.tolist(), "meta": trajectory.meta, "extra": [], "samples": 41}
    old = tmp_path / "old.csv"
    with open(old, "w", encoding="utf-8", newline="") as fh:
        fh.write("# kreisel-trajectory " + json.dumps(header) + "\n")
        trajectory.to_pandas().to_csv(fh, float_format="%.17g")
    frame = trajectory.to_pandas()
    frame.attrs["kreisel"] = json.dumps(header)
    frame.to_parquet(tmp_path / "old.parquet")
    trajectory.to_xarray().to_netcdf(tmp_path / "old.nc", engine="scipy")
    for name in ("old.csv", "old.parquet", "old.nc"):
        assert _same(kr.Trajectory.load(tmp_path / name), trajectory), name


def test_kreisel_csv_is_plain_csv_for_pandas_and_numpy(tmp_path, trajectory):
    import pandas as pd

    path = tmp_path / "traj.csv"
    trajectory.save(path)
    frame = pd.read_csv(path)
    assert frame.shape == (41, 15) and list(frame.columns[:5]) == ["t", "q0", "q1", "q2", "q3"]
    np.testing.assert_array_equal(frame[["q0", "q1", "q2", "q3"]].to_numpy(), trajectory.q)
    table = np.genfromtxt(path, delimiter=",", names=True)
    np.testing.assert_array_equal(table["t"], trajectory.t)
    np.testing.assert_array_equal(table["omega_2"], trajectory.omega[:, 1])
    meta = json.loads(sidecar(path).read_text(encoding="utf-8"))
    assert meta["csv"] == "traj.csv" and meta["samples"] == 41 and meta["sha256"] == checksum(trajectory)


def test_a_csv_without_its_sidecar_recovers_the_inertia_from_its_columns_or_says_what_is_missing(tmp_path,
                                                                                                  trajectory):
    # the viewer's download is the CSV alone; a tumbling body's ω′ spans the body axes, J′ = I ω′ gives I
    path = tmp_path / "traj.csv"
    trajectory.save(path)
    sidecar(path).unlink()
    with pytest.warns(UserWarning, match=r"traj\.csv without its sidecar traj\.csv\.json: inertia recovered"):
        back = kr.Trajectory.load(path)
    np.testing.assert_allclose(back.inertia, trajectory.inertia, rtol=0, atol=1e-13)
    np.testing.assert_array_equal(back.q, trajectory.q)
    assert back.meta["torque"] == "unknown"
    # a steady spin about a principal axis tells only one moment: refused, naming the missing sidecar
    spin = kr.Trajectory(trajectory.t, trajectory.q, np.tile([0.0, 0.0, 1.0], (41, 1)), [1.0, 2.0, 3.0])
    spin.save(path)
    sidecar(path).unlink()
    with pytest.raises(TrajectoryFileError, match=r"traj\.csv: its sidecar file traj\.csv\.json .* is missing.*"
                                                  r"does not turn through all three body axes"):
        kr.Trajectory.load(path)
    path.write_text("t,q0,q1,q2,q3\n0,1,0,0,0\n", encoding="utf-8")
    with pytest.raises(TrajectoryFileError, match=r"its sidecar file traj\.csv\.json .* is missing: keep the two"):
        kr.Trajectory.load(path)


def test_kreisel_simulate_csv_output_reads_as_plain_csv(tmp_path):
    import os
    import pathlib
    import subprocess
    import sys

    import pandas as pd

    src = pathlib.Path(kr.__file__).resolve().parents[1]
    process = subprocess.run([sys.executable, "-m", "kreisel", "simulate", "tennis_racket", "-o", "x.csv"],
                             cwd=tmp_path, capture_output=True, text=True, timeout=600,
                             env=dict(os.environ, PYTHONPATH=str(src)))
    assert process.returncode == 0, process.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.csv", "x.csv.json"]
    frame = pd.read_csv(tmp_path / "x.csv")
    table = np.genfromtxt(tmp_path / "x.csv", delimiter=",", names=True)
    back = kr.Trajectory.load(tmp_path / "x.csv")
    assert frame.shape == (2001, 15) and table.shape == (2001,)
    np.testing.assert_array_equal(frame["t"].to_numpy(), back.t)
    np.testing.assert_array_equal(table["q3"], back.q[:, 3])
    assert back.meta["scenario"] == "Tennis racket (Dzhanibekov) flips"
