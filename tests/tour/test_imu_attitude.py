"""The tour's real-IMU section: kreisel's estimators on the bundled BROAD trial against motion capture."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import kreisel as kr
from kreisel.tour import SECTIONS
from kreisel.tour.imu_attitude import TOTAL_BOUND, angle_between, imu_attitude, rotation_angle
from kreisel.tour.navigation import coning_drift


@pytest.fixture(scope="module")
def section():
    return imu_attitude(True)


def test_section_passes_with_its_figures_and_cites_theory_3(section):
    assert section.ok, [(c.label, c.value, c.expected) for c in section.checks if not c.ok]
    assert section.title == "Attitude from a real IMU against motion capture" and section.seed == "§3.3, §3.5"
    assert len(section.checks) == 8 and len(section.figures) == 2
    # it follows the strapdown section of the chapter
    assert SECTIONS.index(imu_attitude) == SECTIONS.index(coning_drift) + 1


def test_numbers_in_the_prose_are_the_estimators_errors(section):
    rec = kr.io.read_imu(kr.io.recording_path("broad_07"))
    rate = (rec.t.size - 1) / (rec.t[-1] - rec.t[0])
    assert rate == pytest.approx(285.714, rel=1e-5)
    for kwargs in ({}, {"method": "madgwick"}, {"method": "mahony"}, {"offline": True}):
        est = kr.nav.estimate_attitude(rec.omega, rec.accel, rec.mag, rate=rate, **kwargs)
        assert f"{kr.nav.attitude_error(est.q, rec.reference, rec.movement)[0]:.2f}°" in section.text
    causal = next(c for c in section.checks if c.label.startswith("kreisel, causal"))
    # the bound leaves a margin over the measured error, and the error is not trivially small either
    assert 0.5 * TOTAL_BOUND < causal.value < 0.9 * TOTAL_BOUND


def test_rotation_angle_and_angle_between_against_scipy():
    rng = np.random.default_rng(7)
    rotations = Rotation.random(200, random_state=rng)
    small = Rotation.from_rotvec(rng.normal(size=(50, 3)) * 1e-9)
    near_half_turn = Rotation.from_rotvec(np.outer(np.pi - 1e-6 * rng.random(50), [0.0, 0.6, 0.8]))
    for r in (rotations, small, near_half_turn):
        np.testing.assert_allclose(rotation_angle(r.as_matrix()), r.magnitude(), rtol=1e-9, atol=1e-15)
    u, v = rng.normal(size=(2, 100, 3))
    expected = np.arccos(np.sum(u * v, axis=1) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1))
    np.testing.assert_allclose(angle_between(u, v), expected, rtol=1e-10)
    assert angle_between(np.array([1.0, 0.0, 0.0]), np.array([1.0, 1e-12, 0.0])) == pytest.approx(1e-12, rel=1e-12)
