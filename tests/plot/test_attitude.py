"""The attitude figure: angles against time, and with a reference its angles and the errors."""

import numpy as np

import kreisel as kr
from kreisel.plot import attitude_estimate


def test_reference_adds_the_error_panel_and_tolerates_lost_tracking():
    t = np.linspace(0.0, 2.0, 200)
    q = np.column_stack([np.cos(t / 2), 0 * t, 0 * t, np.sin(t / 2)])
    reference = q.copy()
    reference[50:60] = np.nan
    alone = attitude_estimate(t, q)
    assert len(alone.axes) == 1
    fig = attitude_estimate(t, q, reference, mask=t > 0.5)
    top, bottom = fig.axes
    yaw = top.get_lines()[0].get_ydata()
    np.testing.assert_allclose(yaw, np.degrees(t), atol=1e-12)
    total = bottom.get_lines()[0].get_ydata()
    assert np.isnan(total[50:60]).all() and np.allclose(np.delete(total, np.s_[50:60]), 0.0, atol=1e-12)
    # a pure yaw error is heading only, drawn as such
    turned = kr.quat_multiply([np.cos(0.05), 0.0, 0.0, np.sin(0.05)], q)
    heading = attitude_estimate(t, turned, q).axes[1].get_lines()[1].get_ydata()
    np.testing.assert_allclose(heading, np.degrees(0.1), rtol=1e-12)
