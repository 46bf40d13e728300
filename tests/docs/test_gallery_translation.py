"""docs/_ext/gallery_translation.py: the gallery index shows each example's translated title and first paragraph."""

from docutils import nodes

from .conftest import load_extension

OPENING = '\n    <div class="sphx-glr-thumbcontainer" tooltip="{}">\n'
TITLE = '\n      <div class="sphx-glr-thumbnail-title">{}</div>\n    </div>\n'


def _index(*examples):
    """A gallery index's doctree as sphinx-gallery writes it, its links resolved: per example the thumbnail's opening
    with the first paragraph as tooltip, the link to the page, the title."""
    section = nodes.section()
    section += nodes.paragraph("", "", nodes.reference("", "a link in the gallery's text", internal=True,
                                                         refuri="../theory/index.html"))
    for name, title, summary in examples:
        section += nodes.raw("", OPENING.format(summary), format="html")
        section += nodes.paragraph("", "", nodes.reference("", title, internal=True, refuri=f"{name}.html"))
        section += nodes.raw("", TITLE.format(title), format="html")
    return section


def test_each_thumbnail_gets_the_title_and_first_paragraph_of_the_page_it_links_to():
    extension = load_extension("gallery_translation")
    doctree = _index(("plot_06_tennis_racket", "Tennis-racket theorem (Theory §5.4)", "The free (Euler) top ..."),
                     ("plot_07_poinsot", "Poinsot construction", "ρ = ω/√(2T) lies on ..."),
                     ("plot_99_new", "Not translated yet", "Nor its text"))
    titles = {"auto_examples/plot_06_tennis_racket": nodes.title("", "网球拍定理（理论 §5.4）"),
              "auto_examples/plot_07_poinsot": nodes.title("", "潘索构造 & 其他")}
    summaries = {"auto_examples/plot_06_tennis_racket": "自由（欧拉）陀螺 “I = (1, 2, 3)” ……",
                 "auto_examples/plot_07_poinsot": "ρ = ω/√(2T) 位于惯量椭球上"}
    extension.translate_thumbnails(doctree, "auto_examples/index", titles, summaries.get)
    raws = [raw.astext() for raw in doctree.findall(nodes.raw)]
    assert raws == [OPENING.format("自由（欧拉）陀螺 “I = (1, 2, 3)” ……"), TITLE.format("网球拍定理（理论 §5.4）"),
                    OPENING.format("ρ = ω/√(2T) 位于惯量椭球上"), TITLE.format("潘索构造 &amp; 其他"),
                    OPENING.format("Nor its text"), TITLE.format("Not translated yet")]


def test_a_tooltip_is_escaped_as_an_attribute():
    extension = load_extension("gallery_translation")
    doctree = _index(("plot_01", "Title", "English"))
    extension.translate_thumbnails(doctree, "auto_examples/index", {}, lambda target: 'the "ZXZ" sequence <R>')
    assert next(doctree.findall(nodes.raw)).astext() == OPENING.format("the &quot;ZXZ&quot; sequence &lt;R&gt;")
