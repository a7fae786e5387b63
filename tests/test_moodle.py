"""The Moodle XML question bank of a handout (``plans handout … --moodle quiz.xml``): 30 random
variants of each kind of assignment (kinematics, forces, gears, dynamics). The bank must be
well-formed, hold what Moodle's XML importer reads, and each Cloze field's answer, parsed back
from its syntax, must equal the key's value; a student's value is judged by a re-implementation
of Moodle's numerical tolerance (qtype_numerical_answer, "nominal": |r − a| ≤ t + 10⁻¹⁴·max(1, |a|),
PHP's precision 14), written here from Moodle's rule, not taken from plans."""

from __future__ import annotations

import base64
import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plans.handout import moodle_xml, parse_tolerance, random_variants, variant_asked
from plans.errors import OutputError

ROOT = Path(__file__).resolve().parent.parent
BASES = {"kinematics": ROOT / "examples" / "four_bar.toml",
         "forces": ROOT / "examples" / "six_link_press_forces.toml",
         "gears": ROOT / "examples" / "gears" / "planetary_1_21.toml",
         "dynamics": ROOT / "examples" / "six_link_press_flywheel.toml"}
#: Random variants a bank: 30 where a variant costs milliseconds; the loaded press (a force
#: analysis a variant) and the flywheel (a cycle's dynamics a variant) take 12, still every
#: check on each, at a fraction of the time (a variant of the flywheel costs about a second).
COUNTS = {"kinematics": 30, "forces": 12, "gears": 30, "dynamics": 12}
TOLERANCE = 0.02
FIELD = re.compile(r"\{(\d+):NUMERICAL:=([^:}]+):([^}]+)\}")


def moodle_accepts(response: float, answer: float, tolerance: float) -> bool:
    """Moodle's Cloze NUMERICAL check (nominal tolerance, PHP precision 14)."""
    t = abs(tolerance) + 10.0 ** -14 * max(1.0, abs(answer))
    return answer - t <= response <= answer + t


@pytest.fixture(scope="module", params=list(BASES))
def bank(request):
    kind = request.param
    h, drawn = random_variants(BASES[kind], COUNTS[kind], 11)
    asked = [variant_asked(d) for d in drawn]
    text = moodle_xml(h, drawn, asked, tolerance=TOLERANCE)
    return kind, h, drawn, asked, text


def _expected(kind: str, d, h) -> dict[str, float]:
    """The key's values, read here from the variant's JSON report (symbol → value)."""
    r = d.sheets.report
    if kind == "gears":
        z = {w.name: w.teeth for w in d.scene.gears.wheels}
        n1 = dict(d.scene.gears.inputs)["1"]
        nh = n1 * z["1"] / (z["1"] + z["3"])             # ring 3 held: Willis' formula solved by hand
        return {"n_{2}": nh - z["1"] / z["2"] * (n1 - nh), "n_{H}": nh, "i_{1H}": 1.0 + z["3"] / z["1"]}
    if kind == "dynamics":
        dyn = r["cycle"]["dynamics"]
        return {"M_{d}": dyn["constant_moment"], "J_{fw}": dyn["flywheel"]["inertia_exact"]}
    pos = r["positions"][0]
    if kind == "forces":
        f = pos["forces"]
        out = {(f"R_{{{k.replace('-', '')}}}"): math.hypot(*v) for k, v in f["reactions"].items()}
        out["M_{b}"] = f["lever"]["moment"]                # Zhukovsky's lever: another method than the groups'
        return out
    out = {}
    for p, v in pos["points"].items():
        out[f"v_{{{p}}}"] = math.hypot(*v["v"])
        out[f"a_{{{p}}}"] = math.hypot(*v["a"])
    for n, link in pos["links"].items():
        out[f"ω_{{{n}}}"], out[f"ε_{{{n}}}"] = abs(link["omega"]), abs(link["epsilon"])
    return out


def test_bank_is_well_formed_with_one_category_and_a_cloze_question_a_variant(bank):
    kind, h, drawn, asked, text = bank
    root = ET.fromstring(text.encode("utf-8"))
    assert root.tag == "quiz"
    questions = root.findall("question")
    assert [q.get("type") for q in questions] == ["category"] + ["cloze"] * COUNTS[kind]
    category = questions[0].find("category/text").text
    assert category.startswith("$course$/top/") and h.title.replace("/", "-") in category
    assert text.count("<![CDATA[") >= COUNTS[kind]


def test_every_question_has_what_the_importer_reads(bank):
    kind, h, drawn, asked, text = bank
    root = ET.fromstring(text.encode("utf-8"))
    raw_questions = text.split('<question type="cloze">')[1:]
    for q, raw, d in zip(root.findall("question")[1:], raw_questions, drawn):
        assert q.find("name/text").text.strip().endswith(d.name)
        qt = q.find("questiontext")
        assert qt.get("format") == "html"
        body = raw.split("<questiontext", 1)[1].split("</questiontext>", 1)[0]
        assert "<text><![CDATA[" in body            # the HTML travels as CDATA, not escaped
        files = qt.findall("file")
        assert len(files) == 1
        f = files[0]
        assert f.get("encoding") == "base64" and f.get("path") == "/" and f.get("name") == f"{d.name}-assignment.png"
        png = base64.b64decode(f.text)
        assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
        html = qt.find("text").text
        assert f'src="@@PLUGINFILE@@/{f.get("name")}"' in html
        assert "Given:" in html and "Task:" in html
        for tag in ("generalfeedback", "penalty", "hidden"):
            assert q.find(tag) is not None


def test_each_field_parsed_back_equals_the_key(bank):
    kind, h, drawn, asked, text = bank
    root = ET.fromstring(text.encode("utf-8"))
    checked = 0
    for q, d, a in zip(root.findall("question")[1:], drawn, asked):
        html = q.find("questiontext/text").text
        fields = FIELD.findall(html)
        assert len(fields) == len(a) >= 2
        expected = _expected(kind, d, h)
        for (weight, value, tol), item in zip(fields, a):
            assert weight == "1"
            v = float(value)
            assert v == item.value                       # the shortest round-trip decimal: exact
            want = expected[item.symbol]
            assert math.isclose(v, want, rel_tol=1e-9, abs_tol=1e-12 * max(1.0, abs(want))), (d.name, item, want)
            assert math.isclose(float(tol), TOLERANCE * abs(v), rel_tol=1e-15)
            checked += 1
    assert checked >= 2 * COUNTS[kind]


def test_moodle_tolerance_accepts_inside_and_refuses_outside(bank):
    kind, h, drawn, asked, text = bank
    root = ET.fromstring(text.encode("utf-8"))
    for q in root.findall("question")[1:]:
        for _, value, tol in FIELD.findall(q.find("questiontext/text").text):
            a, t = float(value), float(tol)
            assert moodle_accepts(a, a, t)
            for k in (0.999, 0.5, -0.5, -0.999):
                assert moodle_accepts(a + k * TOLERANCE * abs(a), a, t)
            for k in (1.001, 1.5, -1.001, -3.0):
                assert not moodle_accepts(a + k * TOLERANCE * abs(a), a, t)
            assert not moodle_accepts(-a, a, t)          # the sign matters (M_b, n, i are signed)


def test_gear_variants_keep_coaxial_assembly_neighbourhood_and_no_undercut(bank):
    kind, h, drawn, asked, text = bank
    if kind != "gears":
        pytest.skip("the gear train's conditions")
    k = 3
    for d in drawn:
        z = {w.name: w.teeth for w in d.scene.gears.wheels}
        assert z["3"] == z["1"] + 2 * z["2"]                                 # coaxial (one module)
        assert (z["1"] + z["3"]) % k == 0                                    # assembly, 3 planets
        assert z["2"] + 2 < (z["1"] + z["2"]) * math.sin(math.pi / k)        # neighbourhood (tip circles)
        assert min(z["1"], z["2"]) >= 17                                     # no undercut
    assert len({tuple(sorted({w.name: w.teeth for w in d.scene.gears.wheels}.items())) for d in drawn}) > 10


def test_kinematics_variants_keep_grashof(bank):
    kind, h, drawn, asked, text = bank
    if kind != "kinematics":
        pytest.skip("the four-bar's crank")
    for d in drawn:
        lengths = {**h.base_data["lengths"], **d.variant.lengths}
        bars = sorted([lengths["OA"], lengths["AB"], lengths["BC"], lengths["OC"]])
        assert bars[0] == lengths["OA"] and bars[0] + bars[3] < bars[1] + bars[2]   # a crank that turns fully


def test_dynamics_flywheel_gives_the_asked_delta():
    """The J_fw a variant's key gives, put back into the scene as its flywheel, reaches the
    given δ: a second path through the dynamics (a given flywheel, not the one sized)."""
    import copy
    import plans
    from plans.handout.solving import variant_data

    h, drawn = random_variants(BASES["dynamics"], 3, 5)
    for d in drawn:
        j = next(a.value for a in variant_asked(d) if a.symbol == "J_{fw}")
        data = copy.deepcopy(variant_data(h, d.variant))
        delta = data["dynamics"].pop("delta")
        data["dynamics"]["flywheel"] = j
        data["plans"]["draw"] = ["scheme"]
        r = plans.render(plans.parse_scene(data)).report
        assert math.isclose(r["cycle"]["dynamics"]["delta_reached"], delta, rel_tol=1e-7)


def test_parse_tolerance():
    assert parse_tolerance("2%") == 0.02 and parse_tolerance(" 5 ") == 0.05 and parse_tolerance("0.5 %") == 0.005
    for bad in ("0", "-2%", "100%", "nan", "two", "inf%"):
        with pytest.raises(OutputError, match="--tolerance"):
            parse_tolerance(bad)


def _cli(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "plans", "handout", *args], capture_output=True, text=True,
                          cwd=tmp_path)


def test_cli_writes_the_bank_deterministically(tmp_path):
    base = str(BASES["gears"])
    for k in (1, 2):
        r = _cli(tmp_path, base, "--random", "3", "--seed", "4", "-o", f"out{k}", "--moodle", f"quiz{k}.xml",
                 "--tolerance", "3%")
        assert r.returncode == 0, r.stderr
        assert "quiz" in r.stdout and "±3 %" in r.stdout
    one, two = (tmp_path / "quiz1.xml").read_bytes(), (tmp_path / "quiz2.xml").read_bytes()
    assert one == two
    root = ET.fromstring(one)
    tol = [float(t) / abs(float(v)) for q in root.findall("question")[1:]
           for _, v, t in FIELD.findall(q.find("questiontext/text").text)]
    assert tol and all(math.isclose(t, 0.03) for t in tol)


@pytest.mark.parametrize("args, culprit", [
    (["--moodle", "quiz.xml", "--tolerance", "0"], "--tolerance"),
    (["--moodle", "quiz.xml", "--tolerance", "x"], "--tolerance"),
    (["--tolerance", "2%"], "--tolerance"),
    (["--moodle", "quiz.txt"], "--moodle"),
])
def test_cli_refuses_bad_options_in_one_line(tmp_path, args, culprit):
    r = _cli(tmp_path, str(BASES["gears"]), "--random", "2", "-o", "out", *args)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and culprit in lines[0], r.stderr
    assert not (tmp_path / "out").exists() and not list(tmp_path.glob("quiz*"))


def test_cli_never_writes_the_bank_over_its_base(tmp_path):
    base = tmp_path / "base.xml"
    base.write_text(BASES["gears"].read_text(encoding="utf-8"), encoding="utf-8")
    r = _cli(tmp_path, str(base), "--random", "2", "-o", "out", "--moodle", str(base))
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "--moodle" in r.stderr, r.stderr
    assert base.read_text(encoding="utf-8") == BASES["gears"].read_text(encoding="utf-8")
