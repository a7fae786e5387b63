"""The JSON report of one scene (SI units): the structure and, position by position, points,
links, scales, sliders, conditioning, centres, special points and the force analysis — all
read off the solved Motion and Forces — and its text (no negative zero).

Imports nothing of the pipeline's stages, sheets or API; the cycle's part of the report is
made with the cycle's sheets (:mod:`.sheets.cycle`) and added to it."""

from __future__ import annotations

import json
import math
from typing import Mapping

from ..constructions import Scales
from ..constructions.forces import Lever
from ..constructions.kinetostatics import lever_scale, lever_value
from ..kinematics import Motion
from ..kinematics.assemblies import GroupAssemblies
from ..kinematics.centres import Centre, Centres
from ..kinetostatics import Forces
from ..scene import Scene

__all__ = ["report", "report_text"]


def report(scene: Scene, motion: Motion, scales: Scales, forces: Forces | None = None,
           levers: Mapping[int, Lever] | None = None,
           assemblies: list[Mapping[str, GroupAssemblies]] | None = None) -> dict:
    """The JSON report: structure and, per position, points, links, scales, conditioning,
    instantaneous centres and the special points of class III groups (SI), all read off
    ``motion`` (the special points as its second, special-point solution gives them); with
    ``forces``, the force analysis (:func:`_forces_at`) and, at the positions of ``levers``
    (position → Zhukovsky's lever), the lever's balancing element (:func:`_lever_report`); with
    ``assemblies`` (position → group name → its real assemblies), each position's
    ``assemblies``: group name → ``{"count": n, "poses": [{"points": {P: [x, y]}, "chosen": b}]}`` (m)."""
    mech = motion.mechanism
    key = "angle" if mech.drive.kind.angular else "displacement"
    positions = []
    ic: Centres | None = motion.centres if motion.order >= 1 else None
    special_pts = {name: triad.points for name, triad in motion.triads.items()}
    r = {p: motion.position(p) for p in mech.sketch}
    v = {p: motion.velocity(p) for p in mech.sketch} if motion.order >= 1 else {}
    a = {p: motion.acceleration(p) for p in mech.sketch} if motion.order >= 2 else {}
    angles = motion.angles
    slides = motion.sliding
    for i, value in enumerate(motion.values):
        points = {}
        for p in mech.sketch:
            entry = {"r": [float(c) for c in r[p][i]]}
            if v:
                entry["v"] = [float(c) for c in v[p][i]]
            if a:
                entry["a"] = [float(c) for c in a[p][i]]
            points[p] = entry
        links = {}
        for name, state in motion.links.items():
            links[name] = {"angle": float(angles[name][i])}
            if motion.order >= 1:
                links[name]["omega"] = float(state.omega[i])
            if motion.order >= 2:
                links[name]["epsilon"] = float(state.epsilon[i])
        pos = {key: float(value), "points": points, "links": links, "scales": scales.as_dict()}
        if slides:
            pos["sliders"] = {k: _slide(sl, i) for k, sl in slides.items()}
        if motion.sines:
            pos["conditioning"] = {g: float(s[i]) for g, s in motion.sines.items()}
        if ic is not None:
            pos["centres"] = {name: _centre(c, i) for name, c in ic.absolute.items()}
            pos["relative_centres"] = {f"{a}-{b}": _centre(c, i) for (a, b), c in ic.relative.items()}
        if special_pts:
            pos["special_points"] = {g: {p.name: _special(p, i) for p in pts} for g, pts in special_pts.items()}
        if forces is not None:
            pos["forces"] = _forces_at(scene, forces, i)
        if assemblies is not None:
            pos["assemblies"] = {g: found.as_dict() for g, found in assemblies[i].items()}
        positions.append(pos)
    data = {"title": scene.title, "structure": motion.structure.as_dict(), "positions": positions}
    for i, result in (levers or {}).items():
        data["positions"][i]["forces"].update(_lever_report(result, forces, i))
    return data


#: What the report writes for a centre of two links at rest relative to each other (no centre).
AT_REST = "at rest"


def _centre(c: Centre, i: int) -> list[float] | str | None:
    """A centre at position i: [x, y] (m), None at infinity, or ``AT_REST`` when the two links
    do not move relative to each other (to REST_RTOL of the mechanism's speed)."""
    return AT_REST if c.at_rest(i) else _xy(c.at(i))


def report_text(data: dict) -> str:
    """The report file's text: ``data`` as indented JSON (UTF-8 as is), -0.0 written as 0.0. Strict
    JSON: a NaN or an infinity left in ``data`` is a ValueError, never written (undefined values
    are null, by the report's own choice)."""
    return json.dumps(_no_negative_zero(data), indent=1, ensure_ascii=False, allow_nan=False) + "\n"


def _num(x) -> float | None:
    """A float for the JSON report, None for NaN (undefined)."""
    x = float(x)
    return None if math.isnan(x) else x


def _forces_at(scene: Scene, forces: Forces, i: int) -> dict:
    """The force analysis at position i (N, N·m, m): ``reactions`` ("i-j" → the force of link i
    on link j), ``prismatic`` (per prismatic pair, where its reaction acts), ``inertia``,
    ``gravity`` (when set), ``moments`` (the moments with a law in the crank angle: link → its value
    here), ``balance`` (group by group), ``power`` (the same element from the
    power balance) and ``power_residual``; ``lever`` is left for the lever's drawing."""
    out: dict = {"reactions": {k: _xy(r.force[i]) for k, r in forces.reactions.items()}}
    prismatic = {}
    for k, r in forces.reactions.items():
        if r.kind == "P":
            off = _num(r.offset[i])
            prismatic[k] = {"at": r.at, "u": _xy(r.u[i]), "origin": _xy(r.origin[i]), "moment": float(r.moment[i]),
                            "offset": off, "point": None if off is None else _xy(r.point[i])}
    if prismatic:
        out["prismatic"] = prismatic
    inertia: dict = {}
    for l in forces.loads:
        if l.kind == "inertia":
            inertia.setdefault(l.link, {})["force"] = _xy(l.force[i])
    for c in forces.couples:
        if c.kind == "inertia":
            inertia.setdefault(c.link, {})["moment"] = float(c.moment[i])
    if inertia:
        out["inertia"] = {link: {"at": scene.masses[link].centre, **v} for link, v in inertia.items()}
    if scene.gravity is not None:
        out["gravity"] = {l.link: _xy(l.force[i]) for l in forces.loads if l.kind == "gravity"}
    laws = {m.link for m in scene.moments if m.law is not None}
    if laws:            # a moment's law in the crank angle, its value at this position (N·m, CCW +)
        out["moments"] = {c.link: float(c.moment[i]) for c in forces.couples if c.kind == "external" and c.link in laws}
    b = forces.balance
    if b.kind == "moment":
        out["balance"] = {"link": b.link, "moment": float(b.value[i])}
        power = None if forces.power is None else {"moment": _num(forces.power[i])}
    else:
        out["balance"] = {"link": b.link, "at": b.at, "point": _xy(b.point[i]), "force": _xy(b.vector[i]),
                          "value": float(b.value[i]), "direction": _xy(b.direction[i])}
        if b.reacts_on is not None:
            out["balance"]["reacts_on"] = b.reacts_on
        p = None if forces.power is None else _num(forces.power[i])
        power = None if forces.power is None else \
            {"force": None if p is None else _xy(p * b.direction[i]), "value": p}
    out["power"] = power
    out["power_residual"] = None if forces.power_residual is None else float(forces.power_residual[i])
    out["lever"] = None
    return out


def _lever_report(result: Lever, forces: Forces, i: int) -> dict:
    """``lever`` (the balancing element found on Zhukovsky's lever ``result`` at position i)
    and ``agreement``: the differences of the lever's and the power balance's figures from the
    group-by-group one, over the scale of the loads' moments (:func:`lever_scale`; never less
    than the group-by-group figure), not over the figure alone, which near an extreme position
    is itself rounding."""
    value = float(forces.balance.value[i])
    ref = max(lever_scale(result), abs(value), 1e-300)
    power = None if forces.power is None else float(forces.power[i])
    return {"lever": lever_value(result, forces, i),
            "agreement": {"lever": abs(result.result - value) / ref,
                          "power": None if power is None else abs(power - value) / ref}}


def _no_negative_zero(data):
    """``data`` with every -0.0 written as 0.0 (a zero's sign is rounding, not information)."""
    if isinstance(data, float):
        return data + 0.0
    if isinstance(data, dict):
        return {k: _no_negative_zero(v) for k, v in data.items()}
    if isinstance(data, list):
        return [_no_negative_zero(v) for v in data]
    return data


def _xy(p) -> list[float] | None:
    return None if p is None else [float(p[0]), float(p[1])]


def _slide(sl, i: int) -> dict:
    """A prismatic pair at position i: its point, the guide's direction u, the sliding s (m)
    along u from the guide's anchor, σ (m/s) and σ̇ (m/s²) along u, the Coriolis vector (m/s²)
    — each when computed (:mod:`plans.kinematics.sliders`)."""
    out = {"point": sl.point, "u": _xy(sl.u[i]), "s": float(sl.s[i])}
    if sl.v is not None:
        out["v"] = float(sl.v[i])
    if sl.a is not None:
        out["a"] = float(sl.a[i])
        out["coriolis"] = [float(c) for c in sl.coriolis[i]]
    return out


def _special(p, i: int) -> dict:
    """A special point at position i: r (m), the sine between its axes, v and a when known;
    r is null when the axes are parallel (the point is at infinity)."""
    finite = abs(float(p.sin[i])) > 1e-12
    out = {"r": _xy(p.position[i]) if finite else None, "sin": float(p.sin[i])}
    for key, vec in (("v", p.v), ("a", p.a)):
        if vec is not None:
            out[key] = _xy(vec[i]) if finite else None
    return out
