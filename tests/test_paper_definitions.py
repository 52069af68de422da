"""A paper read as its definitions (issue 28): definitions bind names, identities are decided exactly,
conditions against the property their sentence claims; the forms people write assumptions in are
read as meant; a display over names no definition gives is undecided with them listed."""

from __future__ import annotations

import textwrap

import pytest

from hapticproof.audit.paperfile import loads
from hapticproof.audit.runner import audit_paper
from hapticproof.audit.source import draft, read_text


def _verdicts(text: str) -> dict[str, str]:
    return {r.id: r.verdict.value for r in audit_paper(loads(textwrap.dedent(text), "paper.toml").paper).results}


def _details(text: str) -> dict[str, str]:
    return {r.id: r.detail for r in audit_paper(loads(textwrap.dedent(text), "paper.toml").paper).results}


WALL = r"""
[paper]
id = "wall"
title = "A wall"
[symbols]
K = "nonnegative"
B = "nonnegative"
T = "positive"
b = "real"
[[equations]]
id = "1"
printed = 'H(z) = K + B\frac{z-1}{Tz}, \quad K \ge 0'
claim = "definition"
[[equations]]
id = "2"
printed = 'G^{-1}(z) = b + H(z)\frac{T}{z-1}'
claim = "definition"
[[equations]]
id = "3"
printed = 'G^{-1}(z) = b + \frac{KT}{z-1} + \frac{B}{z}'
claim = "identity"
[[equations]]
id = "4"
printed = '\operatorname{Re} G^{-1}(e^{j\omega T}) = b - \frac{KT}{2} + B\cos\omega T'
claim = "identity"
[[equations]]
id = "5"
printed = '\operatorname{Re} G^{-1}(e^{j\omega T}) = b - KT + B\cos\omega T'
claim = "identity"
[[equations]]
id = "6"
printed = 'b \ge \frac{KT}{2} + B'
claim = "condition"
about = "G^{-1}"
property = "positive-real"
strength = "iff"
[[equations]]
id = "7"
printed = 'b \ge KT + 2B'
claim = "condition"
about = "G^{-1}"
property = "positive-real"
strength = "iff"
[[equations]]
id = "8"
printed = 'b \ge \frac{KT}{4}'
claim = "condition"
about = "G^{-1}"
property = "positive-real"
strength = "sufficient"
"""


def test_definitions_identities_and_conditions_of_a_wall():
    verdicts = _verdicts(WALL)
    assert verdicts == {"1": "confirmed", "2": "confirmed", "3": "confirmed", "4": "confirmed", "5": "typo",
                        "6": "confirmed", "7": "typo", "8": "wrong"}
    # (7) is said "if and only if" but is only sufficient: a nearby display is exact (2b >= KT + 2B)
    assert "b -> 2b" in _details(WALL)["7"]


def test_a_trailing_assumption_is_no_side_of_the_equation():
    details = _details(WALL)
    assert "binds H" in details["1"]          # ', \quad K \ge 0' is an assumption, not a relation to check


def test_upright_and_plain_subscripts_are_one_name():
    verdicts = _verdicts(r"""
        [paper]
        id = "w"
        title = "w"
        [symbols]
        h = "positive"
        [[equations]]
        id = "1"
        printed = 'W(z) = K_{\mathrm{w}} + d_w\frac{z-1}{hz}'
        claim = "definition"
        [[equations]]
        id = "2"
        printed = '\operatorname{Re} W(e^{j\omega h}) = K_w + \frac{d_w}{h}(1 - \cos\omega h)'
        claim = "identity"
        """)
    assert verdicts == {"1": "confirmed", "2": "confirmed"}


def test_a_scene_may_refine_a_global_sign():
    verdicts = _verdicts(r"""
        [paper]
        id = "r"
        title = "refine"
        [symbols]
        B = "real"
        K = "positive"
        T = "positive"
        b = "positive"
        [scenes.wall]
        system = "single-user"
        [scenes.wall.params]
        B = "nonnegative"
        [[equations]]
        id = "1"
        printed = 'b > \frac{KT}{2} + B'
        claim = "passivity-condition"
        scene = "wall"
        """)
    assert verdicts == {"1": "confirmed"}
    with pytest.raises(Exception, match="contradicts"):
        loads(textwrap.dedent(r"""
            [paper]
            id = "r"
            title = "refine"
            [symbols]
            B = "positive"
            [scenes.wall]
            system = "single-user"
            [scenes.wall.params]
            B = "negative"
            [[equations]]
            id = "1"
            printed = 'b > B'
            claim = "passivity-condition"
            scene = "wall"
            """))


def test_greek_ranges_linear_relations_and_a_frequency_range_beside_a_display():
    verdicts = _verdicts(r"""
        [paper]
        id = "g"
        title = "greek"
        [symbols]
        alpha = "0 <= alpha < 1"
        g_0 = "g_0 + g_1 >= 0"
        g_1 = "real"
        h = "positive"
        c_d = "real"
        [[equations]]
        id = "1"
        printed = '\Gamma(z) = g_0 + g_1 z^{-1}'
        claim = "definition"
        [[equations]]
        id = "2"
        printed = 'G(z) = c_d + \Gamma(z)\, h\Bigl(\alpha + \frac{1}{z-1}\Bigr)'
        claim = "definition"
        [[equations]]
        id = "3"
        printed = '\operatorname{Re} G(e^{j\vartheta}) = c_d + h\Bigl(\alpha g_0 - \frac{g_0 + g_1}{2} - (1-\alpha) g_1\cos\vartheta\Bigr), \qquad 0 < \vartheta \le \pi'
        claim = "identity"
        [[equations]]
        id = "4"
        printed = 'c_d \ge h\Bigl(\frac{g_0 + g_1}{2} - \alpha g_0 + (1-\alpha)|g_1|\Bigr)'
        claim = "condition"
        about = "G"
        property = "positive-real"
        strength = "iff"
        """)
    assert verdicts == {"1": "confirmed", "2": "confirmed", "3": "confirmed", "4": "confirmed"}


def test_names_no_definition_gives_are_listed_never_a_verdict():
    details = _details(r"""
        [paper]
        id = "u"
        title = "unbound"
        [[equations]]
        id = "1"
        printed = '\operatorname{Re} Z_c(e^{j\omega T}) = B_c - \frac{K_c T}{2}'
        claim = "identity"
        """)
    assert "Z_c" in details["1"] and "no definition" in details["1"]
    assert _verdicts(r"""
        [paper]
        id = "u"
        title = "unbound"
        [[equations]]
        id = "1"
        printed = '\operatorname{Re} Z_c(e^{j\omega T}) = B_c - \frac{K_c T}{2}'
        claim = "identity"
        """) == {"1": "undecided"}


def test_a_negative_damping_is_decided_not_an_internal_error():
    details = _details(r"""
        [paper]
        id = "n"
        title = "negative"
        [symbols]
        b = "real"
        K = "positive"
        T = "positive"
        B = "nonnegative"
        [scenes.wall]
        system = "single-user"
        [[equations]]
        id = "1"
        printed = 'b > \frac{KT}{2} + B'
        claim = "passivity-condition"
        scene = "wall"
        """)
    assert "SceneError" not in details["1"] and "must be non-negative" not in details["1"]


LATEX = r"""\documentclass{article}\begin{document}
Sampled with period $h$, the wall is
\begin{equation} W(z) = K + d\,\frac{z-1}{hz}, \qquad K \ge 0,\; d \ge 0, \label{eq:W} \end{equation}
and the device with damping $c$ gives
\begin{equation} G(z) = c + W(z)\frac{h}{z-1}. \label{eq:G} \end{equation}
On the unit circle
\begin{equation} \operatorname{Re} G(e^{j\omega h}) = c - \frac{Kh}{2} + d\cos\omega h . \end{equation}
Hence $G(z)$ is positive real if and only if
\begin{equation} c \ge \frac{Kh}{2} + d . \end{equation}
A simpler bound, which is sufficient, is
\begin{equation} c \ge Kh + d . \end{equation}
\end{document}"""


def test_an_unedited_draft_of_a_strangers_wall_audits_right():
    """The period is the paper's h (e^{j omega h}), the damping its c: no toolkit name, no scene."""
    result = draft(read_text(LATEX, "wall.tex"), paper_id="wall")
    paper = loads(result.text, "wall.toml")
    assert [c.claim for c in paper.claims] == ["definition", "definition", "identity", "condition", "condition"]
    assert all(c.scene is None for c in paper.claims)
    verdicts = [r.verdict.value for r in audit_paper(paper.paper).results]
    assert verdicts == ["confirmed", "confirmed", "confirmed", "confirmed", "conservative"]
    assert "'positive'" in result.text.split("[[equations]]")[0]          # h, the period, is positive


def test_a_setting_that_names_itself_is_read_once():
    """A display's setting ``b = b + T`` (or a chain back to its own name) substitutes once: the
    value is ``b + T`` in the parameters, never an endless substitution."""
    import sympy as sp

    from hapticproof.audit.definitions.values import Environment, evaluate

    b, T = sp.symbols("b T", real=True)
    value = evaluate(b, Environment(substitutions={"b": b + T}))
    assert sp.sstr(value.to_sympy()) == "T + b"
    value = evaluate(b, Environment(substitutions={"b": T, "T": b}))
    assert sp.sstr(value.to_sympy()) == "b"
