"""Shared fixtures for the so3 tests: a seeded generator and uniform random rotations."""

import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(20240611)


@pytest.fixture
def random_quats(rng):
    """Factory of uniform unit quaternions (normalised Gaussians), scalar first."""

    def make(n):
        q = rng.normal(size=(n, 4))
        return q / np.linalg.norm(q, axis=-1, keepdims=True)

    return make
