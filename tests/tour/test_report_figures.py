"""Every figure of the tour report has labelled axes, and its tables hold words and numbers, not Python reprs."""

import html
import re


from kreisel.tour.report import render_html


def _labelled(ax, axis):
    """The axis has a label, or shares that axis with a panel that shows it (stacked panels)."""
    siblings = (ax.get_shared_x_axes() if axis == "x" else ax.get_shared_y_axes()).get_siblings(ax)
    return any(getattr(other, f"get_{axis}label")().strip() for other in siblings)


def test_every_axis_of_every_figure_is_labelled(sections):
    missing = []
    for section in sections:
        assert section.figures, section.title
        for number, (fig, _) in enumerate(section.figures):
            for ax in fig.axes:
                names = ("x", "y", "z") if ax.name == "3d" else ("x", "y")
                for axis in names:
                    label = ax.get_zlabel() if axis == "z" else None
                    if not (label.strip() if axis == "z" else _labelled(ax, axis)):
                        missing.append(f"{section.title}, figure {number + 1}, {ax.get_title()!r}: {axis} axis")
    assert not missing, "\n".join(missing)


def test_titles_fit_inside_their_figures(sections):
    for section in sections:
        for fig, _ in section.figures:
            fig.canvas.draw()
            width = fig.bbox.width
            for ax in fig.axes:
                box = ax.title.get_window_extent()
                assert box.x0 >= -1 and box.x1 <= width + 1, (section.title, ax.get_title())


def _overlapping_tick_labels(fig):
    """Pairs of neighbouring tick labels of one axis of a 2D panel whose drawn boxes overlap."""
    fig.draw_without_rendering()   # lays out the ticks and formats their labels
    pairs = []
    for ax in fig.axes:
        if ax.name == "3d":
            continue
        for axis in (ax.xaxis, ax.yaxis):
            labels = [label for label in axis.get_ticklabels(which="both") if label.get_visible() and label.get_text()]
            boxes = sorted(((label.get_window_extent(), label.get_text()) for label in labels),
                           key=lambda box: (box[0].x0, box[0].y0))
            for (a, text_a), (b, text_b) in zip(boxes, boxes[1:]):
                if a.overlaps(b):
                    pairs.append((ax.get_title(), text_a, text_b))
    return pairs


def test_tick_labels_do_not_overlap(sections):
    overlapping = [(section.title, *pair) for section in sections for fig, _ in section.figures
                   for pair in _overlapping_tick_labels(fig)]
    assert not overlapping, overlapping


def test_report_tables_hold_no_python_reprs(sections):
    page = render_html(sections)
    cells = [html.unescape(cell) for cell in re.findall(r"<td>(.*?)</td>", page)]
    assert cells
    repr_like = re.compile(r"^\(.*, .*\)$|^\[.*\]$|^'.*'$|', '|\bTrue\b|\bFalse\b|\bNone\b|array\(")
    offending = [cell for cell in cells if "<" not in cell and repr_like.search(cell)]
    assert not offending, offending
