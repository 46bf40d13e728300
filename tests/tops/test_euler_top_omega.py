"""EulerTop.omega: the body angular velocity alone equals what solve returns, for every kind of motion."""

import numpy as np
import pytest

import kreisel as kr


@pytest.mark.parametrize(
    "moments, omega0",
    [
        ((1.0, 2.0, 3.0), (0.3, 1.0, 0.2)),      # about the largest axis
        ((1.0, 2.0, 3.0), (1.0, 0.3, 0.1)),      # about the smallest axis
        ((3.0, 1.0, 2.5), (-0.4, 2.0, 0.7)),     # unsorted moments
        ((3.0, 4.0, 6.0), (2.0, 0.3, 1.0)),      # separatrix
        ((1.0, 1.0, 3.0), (1.0, 0.0, 0.5)),      # symmetric
        ((2.0, 2.0, 2.0), (1.0, -1.0, 0.5)),     # spherical
        ((1.0, 2.0, 3.0), (0.0, 0.0, 2.0)),      # steady about a principal axis
    ],
)
def test_omega_matches_solve(moments, omega0):
    top = kr.EulerTop(*moments, allow_unphysical=True)  # (1, 1, 3) is a textbook symmetric body
    t = np.linspace(-3.0, 7.0, 41)
    np.testing.assert_allclose(top.omega(t, omega0), top.solve(t, omega0).omega, rtol=0, atol=1e-13)


def test_omega_refuses_bad_shapes():
    top = kr.EulerTop(1.0, 2.0, 3.0)
    with pytest.raises(ValueError, match="t must be one-dimensional"):
        top.omega(np.zeros((2, 2)), [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match=r"omega0 must have shape \(3,\)"):
        top.omega([0.0, 1.0], np.ones((2, 3)))
