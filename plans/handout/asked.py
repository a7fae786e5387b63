"""What an assignment asks, kind by kind, and the exact answers from a variant's report.

Four kinds of assignment, told by the base scene (:func:`kind_of`):

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
  constant driving moment M_d (N·m).

A quantity whose exact value is zero (a point on the frame, a translating link's ω, a held
wheel) is given, not asked. Knows only the scene's values; the report is the JSON dict of
:meth:`plans.Sheets.report`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from ..scene import Scene

__all__ = ["KINDS", "Asked", "kind_of", "asked", "symbol_html"]

#: The kinds of assignment, in the course's order.
KINDS = ("kinematics", "forces", "gears", "dynamics")
#: A value below this × the largest of its kind is an exact zero (given, not asked).
ZERO = 1e-12


@dataclass(frozen=True)
class Asked:
    """One asked quantity: ``symbol`` in the sheets' markup (``v_{B}``, ``R_{12}``), its
    ``unit``, what it is in words, and its exact ``value``."""

    symbol: str
    unit: str
    what: str
    value: float

    @property
    def text(self) -> str:
        """``v_{B}, m/s``: how the sheets and the index page head it."""
        return f"{self.symbol}, {self.unit}"


def kind_of(scene: Scene) -> str:
    """The kind of assignment the scene makes (see the module); a scene no handout is made of
    (a synthesis to run, an involute pair alone) is refused naming what to give instead."""
    if scene.drive is None:
        if scene.synthesis is not None:
            raise SceneError("a [synthesis] scene finds its train when it is drawn: a handout varies a train "
                             "given by its teeth; render it, then copy the found wheels into [gears]", key="synthesis")
        if scene.gears is None:
            raise SceneError("a handout is made of a gear train ([gears]), a linkage or a machine; an involute "
                             "pair alone ([gear_pair]) has none yet", key="gear_pair")
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


def _nonzero(items: list[Asked]) -> list[Asked]:
    """``items`` without those whose value is an exact zero beside the largest of their unit."""
    big: dict[str, float] = {}
    for a in items:
        big[a.unit] = max(big.get(a.unit, 0.0), abs(a.value))
    return [a for a in items if abs(a.value) > ZERO * big[a.unit]]


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
    return _nonzero(out)


def _forces(pos: Mapping[str, Any]) -> list[Asked]:
    f = pos["forces"]
    out = [Asked(_pair(name), "N", f"reaction in the pair of links {name.replace('-', ' and ')}", _norm(r))
           for name, r in f["reactions"].items()]
    out = _nonzero(out)
    b = f["balance"]
    if "moment" in b:
        out.append(Asked("M_{b}", "N·m", f"balancing moment on link {b['link']} (counter-clockwise +)",
                         float(b["moment"])))
    else:
        out.append(Asked("F_{b}", "N", f"balancing force on link {b['link']} at {b.get('at', '')}, along its "
                         "line (+ along the drawn direction)", float(b["value"])))
    return out


def _gears(scene: Scene, report: Mapping[str, Any]) -> list[Asked]:
    g = report["gears"]
    train = scene.gears
    assert train is not None
    inputs = [name for name, _ in train.inputs]
    out = [Asked(f"n_{{{name}}}", "rpm", f"speed of {'carrier' if name in train.carriers else 'wheel'} {name} "
                 f"(+ as link {inputs[0]} turns)", float(s["rpm"]))
           for name, s in g["speeds"].items() if name not in inputs]
    out = _nonzero(out)
    if len(inputs) == 1:
        moving = [n for n in train.names if n not in train.fixed and n != inputs[0]]
        target = next((c for c in train.carriers if c in moving), moving[-1] if moving else None)
        ratio = g["ratios"].get(inputs[0], {}).get(target) if target is not None else None
        if ratio is not None:
            out.append(Asked(f"i_{{{inputs[0]}{target}}}", "—", f"ratio from link {inputs[0]} to link {target}",
                             float(ratio["value"])))
    return out


def _dynamics(report: Mapping[str, Any]) -> list[Asked]:
    d = report["cycle"]["dynamics"]
    fw = d["flywheel"]
    out = [Asked("M_{d}", "N·m", "constant driving moment on the driving link", float(d["constant_moment"]))]
    if fw.get("given"):
        out.append(Asked("δ", "—", "coefficient of speed fluctuation reached", float(d["delta_reached"])))
    else:
        out.append(Asked("J_{fw}", "kg·m²", f"flywheel's moment of inertia for δ = {fw['delta']:g}",
                         float(fw["required"])))
    return out


def asked(scene: Scene, report: Mapping[str, Any], *, points: list[str] | None = None,
          links: list[str] | None = None) -> tuple[Asked, ...]:
    """The quantities the assignment of ``scene`` asks, with their exact values from ``report``
    (``points``, ``links``: those a kinematics assignment names; by default every moving point
    and every link but the frame and the driving one)."""
    kind = kind_of(scene)
    if kind == "gears":
        return tuple(_gears(scene, report))
    if kind == "dynamics":
        return tuple(_dynamics(report))
    pos = report["positions"][0]
    if kind == "forces":
        return tuple(_forces(pos))
    assert scene.drive is not None
    if points is None:
        points = [p for p, d in pos["points"].items() if "v" in d]
    if links is None:
        links = [n for n in pos["links"] if n not in ("0", scene.drive.link)]
    return tuple(_kinematics(scene, pos, points, links))


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
