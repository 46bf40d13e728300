"""The command-line reference, generated from the typer application itself.

Every command of :data:`kreisel.cli.app.app` is rendered with its help text,
usage line, arguments and options (names, type, default, help) as click sees
them, followed by worked examples from :data:`EXAMPLES` below; tests/docs/
checks that every command has examples and that they use only options the
command has.
"""

from __future__ import annotations

import pathlib
import typing

# Examples per command: (command line after "kreisel", what it does).
EXAMPLES = {
    "convert": [
        ("convert --from euler:ZXZ --to quat 30 45 60 --degrees", "mechanics Euler angles to a scalar-first quaternion"),
        ("convert --from quat --to matrix 0.9238795 0 0 0.3826834", "a quaternion to its row-major matrix"),
        ("convert --from rotvec --to euler:xyz -i rotvecs.txt", "a file of rotation vectors, one per line"),
    ],
    "simulate": [
        ("simulate tennis_racket", "run a bundled scenario and print its first integrals"),
        ("simulate my_top.toml -o traj.nc", "run a scenario file and save the trajectory (netCDF)"),
        ("simulate my_top.toml -o traj.nc --force", "run it again, replacing the saved trajectory"),
    ],
    "plot": [("plot traj.nc --kind polhode -o polhode.png", "the polhode of a saved trajectory"),
             ("plot traj.nc --kind euler --seq zyx -o yaw_pitch_roll.png", "extrinsic z-y-x angles against time"),
             ("plot phone_toss -o rates.png", "a gyroscope recording's rates, to choose the window of a fit")],
    "animate": [("animate traj.nc -o top.mp4", "an animation of the body with its axes, ω and J")],
    "examples": [("examples", "list the bundled scenarios, gyroscope recordings and sweeps"),
                 ("examples lagrange_cusps --to scenarios/", "copy one out to edit")],
    "tour": [("tour --out tour", "every demonstration of the course, checked, in tour/index.html"),
             ("tour --quick --out /tmp/tour", "smaller, faster demonstrations"),
             ("tour --notebooks class", "the sections as Jupyter notebooks class/01_rotations.ipynb, ... for a course"),
             ("tour --lang zh --out tour-zh", "the report in Chinese: prose, tables, captions, figure text; the same numbers")],
    "sweep": [("sweep lagrange_apex --plot apex.png", "run a bundled sweep on a local Dask cluster and draw the map"),
              ("sweep my_sweep.toml --workers 2 -o map.zarr", "a sweep file; an interrupted run resumes")],
    "fit": [("fit phone_toss", "fit the free-top solution to the bundled gyroscope recording")],
    "attitude": [("attitude broad_07 -o attitude.csv --plot attitude.png",
                  "estimate the bundled BROAD trial's attitude, with its errors against motion capture"),
                 ("attitude imu.csv -o attitude.csv --method mahony --frame NED --force",
                  "Mahony's filter in north-east-down, replacing an earlier output"),
                 ("attitude table.csv -o attitude.csv --rate 100 --units deg/s --no-mag --offline",
                  "a table without a time column, gyro in deg/s, heading from the gyro alone, offline")],
    "compile": [("compile", "compile every kernel for this machine now, instead of on first use"),
                ("compile --only integrator", "only the integrators")],
    "serve": [("serve", "open the 3D viewer in the browser"),
              ("serve symmetric_top --no-browser --port 8000", "serve a scenario without opening a browser"),
              ("serve --recording broad_07", "replay the bundled BROAD trial: kreisel's attitude beside motion capture")],
}


def commands():
    """(name, click command) of every subcommand, in the order of the application."""
    import typer

    from kreisel.cli.app import app

    group = typer.main.get_command(app)
    return group, list(group.commands.items())


def _is_argument(param):
    return getattr(param, "is_flag", None) is None  # options know whether they are flags, arguments do not


_TYPES = {bool: "flag", str: "text", int: "integer", float: "number", pathlib.Path: "path"}


def _type_name(param):
    annotation = param.type_descriptor.annotation
    if typing.get_origin(annotation) in (list, typing.Union):
        inner = [a for a in typing.get_args(annotation) if a is not type(None)]
        prefix = "repeatable " if typing.get_origin(annotation) is list and not _is_argument(param) else ""
        return prefix + _TYPES.get(inner[0], getattr(inner[0], "__name__", str(inner[0])))
    return _TYPES.get(annotation, getattr(annotation, "__name__", str(annotation)))


def _escape(text):
    return text.replace("*", r"\*").replace("|", r"\|").replace("`", "``") if text else ""


def _default(param):
    if param.required:
        return "*required*"
    default = param.default
    if default is None or default is False or default == () or callable(default):
        return "—"
    return f"``{default}``"


def _parameter_rows(command):
    rows = []
    for param in command.params:
        if param.name == "help":
            continue
        if _is_argument(param):
            name = f"``{param.name.upper()}``"
            text = getattr(param, "help", "") or ""
        else:
            name = ", ".join(f"``{opt}``" for opt in param.opts + param.secondary_opts)
            text = param.help or ""
        if getattr(param, "nargs", 1) == -1:
            name += " …"
        rows.append((name, _type_name(param), _default(param), _escape(text)))
    return rows


def cli_reference():
    """reStructuredText of every command, its parameters and examples."""
    group, subcommands = commands()
    lines = []
    for name, command in subcommands:
        title = f"kreisel {name}"
        lines += [title, "-" * len(title), ""]
        for paragraph in (command.help or "").strip().split("\n\n"):
            lines += [_escape(" ".join(paragraph.split())), ""]
        usage = " ".join(["[OPTIONS]"] + [(p.name.upper() if p.required else f"[{p.name.upper()}]")
                                          + (" ..." if p.nargs == -1 else "")
                                          for p in command.params if _is_argument(p)])
        lines += [".. code-block:: text", "", f"   kreisel {name} {usage}", ""]
        rows = _parameter_rows(command)
        if rows:
            lines += [".. list-table::", "   :header-rows: 1", "   :widths: 28 14 14 44", "",
                      "   * - argument or option", "     - type", "     - default", "     - meaning"]
            for row in rows:
                lines += [f"   * - {row[0]}"] + [f"     - {cell or '—'}" for cell in row[1:]]
            lines.append("")
        lines += ["Examples:", "", ".. code-block:: console", ""]
        for example, what in EXAMPLES.get(name, []):
            lines += [f"   $ kreisel {example}    # {what}"]
        lines.append("")
    return "\n".join(lines) + "\n"
