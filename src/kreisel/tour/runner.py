"""Run the tour's sections with a progress bar and write the report."""

from __future__ import annotations

import pathlib
import time
import traceback

from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from .._fileio import atomic_output
from . import earth_frame, free_top, heavy_top, imu_attitude, integrators, kinematics, navigation, phone_lab, rotations
from ._fonts import cjk_family
from .i18n import check_language
from .report import NO_CJK_FONT, Section, render_html

__all__ = ["run_tour", "SECTIONS"]

# in the order of the chapter: §2, §3 (with its navigation remarks), §4, §5, §6, §7, §8
SECTIONS = (
    *rotations.SECTIONS,
    *kinematics.SECTIONS,
    *navigation.SECTIONS,
    *imu_attitude.SECTIONS,
    free_top.inertia_ellipsoid,
    *integrators.SECTIONS,
    free_top.tennis_racket,
    *phone_lab.SECTIONS,
    free_top.poinsot_construction,
    free_top.symmetric_top_cones,
    *heavy_top.SECTIONS,
    *earth_frame.SECTIONS,
)


def _run_one(function, quick):
    start = time.perf_counter()
    try:
        section = function(quick)
    except Exception as exc:  # a failing section is reported, the others still run
        doc = (function.__doc__ or function.__name__).strip().splitlines()[0]
        section = Section(doc, "?", "", [], error=f"{type(exc).__name__}: {exc}\n{traceback.format_exc(limit=3)}")
    section.seconds = time.perf_counter() - start
    return section


def run_tour(out_dir="tour", quick=False, console=None, lang="en"):
    """Run every section, write ``out_dir/index.html``, print a summary; True if all pass.

    Parameters
    ----------
    out_dir : str or os.PathLike
        Created if missing; ``index.html`` inside it is replaced atomically.
    quick : bool
        Smaller problems with the same checks.
    console : rich.console.Console, optional
        Where the progress bar and summary go (default: standard output).
    lang : {"en", "zh"}
        The language of the report (prose, tables, captions, figure text); the summary printed stays English.
    """
    check_language(lang)
    console = console or Console()
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    sections = []
    columns = (TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
               TimeElapsedColumn())
    with Progress(*columns, console=console, transient=True) as progress:
        task = progress.add_task("tour", total=len(SECTIONS))
        for function in SECTIONS:
            progress.update(task, description=f"tour: {function.__name__.replace('_', ' ')}")
            sections.append(_run_one(function, quick))
            progress.advance(task)
    index = out_dir / "index.html"
    with atomic_output(index) as tmp:
        tmp.write_text(render_html(sections, lang=lang), encoding="utf-8")
    table = Table(title="kreisel tour")
    for name in ("section", "theory", "checks", "time"):
        table.add_column(name)
    for s in sections:
        mark = "[green]pass[/]" if s.ok else "[red]FAIL[/]"
        table.add_row(escape(s.title), escape(s.seed), f"{mark} {sum(c.ok for c in s.checks)}/{len(s.checks)}",
                      f"{s.seconds:.1f} s")
    console.print(table)
    for s in sections:
        for c in s.checks:
            if not c.ok:
                console.print("[red]✗[/] " + escape(f"{s.title}: {c.label} = {c.value} (expected {c.expected})"))
        if s.error:
            console.print("[red]✗[/] " + escape(f"{s.title}: {s.error}"))
    if lang != "en" and cjk_family() is None:
        console.print(escape(f"note: {NO_CJK_FONT}"))
    console.print(escape(f"report: {index}"))
    return all(s.ok for s in sections)
