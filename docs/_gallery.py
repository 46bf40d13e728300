"""sphinx-gallery helpers: a scraper for the matplotlib Figure objects that kreisel.plot returns.

kreisel.plot builds figures with matplotlib's object-oriented API, outside pyplot, so
sphinx-gallery's own matplotlib scraper does not see them.
"""

import os


def figure_scraper(block, block_vars, gallery_conf):
    """Save every new ``matplotlib.figure.Figure`` bound in the example's globals."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    if os.path.basename(block_vars["src_file"]).startswith("tour_"):
        return ""  # a tour notebook's section shows its figures in the HTML of its Section
    seen = gallery_conf.setdefault("_kreisel_seen_figures", {}).setdefault(block_vars["src_file"], set())
    paths = []
    for value in list(block_vars["example_globals"].values()):
        if isinstance(value, Figure) and value.canvas.manager is None and id(value) not in seen:
            seen.add(id(value))
            path = next(block_vars["image_path_iterator"])
            value.savefig(path, dpi=100)
            paths.append(path)
    return figure_rst(paths, gallery_conf["src_dir"])
