"""The question bank of every example that takes a handout (its base scene as the one variant),
read by Moodle's own rules, re-implemented here in Python from Moodle's source (moodle/moodle):

- ``question/type/multianswer/questiontype.php``, ``qtype_multianswer_extract_question`` and the
  ``ANSWER_*``, ``NUMBER_REGEX`` and ``NUMERICAL_ALTERNATIVE_REGEX`` defines above it: how the
  importer cuts a Cloze text into subquestions, and a NUMERICAL alternative into its answer and
  tolerance;
- ``question/type/numerical/questiontype.php``: ``qtype_numerical::save_question_options`` (the
  import runs the answer and the tolerance through ``apply_unit`` in the importing user's
  language, and the database keeps PHP's 14 digits), ``qtype_numerical_answer_processor::
  apply_units`` (a response read with the site language's decimal and thousands separators) and
  ``contains_thousands_seaparator`` (the validation that flags a thousands separator);
- ``question/type/numerical/question.php``: ``qtype_numerical_question::is_complete_response``
  (no unit in a Cloze field, no thousands separator) and ``qtype_numerical_answer::
  get_tolerance_interval`` ("nominal") with ``within_tolerance``.

English (decimal ".", thousands ","), Russian ("," and a space or a no-break space) and German
("," and ".") settings: a value typed as the question text says (a decimal point or e-notation;
a decimal comma where Moodle flags the point as a thousands separator) is graded right.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from decimal import Decimal

import numpy as np
import pytest

from plans.errors import SceneError
from plans.handout import field_tolerance, moodle_xml, read_variants, solve_variant, variant_asked
from test_moodle import ROOT, SMALL_SVG, TOLERANCE

EXAMPLES = [*sorted((ROOT / "plans" / "examples").glob("*.toml")),
            *sorted((ROOT / "plans" / "examples" / "gears").glob("*.toml"))]
#: The languages' (decimal separator, thousands separator) of Moodle's langconfig.
LANGUAGES = {"en": (".", ","), "ru": (",", " "), "ru-nbsp": (",", "\u00a0"), "de": (",", ".")}

# -- qtype_multianswer_extract_question: the Cloze syntax --------------------------------------
# An alternative: an optional fraction ("=" right, or %n%), then its answer, the shortest text up
# to "~", "#" or "}" (or the end) that does not end in "\", "&" or "&amp;", then "#feedback".
# Python's look-behind takes one width each, so Moodle's one alternation is three look-behinds.
_ANSWER_TEXT = r".+?(?<!\\)(?<!&)(?<!&amp;)(?=[~#}]|$)"
_FEEDBACK_TEXT = r".*?(?<!\\)(?=[~}]|$)"
_ALTERNATIVE_BARE = rf"(?:=|%-?[0-9]+%)?{_ANSWER_TEXT}(?:#{_FEEDBACK_TEXT})?"
ALTERNATIVE = re.compile(rf"~?(?P<fraction>=|%(?P<percent>-?[0-9]+)%)?(?P<answer>{_ANSWER_TEXT})"
                         rf"(?:#(?P<feedback>{_FEEDBACK_TEXT}))?", re.S)
# A subquestion: {mark:TYPE:alternatives separated by ~}.
_TYPES = "NUMERICAL|NM|MULTICHOICE|MC|MULTICHOICE_V|MCV|MULTICHOICE_H|MCH|SHORTANSWER|SA|MW|SHORTANSWER_C|SAC|MWC"
SUBQUESTION = re.compile(rf"\{{(?P<mark>[0-9]*):(?P<type>{_TYPES}):"
                         rf"(?P<alternatives>{_ALTERNATIVE_BARE}(?:~{_ALTERNATIVE_BARE})*)\}}", re.S)
# A NUMERICAL alternative's answer: a number, then ":" and the tolerance (whose sign is dropped).
_UNSIGNED = r"(?:[0-9]+[.,]?[0-9]*|[.,][0-9]+)(?:[eE][-+]?[0-9]+)?"
NUMERICAL_ANSWER = re.compile(rf"^(?P<answer>-?{_UNSIGNED})(?::-?(?P<tolerance>{_UNSIGNED}))?$", re.S)


@dataclass(frozen=True)
class Alternative:
    fraction: float
    answer: str
    tolerance: str | None      # NUMERICAL only: "0" when none is written


@dataclass(frozen=True)
class Subquestion:
    mark: str
    numerical: bool
    alternatives: tuple[Alternative, ...]


def extract_cloze(text: str) -> tuple[str, list[Subquestion]]:
    """The question text with each subquestion replaced by ``{#k}``, and the subquestions, as
    ``qtype_multianswer_extract_question`` finds them: the first match each time, its
    alternatives read one after the other from what is left."""
    found = []
    while (m := SUBQUESTION.search(text)) is not None:
        numerical = m["type"] in ("NUMERICAL", "NM")
        alternatives, rest = [], m["alternatives"]
        while (a := ALTERNATIVE.search(rest)) is not None:
            fraction = 1.0 if a["fraction"] == "=" else 0.01 * int(a["percent"]) if a["percent"] else 0.0
            n = NUMERICAL_ANSWER.search(a["answer"]) if numerical else None
            alternatives.append(Alternative(fraction, n["answer"], n["tolerance"] or "0") if n is not None
                                else Alternative(fraction, a["answer"], None))
            rest = rest.split(a.group(0), 1)[1]
        found.append(Subquestion(m["mark"] or "1", numerical, tuple(alternatives)))
        text = text.replace(m.group(0), f"{{#{len(found)}}}", 1)
    return text, found


# -- qtype_numerical_answer_processor and qtype_numerical_answer: reading and grading a number ----
_OTHER_E = re.compile(r"(?:e|E|(?:x|\*|×)10(?:\^|\*\*))([+-]?[0-9]+)")
_NUMBER_START = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:e[-+]?[0-9]+)?")


def apply_units(response: str, decsep: str, thousandssep: str) -> tuple[float | None, str]:
    """The value and the unit text of a response, as ``apply_units`` reads it: spaces dropped,
    the ways of writing ×10^ turned to "e"; with a "." (or several ","), every "," is a thousands
    separator and dropped; else the thousands separator is dropped, then the decimal separator
    and a "," become "."; the number is the longest one at the start."""
    r = _OTHER_E.sub(r"e\1", response.replace(" ", ""))
    if "." in r or r.count(",") > 1:
        r = r.replace(",", "")
    else:
        for old, new in ((thousandssep, ""), (decsep, "."), (",", ".")):     # PHP's str_replace, pair by pair
            r = r.replace(old, new)
    m = _NUMBER_START.match(r)
    return (None, r) if m is None else (float(m.group(0)), r[m.end():])


def complete(response: str, decsep: str, thousandssep: str) -> bool:
    """``is_complete_response`` of a Cloze NUMERICAL field (no units): a number, nothing after
    it, and no "." or "," that is the language's thousands separator."""
    value, unit = apply_units(response, decsep, thousandssep)
    flagged = thousandssep in (".", ",") and thousandssep in response
    return value is not None and unit == "" and not flagged


def php14(x: float) -> float:
    """A float after PHP writes it with ``precision`` = 14 (the database's text) and reads it back."""
    return float(f"{x:.14g}")


def graded_right(value: float | None, answer: float, tolerance: float) -> bool:
    """``within_tolerance``, "nominal": |value − answer| ≤ t + 10⁻¹⁴·max(t, |answer|, 10⁻¹⁴)."""
    if value is None:
        return False
    eps = 1e-14
    t = tolerance + eps * max(abs(tolerance), abs(answer), eps)
    return answer - t <= value <= answer + t


# -- the banks ------------------------------------------------------------------------------------

@pytest.fixture(scope="module", params=EXAMPLES, ids=lambda p: p.stem)
def bank(request, tmp_path_factory):
    """The example's base scene as a one-variant handout (a variants file with one empty
    [[variant]]) and its bank (a small image: the sheet is not under test); an example that
    takes no handout (an involute pair, a synthesis) is skipped, refused for that reason."""
    path = request.param
    folder = tmp_path_factory.mktemp(path.stem)
    variants = folder / "variants.toml"
    variants.write_text(f'base = "{path.as_posix()}"\n\n[[variant]]\n', encoding="utf-8")
    try:
        h = read_variants(variants)
    except SceneError as exc:
        assert exc.key in ("gear_pair", "synthesis"), exc
        pytest.skip(f"{path.name} takes no handout ({exc.key})")
    d = solve_variant(h, h.variants[0])
    asked = variant_asked(d)
    text = moodle_xml(h, [d], [asked], tolerance=TOLERANCE, assignments=[SMALL_SVG])
    body = text.split("<![CDATA[")[2].split("]]>")[0]          # the Cloze question's text
    return h, d, asked, body


def typed(v: float) -> list[str]:
    """``v`` as a student types it following the question text: with a decimal point (every
    digit, and 4 significant ones) or in e-notation."""
    return [np.format_float_positional(v, trim="0"),
            np.format_float_positional(v, precision=4, unique=False, fractional=False, trim="0"),
            f"{v:.4e}"]


def test_every_field_parses_by_the_cloze_rules_with_the_answer_and_tolerance_intended(bank):
    h, d, asked, body = bank
    rest, subquestions = extract_cloze(body)
    assert len(subquestions) == len(asked) >= 2
    assert "NUMERICAL" not in rest and not re.search(r"\{[0-9]*:", rest)     # nothing else is read as a field
    assert re.findall(r"\{#([0-9]+)\}", rest) == [str(k) for k in range(1, len(asked) + 1)]
    for sub, item in zip(subquestions, asked):
        assert sub.numerical and sub.mark == "1" and len(sub.alternatives) == 1
        alt = sub.alternatives[0]
        assert alt.fraction == 1.0 and alt.tolerance is not None
        v = item.value
        assert alt.answer == f"{v:.6g}"                                      # 6 significant digits
        a, t = float(alt.answer), float(alt.tolerance)
        w = field_tolerance(item, TOLERANCE)                   # ±2 % of the value, or the drawing's precision
        need = w + abs(v - a)                                  # seen from a
        tol = Decimal(alt.tolerance)
        assert tol - Decimal(1).scaleb(tol.adjusted() - 5) < Decimal(need) <= tol, (item, alt)   # need, rounded up
        assert abs(v - a) <= 5.000001e-6 * abs(v) < 1e-4 * abs(v) <= TOLERANCE * abs(v)   # a is inside the exact one's
        for language, (decsep, thousandssep) in LANGUAGES.items():            # the import reads them, then 14 digits
            stored_a, _ = apply_units(alt.answer, decsep, thousandssep)
            stored_t, _ = apply_units(alt.tolerance, decsep, thousandssep)
            assert (php14(stored_a), php14(stored_t)) == (a, t), (language, alt)
        for text in typed(v):
            assert "." in text or "e" in text
            assert graded_right(float(text), a, t), (item, text)
        assert graded_right(v + w, a, t) and graded_right(v - w, a, t)
        assert not graded_right(v + 1.001 * w, a, t) and not graded_right(-v, a, t)


def test_a_value_typed_as_the_text_says_is_graded_right_in_english_russian_and_german(bank):
    h, d, asked, body = bank
    assert "with a decimal point (0.5336) or in e-notation (5.336e-1), without a unit, spaces or a thousands " \
           "separator" in body
    assert "type a decimal comma instead (0,5336)" in body
    _, subquestions = extract_cloze(body)
    comma_misread = 0
    for sub, item in zip(subquestions, asked):
        a, t = float(sub.alternatives[0].answer), float(sub.alternatives[0].tolerance)
        for text in typed(item.value):
            for language, (decsep, thousandssep) in LANGUAGES.items():
                value, unit = apply_units(text, decsep, thousandssep)
                assert unit == "" and graded_right(value, a, t), (language, text, value, item)
                if complete(text, decsep, thousandssep):
                    continue
                # Only German flags the point as its thousands separator: the text says to type a
                # decimal comma then, read right there.
                assert language == "de" and "." in text, (language, text)
                comma = text.replace(".", ",")
                value, _ = apply_units(comma, decsep, thousandssep)
                assert complete(comma, decsep, thousandssep) and graded_right(value, a, t), (comma, value)
        point = np.format_float_positional(item.value, precision=4, unique=False, fractional=False, trim="0")
        if point.split(".")[1] != "0":       # why the text warns: in English 0,5336 is 5336
            value, _ = apply_units(point.replace(".", ","), *LANGUAGES["en"])
            comma_misread += not graded_right(value, a, t)
        assert not complete(f"{point} {item.unit}", *LANGUAGES["en"])         # with a unit: not an answer
    assert comma_misread > 0 or all(float(x.alternatives[0].answer).is_integer() for x in subquestions)


def test_the_rules_as_written_here_read_moodles_own_examples():
    """The re-implementation against the cases of Moodle's own unit tests (question/type/
    numerical/tests/answerprocessor_test.php: test_apply_units, test_euro_style) and others
    read off the rules: the separators, the ways of writing ×10^, a unit left over, a Cloze with
    feedback and a percentage, an escaped "}" in an answer."""
    en, ru, de = LANGUAGES["en"], LANGUAGES["ru"], LANGUAGES["de"]
    assert apply_units("3x10^8 m/s", *en) == (3e8, "m/s") and apply_units("0001.000 mph", *en) == (1.0, "mph")
    assert apply_units("1 frogs", *en) == (1.0, "frogs") and apply_units(". m/s", *en)[0] is None
    assert apply_units("-1 000", ",", " ") == (-1000.0, "") and apply_units("3,14159", ",", " ") == (3.14159, "")
    assert apply_units("1,234.5", *en) == (1234.5, "") and apply_units("0,5336", *en) == (5336.0, "")
    assert apply_units("0,5336", *ru) == (0.5336, "") and apply_units("1 234,5", *ru) == (1234.5, "")
    assert apply_units("0,5336", *de) == (0.5336, "") and apply_units("1.234,5", *de) == (1.2345, "")
    assert apply_units("1.5x10^3", *en) == (1500.0, "") and apply_units("-2e-3m/s", *en) == (-0.002, "m/s")
    assert apply_units("abc", *en)[0] is None
    assert not complete("1.5", *de) and complete("1,5", *de) and complete("1.5", *ru) and not complete("1,234.5", *en)
    rest, subs = extract_cloze("x {2:NM:=1.5:0.1#right~%50%2:0.5#half} y {:SA:=a\\}b} z")
    assert rest == "x {#1} y {#2} z"
    assert subs[0] == Subquestion("2", True, (Alternative(1.0, "1.5", "0.1"), Alternative(0.5, "2", "0.5")))
    assert subs[1] == Subquestion("1", False, (Alternative(1.0, "a\\}b", None),))
    assert extract_cloze("{1:NUMERICAL:=-3e-05:-2}")[1][0].alternatives == (Alternative(1.0, "-3e-05", "2"),)
    assert graded_right(1.02, 1.0, 0.02) and not graded_right(1.0201, 1.0, 0.02) and php14(1 / 3) == 0.33333333333333
