"""What an assignment asks, kind by kind, and the answers it is marked against.

Five kinds of assignment, told by the base scene (:func:`kind_of`):

- ``kinematics`` — a linkage: |v| (and |a|, when the scene draws the acceleration plan) of the
  moving points, |ω| (and |ε|) of the links other than the driving one, at the first position;
- ``forces`` — a loaded linkage (masses or forces, the force plans drawn): |R| of every pair's
  reaction and the balancing moment M_b (N·m, counter-clockwise positive; or the balancing
  force's signed value along its line), at the first position;
- ``gears`` — a gear train: the speed n of every moving wheel and carrier that is not an input
  (rpm, signed: + turns as the input turns counter-clockwise), and the ratio from the input to
  the carrier (to the last wheel when there is no carrier) when one link drives;
- ``dynamics`` — a machine over its cycle ([dynamics]): the flywheel's moment of inertia J
  (kg·m², on the driving link, for the given δ), or δ reached with a given flywheel, and the
  constant driving moment M_d (N·m), each as the task's graphical integration by chords gives
  it at the cycle's positions (:mod:`.graphical`; the exact value beside it);
- ``balancing`` — a rotor ([rotor]): the mass (kg) and the angle (degrees counter-clockwise from
  θ = 0, in [0, 360)) of the balancing mass in each balancing plane, L then M.

A quantity whose exact value is zero (a point on the frame, a translating link's ω, a held
wheel), or that is zero to rounding (at most :data:`ZERO` × the scale of its kind: M_b at a
dead position of the loads, M_d of a machine loaded by weights alone), is given, not asked;
:func:`task_gap` tells a variant left with nothing to find, or without the quantity its task
names. The report is the JSON dict of :meth:`plans.Sheets.report`; a dynamics or balancing
task's method is solved again from the scene (:mod:`.graphical`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Mapping

from ..errors import SceneError
from ..scene import Scene
from .graphical import balancing_precision, chord_answers

__all__ = ["KINDS", "ZERO", "TASK_NAMES", "Asked", "kind_of", "asked", "task_gap", "symbol_html"]

#: The kinds of assignment, in the course's order.
KINDS = ("kinematics", "forces", "gears", "dynamics", "balancing")
#: A value at most this × the scale of its kind is an exact zero, given (not asked): a computed
#: value carries a rounding error of a few ulps (~1e-16) of the largest term it is summed from,
#: times the position's conditioning (at most 1/MARGIN_SIN = 10 in a random variant); 1e-12 is
#: 10³ above that and 10⁹ below anything a student can draw (0.1 mm on a 100 mm vector).
ZERO = 1e-12


@dataclass(frozen=True)
class Asked:
    """One asked quantity: ``symbol`` in the sheets' markup (``v_{B}``, ``R_{12}``), its
    ``unit``, what it is in words, and the ``value`` it is marked against: the exact one, or
    (``method`` says which, ``exact`` holds the exact value) what the task's graphical method
    gives at the task's positions. ``precision``: how closely a drawing gives it (in ``unit``,
    ± the value; 0: not stated), below which no marking tolerance goes; ``angle``: a direction
    in degrees in [0, 360), marked within ±``precision`` either side of 0°."""

    symbol: str
    unit: str
    what: str
    value: float
    exact: float | None = None
    precision: float = 0.0
    angle: bool = False
    method: str = ""

    @property
    def text(self) -> str:
        """``v_{B}, m/s``: how the sheets and the index page head it."""
        return f"{self.symbol}, {self.unit}"


def kind_of(scene: Scene) -> str:
    """The kind of assignment the scene makes (see the module); a scene no handout is made of
    (a synthesis to run, an involute pair alone) is refused naming what to give instead."""
    if scene.drive is None:
        if scene.rotor is not None:
            return "balancing"
        if scene.flywheel_only:
            raise SceneError("a handout is made of a gear train ([gears]), a linkage, a machine or a rotor ([rotor]); "
                             "a flywheel problem ([turning], [operation]) has none yet",
                             key="turning" if scene.turning is not None else "operation")
        if scene.synthesis is not None:
            raise SceneError("a [synthesis] scene finds its train when it is drawn: a handout varies a train "
                             "given by its teeth; render it, then copy the found wheels into [gears]", key="synthesis")
        if scene.gears is None:
            raise SceneError("a handout is made of a gear train ([gears]), a linkage, a machine or a rotor ([rotor]); "
                             "an involute pair alone ([gear_pair]) has none yet", key="gear_pair")
        return "gears"
    if scene.dynamics is not None:
        return "dynamics"
    if "forces" in scene.draw or "lever" in scene.draw:
        return "forces"
    return "kinematics"


def _pair(name: str) -> str:
    """``R_{12}`` for links 1 and 2 (``R_{A-B}`` when a name has more than one character)."""
    a, b = name.split("-")
    return f"R_{{{a}{b}}}" if len(a) == len(b) == 1 else f"R_{{{a}-{b}}}"


def _norm(v: Any) -> float:
    return math.hypot(float(v[0]), float(v[1]))


def _nonzero(items: list[Asked], scale: Mapping[str, float] | None = None) -> list[Asked]:
    """``items`` without the exact zeros: a value at most ZERO × the scale of its unit (the
    largest of ``items`` in that unit, or ``scale[unit]`` when larger)."""
    big = dict(scale or {})
    for a in items:
        big[a.unit] = max(big.get(a.unit, 0.0), abs(a.value))
    return [a for a in items if abs(a.value) > ZERO * big[a.unit]]


def _size(pos: Mapping[str, Any]) -> float:
    """The mechanism's size at a position (m): the diagonal of its points' bounding box."""
    xy = [(float(d["r"][0]), float(d["r"][1])) for d in pos["points"].values() if "r" in d]
    if not xy:
        return 0.0
    xs, ys = zip(*xy)
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys))


def _kinematic_scales(scene: Scene, pos: Mapping[str, Any]) -> dict[str, float]:
    """The scale of each kinematic unit at a position: the drive's own (ω1·size, (|ε1| + ω1²)·size,
    ω1, |ε1| + ω1²; a linear drive's v1 and a1 turned into the same with the size), or the
    largest value of the unit over every point and link there, when larger. A mechanism at rest
    has scale 0: every value of it is an exact zero."""
    size = _size(pos) or 1.0
    d = scene.drive
    assert d is not None
    if d.kind.angular:                      # the report's ω1, ε1 (a crank the gear train turns: the train's)
        own = pos["links"].get(d.link, {})
        w, e = abs(float(own.get("omega", d.speed))), abs(float(own.get("epsilon", d.rate)))
    else:                                   # a slider's v1 (m/s), a1 (m/s²) as a crank's ω1, ε1
        w, e = abs(d.speed) / size, abs(d.rate) / size
    scale = {"m/s": w * size, "m/s²": (e + w * w) * size, "rad/s": w, "rad/s²": e + w * w}
    for data in pos["points"].values():
        for key, unit in (("v", "m/s"), ("a", "m/s²")):
            if key in data:
                scale[unit] = max(scale[unit], _norm(data[key]))
    for data in pos["links"].values():
        for key, unit in (("omega", "rad/s"), ("epsilon", "rad/s²")):
            if key in data:
                scale[unit] = max(scale[unit], abs(float(data[key])))
    return scale


def _kinematics(scene: Scene, pos: Mapping[str, Any], points: list[str], links: list[str]) -> list[Asked]:
    out = []
    with_a = "acceleration" in scene.draw
    for p in points:
        data = pos["points"].get(p, {})
        if "v" in data:
            out.append(Asked(f"v_{{{p}}}", "m/s", f"velocity of point {p}", _norm(data["v"])))
        if with_a and "a" in data:
            out.append(Asked(f"a_{{{p}}}", "m/s²", f"acceleration of point {p}", _norm(data["a"])))
    for n in links:
        data = pos["links"].get(n, {})
        if "omega" in data:
            out.append(Asked(f"ω_{{{n}}}", "rad/s", f"angular velocity of link {n}", abs(float(data["omega"]))))
        if with_a and "epsilon" in data:
            out.append(Asked(f"ε_{{{n}}}", "rad/s²", f"angular acceleration of link {n}",
                             abs(float(data["epsilon"]))))
    return _nonzero(out, _kinematic_scales(scene, pos))


def _law_bound(law) -> float:
    """A bound of |M| (N·m) over a moment's law in the crank angle: its table's largest |value|,
    |mean| + Σ|A| of its harmonics, Σ|peak| of its shapes."""
    return max([abs(y) for _, y in law.table] + [abs(law.mean) + sum(abs(a) for a, _, _ in law.harmonics)]
               + [sum(abs(sh.peak) for sh in law.shapes)])


def _forces(scene: Scene, pos: Mapping[str, Any]) -> list[Asked]:
    """The reactions (zeros beside the largest |R| given) and the balancing element: M_b is an
    exact zero at most ZERO × the largest moment it is summed from — |R|·size (an arm is at most
    the mechanism's size), an inertia couple, a given couple; F_b at most ZERO × the largest |R|."""
    f = pos["forces"]
    out = [Asked(_pair(name), "N", f"reaction in the pair of links {name.replace('-', ' and ')}", _norm(r))
           for name, r in f["reactions"].items()]
    big = max((a.value for a in out), default=0.0)
    out = _nonzero(out)
    b = f["balance"]
    if "moment" in b:
        couples = [abs(float(i["moment"])) for i in f.get("inertia", {}).values() if "moment" in i]
        couples += [abs(m.value) if m.law is None else _law_bound(m.law) for m in scene.moments]
        scale = max([big * _size(pos), *couples])
        balance = Asked("M_{b}", "N·m", f"balancing moment on link {b['link']} (counter-clockwise +)",
                        float(b["moment"]))
    else:
        scale = big
        balance = Asked("F_{b}", "N", f"balancing force on link {b['link']} at {b.get('at', '')}, along its "
                        "line (+ along the drawn direction)", float(b["value"]))
    return out + _nonzero([balance], {balance.unit: scale})


def _gears(scene: Scene, report: Mapping[str, Any]) -> list[Asked]:
    """The speeds (zeros beside the largest of the inputs' and theirs given) and the ratio."""
    g = report["gears"]
    train = scene.gears
    assert train is not None
    inputs = [name for name, _ in train.inputs]
    out = [Asked(f"n_{{{name}}}", "rpm", f"speed of {'carrier' if name in train.carriers else 'wheel'} {name} "
                 f"(+ as link {inputs[0]} turns)", float(s["rpm"]))
           for name, s in g["speeds"].items() if name not in inputs]
    out = _nonzero(out, {"rpm": max((abs(n) for _, n in train.inputs), default=0.0)})
    if len(inputs) == 1:
        moving = [n for n in train.names if n not in train.fixed and n != inputs[0]]
        target = next((c for c in train.carriers if c in moving), moving[-1] if moving else None)
        ratio = g["ratios"].get(inputs[0], {}).get(target) if target is not None else None
        if ratio is not None and math.isfinite(float(ratio["value"])) and abs(float(ratio["value"])) > ZERO:
            out.append(Asked(f"i_{{{inputs[0]}{target}}}", "—", f"ratio from link {inputs[0]} to link {target}",
                             float(ratio["value"])))
    return out


def _dynamics(scene: Scene, report: Mapping[str, Any]) -> list[Asked]:
    """M_d, an exact zero at most ZERO × the largest |M_r| of the loads over the cycle (a machine
    loaded by weights alone does no work over its cycle); J_fw, at most ZERO × (max|ΔT|/ω_m² +
    max I_r)/δ, the size of the terms it is found from; δ reached, at most ZERO (a ratio of speeds).
    Each is then marked against the chord method at the cycle's positions (:mod:`.graphical`),
    its exact value kept beside it."""
    d = report["cycle"]["dynamics"]
    fw = d["flywheel"]
    moments = max((abs(float(m)) for m in d["reduced_moment"]), default=0.0)
    out = [] if scene.dynamics.driving == "law" else \
        _nonzero([Asked("M_{d}", "N·m", "constant driving moment on the driving link",
                        float(d["constant_moment"]))], {"N·m": moments})     # a driving law is given, not asked
    if fw.get("given"):
        out += _nonzero([Asked("δ", "—", "coefficient of speed fluctuation reached", float(d["delta_reached"]))],
                        {"—": 1.0})
    else:
        w2 = float(d["omega_mean"]) ** 2
        energy = max((abs(float(t)) for t in d["kinetic_energy_change"]), default=0.0)
        inertia = max((abs(float(i)) for i in d["reduced_inertia"]), default=0.0)
        scale = (energy / w2 + inertia) / float(fw["delta"]) if w2 > 0.0 and fw["delta"] else 0.0
        out += _nonzero([Asked("J_{fw}", "kg·m²", f"flywheel's moment of inertia for δ = {fw['delta']:g}",
                               float(fw["required"]))], {"kg·m²": scale})
    if not out:
        return out
    c = chord_answers(scene)
    by = {"M_{d}": (c.moment, c.moment_precision), "J_{fw}": (c.inertia, c.inertia_precision),
          "δ": (c.delta, c.delta_precision)}
    method = f"the chord method at the {c.positions} given positions"
    return [replace(a, value=by[a.symbol][0], exact=a.value, precision=by[a.symbol][1], method=method) for a in out]


def _balancing(scene: Scene, report: Mapping[str, Any]) -> list[Asked]:
    """The mass and angle of each balancing mass (L, the reference plane, then M); a plane that
    needs no mass (0 kg: its polygon closes by itself, to rounding) asks neither."""
    out = []
    for name, b, (dm, da) in zip(("L", "M"), report["rotor"]["balancing"], balancing_precision(scene)):
        if not float(b["mass"]) > 0.0:
            continue
        where = f"plane {name} ({float(b['plane']):g} m{', the reference plane' if name == 'L' else ''})"
        out += [Asked(f"m_{{{name}}}", "kg", f"balancing mass in {where}", float(b["mass"]), precision=dm),
                Asked(f"θ_{{{name}}}", "°", f"angle of the balancing mass in plane {name} (counter-clockwise from "
                      "θ = 0)", float(b["angle"]), precision=da, angle=True)]
    return out


def asked(scene: Scene, report: Mapping[str, Any], *, points: list[str] | None = None,
          links: list[str] | None = None) -> tuple[Asked, ...]:
    """The quantities the assignment of ``scene`` asks, with the values they are marked against
    (:class:`Asked`: the exact ones from ``report``, or the task's graphical method's);
    ``points``, ``links``: those a kinematics assignment names (by default every moving point
    and every link but the frame and the driving one); an exact zero (see :data:`ZERO`) is
    given, not asked."""
    kind = kind_of(scene)
    if kind == "gears":
        return tuple(_gears(scene, report))
    if kind == "dynamics":
        return tuple(_dynamics(scene, report))
    if kind == "balancing":
        return tuple(_balancing(scene, report))
    pos = report["positions"][0]
    if kind == "forces":
        return tuple(_forces(scene, pos))
    assert scene.drive is not None
    if points is None:
        points = [p for p, d in pos["points"].items() if "v" in d]
    if links is None:
        links = [n for n in pos["links"] if n not in ("0", scene.drive.link)]
    return tuple(_kinematics(scene, pos, points, links))


#: The quantity a task of each kind names and must ask (its text states it): the balancing
#: element of a forces assignment, the flywheel's J or δ of a dynamics one.
TASK_NAMES = {"forces": ("M_{b}", "F_{b}"), "dynamics": ("J_{fw}", "δ")}


def task_gap(scene: Scene, items: tuple[Asked, ...]) -> str:
    """Why an assignment asking ``items`` cannot be set, and what to change ("" when it can): it
    asks nothing (a mechanism or a train at rest), or the quantity its task names is an exact
    zero (a balancing moment at a dead position of the loads, a flywheel of J = 0)."""
    kind = kind_of(scene)
    d = scene.drive
    angular = d is None or d.kind.angular
    pos, speed, rate = ("angle", "omega", "epsilon") if angular else ("displacement", "velocity", "acceleration")
    if not items:
        if kind == "gears":
            return "nothing to find: every speed is 0 (the input stands); give a nonzero input speed"
        if kind == "dynamics":
            return "nothing to find: its loads do no work over the cycle and need no flywheel; give it loads"
        if kind == "balancing":
            return "nothing to find: the rotor is balanced already (no plane needs a mass); change its masses or angles"
        return (f"nothing to find: every asked quantity is 0 (the mechanism is at rest); give a nonzero {speed} (or "
                f"{rate})")
    names = TASK_NAMES.get(kind, ())
    if names and not any(a.symbol in names for a in items):
        if kind == "forces":
            what = "moment M_b" if scene.balance is None or scene.balance.kind == "moment" else "force F_b"
            return (f"the balancing {what} is 0 at the asked position, to rounding (the loads do no work there), so "
                    f"the task's answer would be noise; give another {pos}")
        return "the flywheel's J is 0, to rounding, so the task's answer would be noise; change the loads or δ"
    return ""


def symbol_html(symbol: str) -> str:
    """``v_{B}`` as HTML: ``v<sub>B</sub>`` (the text escaped)."""
    import html
    out, k = [], 0
    while k < len(symbol):
        if symbol.startswith("_{", k):
            end = symbol.find("}", k)
            out.append(f"<sub>{html.escape(symbol[k + 2:end])}</sub>")
            k = end + 1
        else:
            out.append(html.escape(symbol[k]))
            k += 1
    return "".join(out)
