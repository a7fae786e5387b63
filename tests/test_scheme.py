"""The kinematic scheme as a textbook draws it: a slotted link joined to its own link (the
Scotch yoke's yoke), bars over plates, two blocks on one pin drawn apart, the drive's angle
φ1 and arc arrows ω1, ε1 with proper heads, the links' ω_j, ε_j on request, coupler points as
dots. Measured on the Scheme object and on the SVG it is drawn to."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
import shapely

from plans.constructions import scheme
from plans.constructions.scheme import BLOCK_MM
from plans.drawing import Heading, Style
from plans.drawing.svg import draw_scheme
from plans.drawing.text import box, runs
from plans.pipeline import solve_scene
from plans.pipeline.scales import scene_scales as _scales
from plans.scene import read_scene

from conftest import EXAMPLES, toml_text

STYLE = Style()
EX = {p.stem: p for p in EXAMPLES}
NS = "{http://www.w3.org/2000/svg}"
#: A written point is within √2·0.0005 mm of the exact one (three decimals), and so is the paper
#: map taken from the first pin's rounded circle: a drawn point or line against an exact point,
#: within twice that (exact by construction).
ROUND_MM = 2.0 * math.sqrt(2.0) * 0.0005


def _solve(path):
    scene = read_scene(path)
    motion = solve_scene(scene)
    return motion, _scales(scene, motion).mu_l


def _scheme(stem: str, i: int = 0, **kw):
    motion, mu = _solve(EX[stem])
    return motion, scheme(motion, i, mu, **kw)


def _svg(sch) -> dict:
    """The drawn scheme: element id → element."""
    text = draw_scheme(sch, Heading("m", "Kinematic scheme", "p"), formula="f", ident="s", style=STYLE)
    root = ET.fromstring(text)
    return {el.get("id"): el for el in root.iter() if el.get("id")}, root


def _path_points(d: str) -> list[tuple[float, float]]:
    return [(float(x), float(y)) for x, y in re.findall(r"(-?[\d.]+),(-?[\d.]+)", d)]


def _shape(el):
    """The inked shape of a line, path, polygon or circle (paper mm)."""
    tag = el.tag.replace(NS, "")
    if tag == "line":
        return shapely.LineString([(float(el.get("x1")), float(el.get("y1"))), (float(el.get("x2")), float(el.get("y2")))])
    if tag == "polygon":
        pts = [tuple(map(float, p.split(","))) for p in el.get("points").split()]
        return shapely.Polygon(pts)
    if tag == "circle":
        return shapely.Point(float(el.get("cx")), float(el.get("cy"))).buffer(float(el.get("r")))
    pts = _path_points(el.get("d"))
    return shapely.Polygon(pts) if el.get("d").rstrip().endswith("Z") else shapely.LineString(pts)


def _paper(els, sch):
    """The content → paper map of a drawn scheme, from its first pin's circle."""
    p = sch.joints[0]
    c = els["s-j0"]
    dx = float(c.get("cx")) - sch.points[p][0]
    dy = float(c.get("cy")) + sch.points[p][1]
    return lambda q: (q[0] + dx, dy - q[1])


def _angle(centre, p) -> float:
    """Angle of paper point p about paper centre, degrees, y up (counter-clockwise positive)."""
    return math.degrees(math.atan2(-(p[1] - centre[1]), p[0] - centre[0]))


def _head(el):
    """Tip, base midpoint and length of a drawn arrowhead (paper mm)."""
    tip, b1, b2 = (np.array(p) for p in _path_points(el.get("d"))[:3])
    base = (b1 + b2) / 2
    return tip, base, float(np.linalg.norm(tip - base))


# -- 1. a slotted link is joined to its own link -----------------------------------------

def test_scotch_yoke_slot_is_joined_to_slider_3_by_a_stem():
    motion, sch = _scheme("scotch_yoke")
    slot = next(g for g in sch.guides if g.link == "3")
    assert not slot.fixed and slot.stem is not None
    foot, end = slot.stem
    assert end == sch.points["Y"]                          # the stem reaches the yoke's point...
    block3 = next(b for b in sch.blocks if b.link == "3")
    assert block3.center == sch.points["Y"]                # ...where slider 3's block is
    seg = shapely.LineString([slot.start, slot.end])
    assert seg.distance(shapely.Point(foot)) < 1e-9      # the foot lies on the slot
    u = np.subtract(slot.end, slot.start)
    assert abs(np.dot(u, np.subtract(end, foot))) < 1e-9 * np.linalg.norm(u) * 100.0   # perpendicular
    # drawn: the stem touches the slot and slider 3's block, the slot carries block 2
    els, _ = _svg(sch)
    k = sch.guides.index(slot)
    stem, slot_el = _shape(els[f"s-stem{k}"]), _shape(els[f"s-guide{k}"])
    assert stem.intersects(slot_el)
    assert stem.intersects(_shape(els["s-block3"]))
    assert slot_el.intersects(_shape(els["s-block2"]))


@pytest.mark.parametrize("stem", sorted(EX))
def test_every_slot_reaches_its_own_link(stem):
    """At every position, a moving guide touches a point of its own link: on the slot's
    segment, or at the end of its stem."""
    motion, mu = _solve(EX[stem])
    for i in range(len(motion.values)):
        sch = scheme(motion, i, mu)
        for g in sch.guides:
            if g.fixed:
                continue
            shape = shapely.LineString([g.start, g.end])
            if g.stem is not None:
                assert shape.distance(shapely.Point(g.stem[0])) < 1e-6
                shape = shape.union(shapely.LineString(g.stem))
            own = motion.mechanism.links[g.link].points
            assert min(shape.distance(shapely.Point(sch.points[p])) for p in own) < 1e-6, (stem, i, g.link)


# -- 2. bars over plates ------------------------------------------------------------------

def test_class4_rod_3_is_drawn_over_plate_4_and_pinned():
    motion, sch = _scheme("class4_six_link")
    els, root = _svg(sch)
    order = [el.get("id") for el in root.iter() if el.get("id")]
    plates = [f"s-link{n}" for n, pts in sch.links if len(pts) >= 3]
    assert "s-link4" in plates and "s-link3" not in plates
    assert order.index("s-link3") > max(order.index(p) for p in plates)   # over the plates' fill
    k = sch.joints.index("D")
    assert order.index(f"s-j{k}") > order.index("s-link3")               # the pin D on top: pinned
    pin = els[f"s-j{k}"]
    assert pin.get("fill") == "#fff" and float(pin.get("r")) == STYLE.joint_radius
    rod = _shape(els["s-link3"])
    assert rod.intersects(_shape(els[f"s-j{k}"]))


# -- 3. two blocks on one pin --------------------------------------------------------------

def test_tangent_mechanism_blocks_on_pin_b_are_apart():
    motion, sch = _scheme("tangent_mechanism")
    b2 = next(b for b in sch.blocks if b.link == "2")
    b3 = next(b for b in sch.blocks if b.link == "3")
    assert b2.center == sch.points["B"] and b2.pin is None       # the block in the slot stays on B
    assert b3.pin == sch.points["B"] and b3.center != b2.center   # the slider is moved along its guide...
    u = np.array([math.cos(math.radians(b3.angle)), math.sin(math.radians(b3.angle))])
    off = np.subtract(b3.center, b3.pin)
    assert abs(u[0] * off[1] - u[1] * off[0]) < 1e-9                            # ...along its guide
    guide = next(g for g in sch.guides if g.fixed)
    seg = shapely.LineString([guide.start, guide.end])
    assert seg.distance(shapely.Point(b3.center)) < 1e-9
    assert all(seg.distance(shapely.Point(b3.center + s * BLOCK_MM[0] / 2 * u)) < 1e-9 for s in (-1, 1))
    els, _ = _svg(sch)
    p2, p3 = _shape(els["s-block2"]), _shape(els["s-block3"])
    assert not p2.equals(p3)
    assert p2.intersection(p3).area == 0.0                         # distinguishable: no overlap
    rod = _shape(els["s-rod3"])                                   # ...and carried from the pin on a rod
    assert rod.intersects(p3) and rod.distance(shapely.Point(_paper(els, sch)(sch.points["B"]))) <= ROUND_MM
    boxes = []
    for name in ("2", "3"):
        t = els[f"s-n{name}"]
        text = "".join(t.itertext())
        assert text == name
        boxes.append(box(runs(text), float(t.get("font-size")), False, float(t.get("x")), float(t.get("y"))))
    a, b = boxes
    assert a.x1 <= b.x0 or b.x1 <= a.x0 or a.y1 <= b.y0 or b.y1 <= a.y0   # the numbers do not overlap


# -- 4. φ1 ---------------------------------------------------------------------------------

@pytest.mark.parametrize("stem,i", [("scotch_yoke", 0), ("quick_return", 1), ("four_bar", 4)])
def test_phi_arc_runs_from_the_reference_to_the_crank(stem, i):
    motion, sch = _scheme(stem, i)
    phi = float(motion.values[i])
    arc = next(a for a in sch.arcs if a.kind == "phi")
    assert sch.phi == phi and sch.reference == 0.0 and arc.label == "φ_{1}"
    assert arc.start == 0.0 and arc.end == pytest.approx(phi, abs=1e-9)
    crank = np.subtract(sch.points[motion.mechanism.drive.tip], sch.points[sch.drive_pivot])
    assert (math.degrees(math.atan2(crank[1], crank[0])) - arc.end + 180.0) % 360.0 - 180.0 == pytest.approx(0.0, abs=1e-9)
    els, _ = _svg(sch)
    to_paper = _paper(els, sch)
    c = to_paper(sch.points[sch.drive_pivot])
    pts = _path_points(els["s-phi1"].get("d"))
    assert _angle(c, pts[0]) == pytest.approx(0.0, abs=0.01)
    assert _angle(c, pts[-1]) % 360.0 == pytest.approx(phi % 360.0, abs=0.01)
    swept = np.unwrap([math.radians(_angle(c, p)) for p in pts])
    assert math.degrees(swept[-1] - swept[0]) == pytest.approx(phi, abs=0.02)   # counter-clockwise through φ1
    ref = _shape(els["s-phi1ref"])
    assert ref.distance(shapely.Point(c)) <= ROUND_MM and ref.length > arc.radius     # the reference line
    a, b = ref.coords
    assert abs(a[1] - b[1]) < 1e-9                                                 # horizontal
    assert any(t.get("id") == "s-phi1l" and "".join(t.itertext()) == "φ1" for t in els.values())


def test_no_phi_arc_when_the_crank_lies_on_the_reference():
    motion, sch = _scheme("four_bar", 0)
    assert motion.values[0] == 0.0
    assert not any(a.kind == "phi" for a in sch.arcs)


# -- 5. ω1, ε1 -------------------------------------------------------------------------------

def _sense_of_head(els, key, centre):
    """+1 when the head points counter-clockwise about ``centre`` (y up), −1 clockwise."""
    tip, base, length = _head(els[key])
    r, d = tip - np.array(centre), tip - base
    r, d = (r[0], -r[1]), (d[0], -d[1])                 # paper (y down) → y up
    return float(np.sign(r[0] * d[1] - r[1] * d[0])), length


@pytest.mark.parametrize("stem", ["scotch_yoke", "crank_slider_offset", "four_bar", "six_link_press"])
def test_omega_arrow_has_a_textbook_head(stem):
    motion, sch = _scheme(stem)
    arc = next(a for a in sch.arcs if a.kind == "omega")
    assert arc.label == "ω_{1}" and math.copysign(1.0, arc.sweep) == math.copysign(1.0, sch.omega)
    els, _ = _svg(sch)
    c = _paper(els, sch)(sch.points[sch.drive_pivot])
    sense, length = _sense_of_head(els, "s-omega1h", c)
    assert 2.5 <= length <= 3.5
    assert sense == math.copysign(1.0, sch.omega)
    assert els["s-omega1h"].get("data-for") == "s-omega1"
    # the head's tip is the arc's end, its base where the drawn arc stops
    tip, base, _ = _head(els["s-omega1h"])
    line = _path_points(els["s-omega1"].get("d"))
    assert math.dist(line[-1], base) < 0.05
    assert math.dist(tip, c) == pytest.approx(arc.radius, abs=ROUND_MM)


def _with_drive(tmp_path, stem, old, new):
    text = EX[stem].read_text()
    assert old in text
    p = tmp_path / f"{stem}.toml"
    p.write_text(text.replace(old, new))
    motion, mu = _solve(p)
    return motion, scheme(motion, 0, mu)


@pytest.mark.parametrize("eps", [20.0, -20.0, 0.0])
def test_epsilon_arrow_iff_epsilon_is_not_zero(tmp_path, eps):
    motion, sch = _with_drive(tmp_path, "crank_slider_offset", "epsilon = 20.0", f"epsilon = {eps!r}")
    assert sch.epsilon == eps
    arcs = [a for a in sch.arcs if a.kind == "epsilon"]
    els, _ = _svg(sch)
    if eps == 0.0:
        assert arcs == [] and "s-epsilon1" not in els and "s-epsilon1h" not in els
        return
    (arc,) = arcs
    assert arc.label == "ε_{1}" and math.copysign(1.0, arc.sweep) == math.copysign(1.0, eps)
    c = _paper(els, sch)(sch.points[sch.drive_pivot])
    sense, length = _sense_of_head(els, "s-epsilon1h", c)
    assert sense == math.copysign(1.0, eps) and length >= 2.5
    assert "".join(els["s-epsilon1l"].itertext()) == "ε1"
    omega = next(a for a in sch.arcs if a.kind == "omega")
    assert arc.radius != omega.radius                      # not drawn over ω1


def test_clockwise_omega_and_no_omega_when_the_crank_stands(tmp_path):
    motion, sch = _with_drive(tmp_path, "crank_slider_offset", "omega = 12.0", "omega = -12.0")
    els, _ = _svg(sch)
    c = _paper(els, sch)(sch.points[sch.drive_pivot])
    assert _sense_of_head(els, "s-omega1h", c)[0] == -1.0
    motion, sch = _with_drive(tmp_path, "crank_slider_offset", "omega = 12.0", "omega = 0.0")
    assert [a.kind for a in sch.arcs] == ["phi", "epsilon"]


# -- 6. ω_j, ε_j on request --------------------------------------------------------------------

@pytest.mark.parametrize("stem", ["four_bar", "crank_slider_offset", "tangent_mechanism", "watt_six_bar"])
def test_senses_of_every_other_link_on_request(stem):
    motion, mu = _solve(EX[stem])
    i = 1 if len(motion.values) > 1 else 0
    plain = scheme(motion, i, mu)
    assert {a.kind for a in plain.arcs} <= {"phi", "omega", "epsilon"} and all(a.link == "1" for a in plain.arcs)
    sch = scheme(motion, i, plain.mu_l, senses=True)
    drive = motion.mechanism.drive.link
    extra = [a for a in sch.arcs if a.link != drive]
    assert motion.order >= 2
    for name in motion.mechanism.moving:
        if name == drive:
            continue
        for kind in ("omega", "epsilon"):
            value = float(getattr(motion.links[name], kind)[i])
            mine = [a for a in extra if a.link == name and a.kind == kind]
            if abs(value) < 1e-9:
                assert mine == []                          # a translating link has no arc
            else:
                (a,) = mine
                assert math.copysign(1.0, a.sweep) == math.copysign(1.0, value)
                assert a.label == ("ω" if kind == "omega" else "ε") + f"_{{{name}}}"
                pts = [sch.points[p] for p in dict(sch.links)[name]]
                if len(pts) >= 2:
                    assert a.centre == pytest.approx(tuple(np.mean(pts, axis=0)))   # at the link's middle
    els, _ = _svg(sch)
    for a in extra:
        key = f"s-{a.kind}{a.link}"
        assert key in els and els[key].get("data-link") == a.link
        tip, base, length = _head(els[key + "h"])
        assert length >= 2.5 - 4 * STYLE.precision          # SENSE_HEAD_MM, up to the coordinates' rounding


def test_senses_of_a_slider_on_the_frame_are_absent():
    motion, sch = _scheme("crank_slider_central", senses=True)
    assert not any(a.link == "3" for a in sch.arcs)         # the slider translates
    assert {a.link for a in sch.arcs if a.kind == "omega"} == {"1", "2"}


def test_senses_need_velocities():
    scene = read_scene(EX["four_bar"])
    from plans.kinematics import analyse
    from plans.model import build_mechanism
    from plans.structure import analyse_structure
    mech = build_mechanism(scene)
    motion = analyse(mech, analyse_structure(mech), order=1)
    sch = scheme(motion, 2, 0.0025, senses=True)
    assert {a.kind for a in sch.arcs if a.link != "1"} == {"omega"}   # no ε_j without accelerations


@pytest.mark.parametrize("senses, arcs", [(True, {"omega2", "omega3", "epsilon2", "epsilon3"}), (False, set())])
def test_senses_key_in_the_scene(tmp_path, senses, arcs):
    """[plans] senses = true marks ω_j and ε_j of the four-bar's coupler and rocker on the
    scheme, from a scene that draws the scheme alone (so accelerations are computed for it)."""
    from plans.cli import main

    scene = _four_bar_with(tmp_path, {"draw": ["scheme"], "senses": senses})
    assert main(["render", str(scene), "-o", str(tmp_path / "o"), "-q"]) == 0
    sheet = sorted((tmp_path / "o").glob("fb-scheme*.svg"))[0].read_text(encoding="utf-8")
    found = set(re.findall(r'id="scheme-[^"]*?-((?:omega|epsilon)[2-9])"', sheet))
    assert found == arcs


def _four_bar_with(tmp_path, plans: dict):
    """The four-bar scene with its [plans] table replaced."""
    import tomllib

    data = tomllib.loads(EX["four_bar"].read_text(encoding="utf-8"))
    data["plans"] = plans
    scene = tmp_path / "fb.toml"
    scene.write_text(toml_text(data), encoding="utf-8")
    return scene


@pytest.mark.parametrize("plans, fragment", [
    ({"draw": ["scheme"], "senses": 1}, "senses is true or false"),
    ({"draw": ["velocity"], "senses": True}, "add \"scheme\" to draw"),
])
def test_senses_key_refused(tmp_path, capsys, plans, fragment):
    from plans.cli import main

    scene = _four_bar_with(tmp_path, plans)
    assert main(["render", str(scene), "-o", str(tmp_path / "o"), "-q"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "plans.senses" in err and fragment in err
    assert not (tmp_path / "o").exists()


# -- 7. coupler points -------------------------------------------------------------------------

def test_coupler_point_m_is_a_filled_dot():
    motion, sch = _scheme("four_bar", 1)
    assert "M" in sch.dots and "M" not in sch.joints
    assert not set(sch.dots) & set(sch.joints)
    els, _ = _svg(sch)
    k = sch.dots.index("M")
    dot = els[f"s-dot{k}"]
    xy = _paper(els, sch)(sch.points["M"])
    # cx, cy rounded to 0.001 mm, and the paper map taken from the first pin's rounded circle:
    # each coordinate within 2 × 0.0005 mm (exact by construction)
    assert (float(dot.get("cx")), float(dot.get("cy"))) == pytest.approx(xy, abs=1e-3)
    assert dot.get("fill") == STYLE.colour and float(dot.get("r")) < STYLE.joint_radius
    pins = [el for key, el in els.items() if re.fullmatch(r"s-j\d+", key)]
    assert all(math.dist((float(p.get("cx")), float(p.get("cy"))), xy) > 1.0 for p in pins)   # no pin at M


def test_block_centres_and_pins_are_not_dots():
    motion, sch = _scheme("scotch_yoke")
    assert "Y" not in sch.dots and "A" not in sch.dots     # Y: slider 3's block, A: a pin
    motion, sch = _scheme("tangent_mechanism")
    assert sch.dots == ("K",)                              # the slotted link's end
