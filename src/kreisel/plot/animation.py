"""Animation of a rigid body's motion: the body, its principal axes, ω and J."""

from __future__ import annotations

import pathlib
import shutil

import numpy as np
from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter
from matplotlib.figure import Figure

from .._fileio import atomic_output
from ..so3 import quat_apply

__all__ = ["box_half_extents", "animate"]

# unit-cube edges as pairs of corner indices (corners are the 8 sign patterns)
_CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
_EDGES = [(i, j) for i in range(8) for j in range(i + 1, 8) if np.sum(_CORNERS[i] != _CORNERS[j]) == 1]


def box_half_extents(moments):
    """Half edge lengths of the uniform box with principal moments ``moments`` (unit mass).

    I1 = (b² + c²)/12 and cyclic, so a² = 6 (I2 + I3 − I1) etc.; scaled so the
    longest half edge is 1. Bodies violating the triangle inequality get a
    minimal thickness instead of an imaginary edge.
    """
    moments = np.asarray(moments, dtype=float)
    squares = 6.0 * (moments.sum() - 2.0 * moments)
    half = np.sqrt(np.maximum(squares, 1e-3 * squares.max())) / 2
    return half / half.max()


def animate(traj, path, frames=120, fps=24):
    """Write an animation of ``traj`` to ``path`` (.gif with Pillow, .mp4 with ffmpeg).

    The body is drawn as the uniform box with the trajectory's principal
    moments, with its principal axes; ω (red) and J (black) are scaled to unit
    length at the start. The file is written atomically; an existing one is
    replaced.
    """
    path = pathlib.Path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ValueError(f"path must end in .gif or .mp4, got {path.name!r}")
    if suffix == ".mp4" and shutil.which("ffmpeg") is None:
        raise ValueError("writing .mp4 needs ffmpeg on PATH; write a .gif instead")
    if traj.batch_shape:
        raise ValueError("animate draws one body; select one from the batch first")
    index = np.linspace(0, len(traj) - 1, min(frames, len(traj))).round().astype(int)
    q = traj.q[index]
    half = box_half_extents(np.diagonal(traj.inertia))
    corners = _CORNERS * half
    w = traj.omega_space[index]
    j = traj.angular_momentum_space[index]
    w_scale = 1.0 / max(np.linalg.norm(w, axis=-1).max(), 1e-300)
    j_scale = 1.0 / max(np.linalg.norm(j, axis=-1).max(), 1e-300)

    fig = Figure(figsize=(5, 5), layout="constrained")
    ax = fig.add_subplot(projection="3d")
    ax.set(xlim=(-1.2, 1.2), ylim=(-1.2, 1.2), zlim=(-1.2, 1.2), xlabel="x", ylabel="y", zlabel="z")
    ax.set_box_aspect((1, 1, 1))
    edge_lines = [ax.plot([], [], [], color="0.3", linewidth=1)[0] for _ in _EDGES]
    axis_lines = [ax.plot([], [], [], color=f"C{k}", linewidth=2)[0] for k in range(3)]
    omega_line = ax.plot([], [], [], color="red", linewidth=2.5, label="ω")[0]
    momentum_line = ax.plot([], [], [], color="black", linewidth=2.5, label="J")[0]
    ax.legend(loc="upper left")
    title = ax.set_title("")

    def draw(k):
        turned = quat_apply(q[k], corners)
        for line, (a, b) in zip(edge_lines, _EDGES):
            line.set_data_3d(*np.c_[turned[a], turned[b]])
        axes = quat_apply(q[k], np.diag(half) * 1.2)
        for line, axis in zip(axis_lines, axes):
            line.set_data_3d(*np.c_[np.zeros(3), axis])
        omega_line.set_data_3d(*np.c_[np.zeros(3), w[k] * w_scale])
        momentum_line.set_data_3d(*np.c_[np.zeros(3), j[k] * j_scale])
        title.set_text(f"t = {traj.t[index[k]]:.2f} s")
        return [*edge_lines, *axis_lines, omega_line, momentum_line, title]

    writer = PillowWriter(fps=fps) if suffix == ".gif" else FFMpegWriter(fps=fps)
    with atomic_output(path) as tmp:
        # made only once the file can be written: an animation dropped unsaved warns when collected
        FuncAnimation(fig, draw, frames=len(index), blit=False).save(tmp, writer=writer)
    return path
