"""docs/_ext/gallery_translation.py: the gallery index shows each example's translated title under its thumbnail."""

from docutils import nodes

from .conftest import load_extension

RAW_TITLE = '\n      <div class="sphx-glr-thumbnail-title">{}</div>\n    </div>\n'


def _index(*examples):
    """A gallery index's doctree as sphinx-gallery writes it, its links resolved: link, then raw title, per example."""
    section = nodes.section()
    for name, title in examples:
        section += nodes.raw("", '<div class="sphx-glr-thumbcontainer" tooltip="...">', format="html")
        section += nodes.paragraph("", "", nodes.reference("", title, internal=True, refuri=f"{name}.html"))
        section += nodes.raw("", RAW_TITLE.format(title), format="html")
    return section


def test_each_thumbnail_gets_the_title_of_the_page_it_links_to():
    extension = load_extension("gallery_translation")
    doctree = _index(("plot_06_tennis_racket", "Tennis-racket theorem (Theory §5.4)"),
                     ("plot_07_poinsot", "Poinsot construction & friends"), ("plot_99_new", "Not translated yet"))
    titles = {"auto_examples/plot_06_tennis_racket": nodes.title("", "网球拍定理（理论 §5.4）"),
              "auto_examples/plot_07_poinsot": nodes.title("", "潘索构造 & 其他")}
    extension.thumbnail_titles(doctree, "auto_examples/index", titles)
    raws = [raw.astext() for raw in doctree.findall(nodes.raw) if "thumbnail-title" in raw.astext()]
    assert raws == [RAW_TITLE.format("网球拍定理（理论 §5.4）"), RAW_TITLE.format("潘索构造 &amp; 其他"),
                    RAW_TITLE.format("Not translated yet")]
