"""The Moodle XML question bank of a handout (``plans handout … --moodle quiz.xml``): 30 random
variants of each kind of assignment (kinematics, forces, gears, dynamics). The bank must be
well-formed, hold what Moodle's XML importer reads, and each Cloze field's answer, parsed back
from its syntax, must be the key's value to 6 significant digits with a tolerance that holds
every value within ±2 % of the exact one; a student's value is judged by a re-implementation
of Moodle's numerical tolerance (qtype_numerical_answer, "nominal": |r − a| ≤ t + 10⁻¹⁴·max(t, |a|),
PHP's precision 14), written here from Moodle's rule, not taken from plans. Moodle's own Cloze
and number parsing: test_moodle_rules.py."""

from __future__ import annotations

import base64
import math
import re
import struct
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from plans.handout import (chord_answers, field_tolerance, moodle_xml, parse_tolerance, random_variants, read_variants,
                           solve_variant, variant_asked)
from plans.handout.moodle import UPLOAD_LIMIT, size_warning
from plans.errors import OutputError

from conftest import plans_cli

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
    t = abs(tolerance) + 10.0 ** -14 * max(abs(tolerance), abs(answer), 1e-14)
    return answer - t <= response <= answer + t


def digits(text: str) -> int:
    """Significant digits of a decimal number's text (``-52.2256`` → 6, ``1.5e-05`` → 2)."""
    mantissa = text.lstrip("-").lower().split("e")[0].replace(".", "").lstrip("0")
    return len(mantissa)


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
    if kind == "dynamics":       # marked against the chord method at the 12 positions (test_handout_dynamics_marking)
        c = chord_answers(d.scene)
        return {"M_{d}": c.moment, "J_{fw}": c.inertia}
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
    assert category == f"top/{h.title.replace('/', '-')} ({h.base.name}, seed 11)"     # not $course$/: Moodle 5
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
        depth, colour = struct.unpack(">BB", png[24:26])            # IHDR: an 8-bit palette, not RGBA (6)
        assert (depth, colour) == (8, 3)
        html = qt.find("text").text
        assert f'src="@@PLUGINFILE@@/{f.get("name")}"' in html
        assert "Given:" in html and "Task:" in html
        assert "with a decimal point (0.5336) or in e-notation (5.336e-1), without a unit" in html
        assert "0,5336 as 5336" in html
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
            v, t = float(value), float(tol)
            assert v == float(f"{item.value:.6g}") and digits(value) <= 6 and digits(tol) <= 6, (value, tol)
            want = expected[item.symbol]
            assert math.isclose(v, want, rel_tol=5.01e-6), (d.name, item, want)       # 6 digits of the key's value
            assert math.isclose(item.value, want, rel_tol=1e-9, abs_tol=1e-12 * max(1.0, abs(want))), (d.name, item)
            if kind == "dynamics":
                dyn = d.sheets.report["cycle"]["dynamics"]
                assert item.exact == {"M_{d}": dyn["constant_moment"], "J_{fw}": dyn["flywheel"]["inertia_exact"]}[
                    item.symbol]
            exact = field_tolerance(item, TOLERANCE)          # 2 %, or the drawing's precision when wider
            assert exact + abs(item.value - v) <= t <= exact * (1 + 1e-5) + abs(item.value - v)   # rounded up only
            assert abs(item.value - v) < 5.01e-6 * abs(item.value) < 1e-4 * exact / TOLERANCE  # inside 0.01 %
            checked += 1
    assert checked >= 2 * COUNTS[kind]


def test_moodle_tolerance_accepts_inside_and_refuses_outside(bank):
    """Every value within ±2 % of the exact one is right (the field's 6-digit answer does not
    narrow the window), none beyond ±2.002 %."""
    kind, h, drawn, asked, text = bank
    root = ET.fromstring(text.encode("utf-8"))
    for q, items in zip(root.findall("question")[1:], asked):
        for (_, value, tol), item in zip(FIELD.findall(q.find("questiontext/text").text), items):
            a, t, v = float(value), float(tol), item.value
            w = field_tolerance(item, TOLERANCE)             # 2 %, or the drawing's precision when wider
            assert moodle_accepts(a, a, t) and moodle_accepts(v, a, t)
            for k in (1.0, 0.999, 0.5, -0.5, -0.999, -1.0):
                assert moodle_accepts(v + k * w, a, t), (item, k)
            for k in (1.001, 1.5, -1.001, -3.0):
                assert not moodle_accepts(v + k * w, a, t), (item, k)
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
        j = next(a.exact for a in variant_asked(d) if a.symbol == "J_{fw}")     # the exact J (marked: the chords')
        data = copy.deepcopy(variant_data(h, d.variant))
        delta = data["dynamics"].pop("delta")
        data["dynamics"]["flywheel"] = j
        data["plans"]["draw"] = ["scheme"]
        r = plans.render(plans.parse_scene(data)).report
        assert math.isclose(r["cycle"]["dynamics"]["delta_reached"], delta, rel_tol=1e-7)


def test_parse_tolerance():
    assert parse_tolerance("2%") == 0.02 and parse_tolerance(" 5 ") == 0.05 and parse_tolerance("0.5 %") == 0.005
    assert parse_tolerance("0.01%") == 1e-4 and math.isclose(parse_tolerance("99.9"), 0.999)
    for bad in ("0", "-2%", "100%", "nan", "two", "inf%"):
        with pytest.raises(OutputError, match="--tolerance"):
            parse_tolerance(bad)


@pytest.mark.parametrize("tiny", ["0.0099%", "0.001", "1e-12%"])
def test_tolerance_below_moodles_precision_is_refused_naming_the_range(tiny):
    """Moodle keeps 14 digits of an answer and adds 10⁻¹⁴ of slack, and the fields' answers
    have 6 digits: a tolerance under 0.01 % would not be met as written."""
    with pytest.raises(OutputError, match=r"--tolerance.*between 0\.01 % and 100 %") as e:
        parse_tolerance(tiny)
    assert e.value.key == "--tolerance" and tiny in str(e.value)


def test_bank_of_a_base_named_with_a_double_hyphen_is_well_formed(tmp_path):
    """"--" may not stand inside an XML comment (Moodle's xmlize refuses the whole file): no
    file name is written into one."""
    base = tmp_path / "four--bar.toml"
    base.write_text(BASES["kinematics"].read_text(encoding="utf-8"), encoding="utf-8")
    h, drawn = random_variants(base, 1, 2)
    text = moodle_xml(h, drawn, [variant_asked(d) for d in drawn], assignments=[SMALL_SVG])
    root = ET.fromstring(text.encode("utf-8"))                  # expat refuses "--" in a comment too
    assert "four--bar.toml" in root.find("question/category/text").text        # element text: allowed
    for comment in re.findall(r"<!--(.*?)-->", text, re.S):
        assert "--" not in comment and not comment.endswith("-")


#: A small sheet for the banks whose image is not under test.
SMALL_SVG = '<svg xmlns="http://www.w3.org/2000/svg" width="20mm" height="10mm"><path d="M1 1 L10 5"/></svg>'


@pytest.mark.parametrize("base, angle, given", [
    ("six_link_press.toml", "30.0", "30°, 60°, 90°, 120°"),                  # positions = 12 from the angle
    ("four_bar.toml", "[30.0, 120.0, 210.0]", "30°, 120°, 210°;"),           # a list of angles
])
def test_several_positions_the_fields_name_the_first(tmp_path, base, angle, given):
    """A variant with several crank angles: the task lists them, the fields are for the first
    (named, φ1 = 30°), and each answer is that position's value to 6 digits."""
    variants = tmp_path / "variants.toml"
    variants.write_text(f'base = "{(ROOT / "examples" / base).as_posix()}"\n\n'
                        f"[[variant]]\nangle = {angle}\nomega = 10.0\n", encoding="utf-8")
    h = read_variants(variants)
    d = solve_variant(h, h.variants[0])
    a = variant_asked(d)
    text = moodle_xml(h, [d], [a], assignments=[SMALL_SVG])
    body = ET.fromstring(text.encode("utf-8")).findall("question")[1].find("questiontext/text").text
    assert f"φ<sub>1</sub> = {given}" in body                                    # the given positions
    assert "at each given position to scale; find v<sub>" in body
    assert "(magnitudes) at φ<sub>1</sub> = 30° (the first given position)." in body
    assert "<th>your value at φ<sub>1</sub> = 30°</th>" in body
    pos = d.sheets.report["positions"][0]
    assert pos["angle"] == 30.0
    fields = FIELD.findall(body)
    assert len(fields) == len(a) >= 10
    for (_, value, _), item in zip(fields, a):
        assert value == f"{item.value:.6g}"
    v_b = next(value for (_, value, _), item in zip(fields, a) if item.symbol == "v_{B}")
    assert float(v_b) == float(f"{math.hypot(*pos['points']['B']['v']):.6g}")


def test_forces_task_names_the_position_its_fields_are_for():
    h, drawn = random_variants(BASES["forces"], 1, 3)
    d = drawn[0]
    text = moodle_xml(h, drawn, [variant_asked(d)], assignments=[SMALL_SVG])
    angle = d.scene.drive.values[0] % 360.0
    first = " (the first given position)" if len(d.scene.drive.values) > 1 else ""
    assert d.sheets.report["positions"][0]["angle"] % 360.0 == angle
    assert f"Task: at φ<sub>1</sub> = {angle:g}°{first} draw the velocity" in text
    assert f"<th>your value at φ<sub>1</sub> = {angle:g}°</th>" in text


def test_the_bank_embeds_palette_pngs_and_stays_small():
    """A sheet as a 256-colour palette PNG (the RGBA one was 3.3 MB a 30-variant bank): three
    variants of the four-bar under 60 KB each."""
    h, drawn = random_variants(BASES["kinematics"], 3, 1)
    text = moodle_xml(h, drawn, [variant_asked(d) for d in drawn])
    root = ET.fromstring(text.encode("utf-8"))
    for f in root.iter("file"):
        png = base64.b64decode(f.text)
        assert struct.unpack(">IIBB", png[16:26]) == (1654, 1169, 8, 3)       # 8-bit palette
        assert len(png) < 45_000
    assert len(text.encode("utf-8")) < 3 * 60_000


def test_size_warning_names_the_size_the_limit_and_the_fix():
    assert UPLOAD_LIMIT == 2 * 2 ** 20 and size_warning(UPLOAD_LIMIT, 40) is None
    w = size_warning(3_481_988, 30)
    assert w is not None and "\n" not in w
    assert "3.3 MB" in w and "2 MB" in w and "upload_max_filesize" in w and "fewer variants per bank" in w
    assert "about 18 fit" in w


def _cli(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    return plans_cli(["handout", *args], cwd=tmp_path)


def test_cli_writes_the_bank_deterministically(tmp_path):
    base = str(BASES["gears"])
    for k in (1, 2):
        r = _cli(tmp_path, base, "--random", "3", "--seed", "4", "-o", f"out{k}", "--moodle", f"quiz{k}.xml",
                 "--tolerance", "3%")
        assert r.returncode == 0, r.stderr
        size = (tmp_path / f"quiz{k}.xml").stat().st_size
        assert f"the Moodle question bank to quiz{k}.xml ({size / 2 ** 20:.2f} MB, tolerance ±3 %)" in r.stdout
        assert "warning" not in r.stderr
    one, two = (tmp_path / "quiz1.xml").read_bytes(), (tmp_path / "quiz2.xml").read_bytes()
    assert one == two
    root = ET.fromstring(one)
    tol = [float(t) / abs(float(v)) for q in root.findall("question")[1:]
           for _, v, t in FIELD.findall(q.find("questiontext/text").text)]
    assert tol and all(0.03 <= t < 0.03 * (1 + 1e-4) for t in tol)       # 3 %, widened by 6-digit rounding only


@pytest.mark.parametrize("args, culprit", [
    (["--moodle", "quiz.xml", "--tolerance", "0"], "--tolerance"),
    (["--moodle", "quiz.xml", "--tolerance", "0.005%"], "--tolerance"),
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


def test_cli_warns_once_when_the_bank_is_above_the_upload_limit(tmp_path, monkeypatch, capsys):
    import plans.handout.moodle as moodle
    from plans.cli import main

    monkeypatch.setattr(moodle, "UPLOAD_LIMIT", 10_000)
    monkeypatch.chdir(tmp_path)
    assert main(["handout", str(BASES["gears"]), "--random", "2", "-o", "out", "--moodle", "quiz.xml", "-q"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    size = (tmp_path / "quiz.xml").stat().st_size
    assert len(err) == 1 and err[0].startswith("warning: quiz.xml: the question bank is ")
    assert f"{size / 2 ** 20:.1f} MB" in err[0] and "2 MB" in err[0] and "fewer variants per bank" in err[0]


@pytest.mark.parametrize("setup, args", [
    ("folder", ["-o", "out", "--moodle", "bank.xml"]),
    ("file", ["-o", "out", "--moodle", "afile/q.xml"]),
    ("", ["-o", "q.xml", "--moodle", "q.xml"]),
    ("", ["-o", "q.xml/handout", "--moodle", "q.xml"]),
])
def test_cli_checks_the_banks_path_with_o_before_writing_anything(tmp_path, setup, args):
    """A bank path that is a folder, lies below a file, or is the -o folder (or above it) is
    refused naming --moodle before anything is computed, written or made."""
    if setup == "folder":
        (tmp_path / "bank.xml").mkdir()
    if setup == "file":
        (tmp_path / "afile").write_text("x", encoding="utf-8")
    before = sorted(p.name for p in tmp_path.iterdir())
    r = _cli(tmp_path, str(BASES["gears"]), "--random", "2", *args)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1 and "[--moodle]" in lines[0] and "-o]" not in lines[0], r.stderr
    assert "give --moodle" in lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == before and r.stdout == ""
