"""The code on the getting-started, coming-from and user-guide pages runs, and its claims hold."""

import re

import numpy as np
import pytest

from .conftest import DOCS


def _python_blocks(page):
    text = (DOCS / page).read_text(encoding="utf-8")
    blocks = re.findall(r"\.\. code-block:: python\n\n((?:   .*\n|\n)+)", text)
    return ["\n".join(line[3:] for line in block.splitlines()) for block in blocks]


@pytest.mark.parametrize("page", ["getting_started.rst", "coming_from.rst"])
def test_python_examples_run(page):
    blocks = _python_blocks(page)
    assert blocks
    namespace = {}
    for block in blocks:
        exec(compile(block, page, "exec"), namespace)


USER_GUIDE_WITH_CODE = sorted(path.name for path in (DOCS / "user_guide").glob("*.rst")
                              if ".. code-block:: python" in path.read_text(encoding="utf-8"))


@pytest.mark.parametrize("page", USER_GUIDE_WITH_CODE)
def test_user_guide_page_runs_on_its_own(page, tmp_path, monkeypatch):
    """A reader who lands on one page can paste its code into a fresh session."""
    monkeypatch.chdir(tmp_path)  # pages save figures such as fit.png where the reader works
    namespace = {}
    for block in _python_blocks(f"user_guide/{page}"):
        exec(compile(block, page, "exec"), namespace)


def test_user_guide_kovalevskaya_keeps_its_integral():
    namespace = {}
    for block in _python_blocks("user_guide/07_kovalevskaya.rst"):
        exec(compile(block, "07_kovalevskaya.rst", "exec"), namespace)
    k = namespace["top"].integrals(namespace["traj"].omega, namespace["traj"].gamma).kovalevskaya
    assert k.shape == namespace["t"].shape
    assert np.ptp(k) < 1e-8 * np.max(np.abs(k))


def test_getting_started_results_are_the_ones_stated():
    namespace = {}
    for block in _python_blocks("getting_started.rst"):
        exec(compile(block, "getting_started.rst", "exec"), namespace)
    assert namespace["top"].regime([0.01, 1.0, 0.01]) == "about_largest_axis"
    assert namespace["heavy"].apex_locus_kind(namespace["euler0"], namespace["rates0"]) == "cusp"
    assert abs(namespace["num"].q - namespace["traj"].q).max() < 1e-6
    assert max(namespace["traj"].drift().values()) < 1e-13


def test_coming_from_scipy_translation_agrees_with_scipy():
    namespace = {}
    for block in _python_blocks("coming_from.rst"):
        exec(compile(block, "coming_from.rst", "exec"), namespace)
    import numpy as np
    from scipy.spatial.transform import Rotation

    scipy_rotation = Rotation.from_euler("ZXZ", [30, 45, 60], degrees=True)
    assert np.allclose(namespace["q_wxyz"], np.roll(scipy_rotation.as_quat(), 1))
    assert np.allclose(namespace["v"], scipy_rotation.apply([1.0, 0.0, 0.0]))


def test_coming_from_gimbal_lock_splits_are_the_ones_stated():
    import warnings

    import numpy as np
    from scipy.spatial.transform import Rotation

    import kreisel as kr

    def both(seq, angles):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # scipy's "Gimbal lock detected"
            theirs = Rotation.from_euler(seq, angles).as_euler(seq)
        return kr.Rotation.from_euler(seq, angles).as_euler(seq), theirs

    ours, theirs = both("ZXZ", [0.3, 0.0, 0.7])  # exactly singular, intrinsic: the same split
    np.testing.assert_allclose(ours, [1.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(theirs, [1.0, 0.0, 0.0], atol=1e-15)
    ours, theirs = both("zxz", [0.3, 0.0, 0.7])  # extrinsic: kreisel zeroes the first angle, scipy the third
    np.testing.assert_allclose(ours, [0.0, 0.0, 1.0], atol=1e-15)
    np.testing.assert_allclose(theirs, [1.0, 0.0, 0.0], atol=1e-15)
    ours, theirs = both("ZXZ", [0.3, np.pi, 0.7])  # cos(pi/2) is 6e-17, singular to rounding: the same split
    np.testing.assert_allclose(ours, [-0.4, np.pi, 0.0], atol=1e-15)
    np.testing.assert_allclose(theirs, [-0.4, np.pi, 0.0], atol=1e-15)
    ours, theirs = both("ZXZ", [0.3, np.pi - 1e-8, 0.7])  # near lock: kreisel keeps its split, scipy zeroes
    np.testing.assert_allclose(ours, [0.3, np.pi - 1e-8, 0.7], atol=1e-7)  # the split is known to eps / 1e-8
    np.testing.assert_allclose(theirs, [-0.4, np.pi - 1e-8, 0.0], atol=1e-7)
    # scipy moves the rotation by about the distance to lock: its split is the rotation to 1e-8 rad only
    assert kr.Rotation.from_euler("ZXZ", ours).approx_equal(kr.Rotation.from_euler("ZXZ", theirs), atol=1e-7)
