"""Rich display in notebooks: every summary is well-formed, escaped HTML with the key numbers."""

from html.parser import HTMLParser

import numpy as np
import pytest

import kreisel as kr
from kreisel._html import html_table, number

VOID = {"br", "hr", "img", "meta", "input"}


class _Checker(HTMLParser):
    """Collects the text and fails on a closing tag that does not match the open one."""

    def __init__(self):
        super().__init__()
        self.stack, self.text = [], []

    def handle_starttag(self, tag, attrs):
        if tag not in VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):
        assert self.stack and self.stack[-1] == tag, f"</{tag}> closes {self.stack[-1:]}"
        self.stack.pop()

    def handle_data(self, data):
        self.text.append(data)


def parse(markup):
    """The visible text of ``markup``, after checking that every tag is closed in order."""
    checker = _Checker()
    checker.feed(markup)
    checker.close()
    assert checker.stack == [], f"unclosed tags {checker.stack}"
    return " ".join(checker.text)


def test_table_escapes_every_text():
    markup = html_table("<b>", [("a<script>", "x & y"), ("n", np.float64(0.5))], note="</table>")
    text = parse(markup)
    assert "<script>" not in markup and "</table></table>" not in markup
    assert "a<script>" in text and "x & y" in text and "</table>" in text and "0.5" in text


def test_number_is_short_and_exact_enough():
    assert number([1.0, 2.5, 1 / 3], digits=3) == "[1, 2.5, 0.333]"
    assert number(np.float64(4.0)) == "4"


def _free_trajectory():
    t = np.linspace(0.0, 2.0, 201)
    return kr.EulerTop(1.0, 2.0, 3.0).solve(t, [0.1, 2.0, 0.1])


def test_trajectory_shows_first_integrals_and_meta():
    tr = _free_trajectory()
    tr.meta["note"] = "<i>mine</i>"
    text = parse(tr._repr_html_())
    assert "201" in text and "0 … 2 s" in text
    assert "[1, 2, 3] kg m²" in text                        # principal moments
    assert number(0.5 * (1 * 0.01 + 2 * 4 + 3 * 0.01)) in text   # T(t0) = ½ Σ I ω²
    assert "[0.1, 4, 0.3]" in text                          # J(t0) = I ω0, identity attitude
    assert "<i>mine</i>" in text and "scalar-first" in text
    assert len(repr(tr)) < 80


@pytest.mark.parametrize("array", ["q", "omega"])
def test_trajectory_with_nan_samples_shows_where_they_are(array):
    # Trajectory accepts non-finite samples; its summary must not fail on them (Jupyter would show a traceback)
    tr = _free_trajectory()
    values = getattr(tr, array).copy()
    values[150:, 0] = np.nan
    tr = kr.dynamics.Trajectory(tr.t, values if array == "q" else tr.q, values if array == "omega" else tr.omega,
                                tr.inertia)
    text = parse(tr._repr_html_())
    assert "non-finite samples 51 of 201, the first at t = 1.5 s" in text and "T(t0)" not in text


def test_batched_trajectory_shows_its_batch_shape():
    t = np.linspace(0.0, 1.0, 11)
    tr = kr.simulate_batch(np.array([[1.0, 2.0, 3.0]] * 2), t, [0.1, 1.0, 0.1])
    assert "(2,)" in parse(tr._repr_html_())


def test_rotation_single_and_batch():
    r = kr.Rotation.from_rotvec([0.0, 0.0, np.pi / 2])
    text = parse(r._repr_html_())
    assert number(np.sqrt(0.5)) in text and "90°" in text and "[90, 0, 0]°" in text
    batch = kr.Rotation.from_rotvec([[0.0, 0.0, 0.5], [0.0, 1.0, 0.0]])
    text = parse(batch._repr_html_())
    assert "(2,)" in text and f"{number(np.degrees(0.5))}° … {number(np.degrees(1.0))}°" in text
    assert len(repr(r)) < 80


def test_rigid_transform_shows_rotation_and_translation():
    tf = kr.RigidTransform.from_rotation_translation(kr.Rotation.from_rotvec([np.pi / 3, 0.0, 0.0]), [1.0, -2.0, 3.5])
    text = parse(tf._repr_html_())
    assert "60°" in text and "[1, -2, 3.5]" in text


def test_rigid_body_shows_mass_and_principal_moments():
    text = parse(kr.RigidBody.box(12.0, (1.0, 2.0, 3.0))._repr_html_())
    assert "12 kg" in text and "[5, 10, 13] kg m²" in text
    tilted = kr.RigidBody(np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 4.0]]))
    assert "[1, 3, 4] kg m²" in parse(tilted._repr_html_())


def test_tops_show_their_stability_numbers():
    assert "y" in parse(kr.EulerTop(1.0, 2.0, 3.0)._repr_html_()).split("intermediate moment)")[1][:3]
    assert "symmetric" in parse(kr.EulerTop(1.0, 1.0, 1.5)._repr_html_())
    lagrange = kr.LagrangeTop(1.0, 0.5, 1.0)
    assert "4 rad/s" in parse(lagrange._repr_html_())        # 2 √(I1 mgl) / I3
    assert repr(lagrange) == "LagrangeTop(I1=1, I3=0.5, mgl=1)"


def test_fit_shows_moments_regime_and_quality():
    t = np.linspace(0.0, 1.0, 300)
    fit = kr.fit_free_rotation(t, kr.EulerTop(0.2, 0.8, 1.0).omega(t, [0.5, 12.0, 0.3]))
    text = parse(fit._repr_html_())
    assert "[0.2, 0.8, 1]" in text and fit.regime in text and "True" in text
    assert fit.regime in repr(fit) and len(repr(fit)) < 120


@pytest.mark.parametrize("obj", [kr.Rotation.identity(), kr.RigidBody([1.0, 2.0, 3.0])])
def test_contract_objects_have_html(obj):
    assert parse(obj._repr_html_()).strip()
