"""The whole path for one scene: read → model → structure → kinematics → constructions →
SVG and JSON text → files. Nothing is written until everything has been computed and
checked, so a failing scene leaves no partial files behind.

:func:`render` (``plans.render``) is the Python API: a :class:`~plans.scene.Scene` or a scene
file in, :class:`Sheets` out — the sheets display themselves in Jupyter and ``.save`` writes
them (SVG, PNG, PDF and the JSON report), all or nothing."""

from __future__ import annotations

import base64
import contextlib
import html
import json
import math
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

import numpy as np

from .checking import check_plan, similarity_ratio
from .constructions import Scales, acceleration_plan, choose_scales, scheme, uncertain_plan, velocity_plan
from .constructions.plans import Plan, PlanPoint
from .constructions.scales import extent_of
from .constructions.centres import centres_sheet
from .constructions.kinetostatics import group_force_plans, lever, lever_plan_scale, lever_value
from .constructions.koshel import fit_segment, koshel_sheet
from .constructions.cycle import positions_sheet, velocities_sheet
from .constructions.diagrams import diagrams
from .drawing import Heading, Style, draw_centres, draw_plan, draw_scheme
from .drawing.forces import draw_force_plans, draw_lever
from .drawing.koshel import draw_koshel
from .drawing.diagrams import draw_diagrams
from .drawing.positions import draw_positions, draw_velocities
from .errors import ConstructionError, OutputError, PlansError
from .export import DEFAULT_DPI, convert, parse_formats, require_cairo
from .kinematics import WARN_SIN, Motion, analyse
from .kinematics.centres import Centres
from .kinematics.cycle import Cycle, solve_cycle
from .kinematics.tolerances import CROSS_CHECK_RTOL
from .kinetostatics import Forces, solve_forces
from .output import check_folder, write_files
from .model import build_mechanism
from .scene import Scene, read_scene
from .structure import ComplexGroup, analyse_structure

__all__ = ["Rendered", "Sheet", "Sheets", "render", "render_scene", "report", "solve_scene", "record_stages"]

#: The stages run, in order, while :func:`record_stages` is active (None otherwise).
_stages: list[str] | None = None
#: The kinematic stages an order of analysis runs.
_ORDER_STAGES = ("positions", "velocities", "accelerations")


@contextlib.contextmanager
def record_stages() -> Iterator[list[str]]:
    """Record the computing stages each render runs (``positions``, ``velocities``,
    ``accelerations``, ``forces``), in order, into the list it yields."""
    global _stages
    previous, _stages = _stages, []
    try:
        yield _stages
    finally:
        _stages = previous


def _ran(*stages: str) -> None:
    if _stages is not None:
        _stages.extend(stages)


@dataclass(frozen=True)
class Rendered:
    """The files of one scene (name → text), its motion, scales and warnings."""

    stem: str
    files: dict[str, str]
    motion: Motion
    scales: Scales
    warnings: tuple[str, ...]
    forces: Forces | None = None    # the force analysis, when the scene asks for it


def solve_scene(scene: Scene) -> Motion:
    """Solve a scene to the order its drawings need (scheme only: positions; the senses of
    ω and ε on the scheme: accelerations)."""
    return _solve(scene)[0]


def _solve(scene: Scene) -> tuple[Motion, Cycle | None]:
    """The scene's motion and, with ``[drive] positions``, its solved revolution (the motion
    is then the revolution's N positions)."""
    mech = build_mechanism(scene)
    structure = analyse_structure(mech)
    order = 2 if "acceleration" in scene.draw or scene.senses else \
        1 if {"velocity", "centres", "velocities"} & set(scene.draw) else 0
    if scene.wants_forces:      # the power balance needs velocities, inertia accelerations
        order = max(order, 2 if scene.wants_inertia else 1)
    _ran(*_ORDER_STAGES[:order + 1])
    c = scene.cycle
    if c is None:
        return analyse(mech, structure, order=order), None
    cycle = solve_cycle(mech, structure, positions=c.positions, output=c.output, order=order,
                        start=None if c.start == "extreme" else scene.drive.values[0],
                        dense_order=2 if "diagrams" in scene.draw else 0)
    return cycle.motion, cycle


def _forces(scene: Scene, motion: Motion) -> Forces | None:
    """The force analysis when the scene asks for it (force plans, the lever, or [balance])."""
    if not scene.wants_forces:
        return None
    _ran("forces")
    return solve_forces(motion, scene)


def _scales(scene: Scene, motion: Motion, rest: tuple[bool, bool] = (False, False)) -> Scales:
    """μl, μV, μa for a scene (no μV, μa for plans that are at rest: ``rest`` from :func:`at_rest`).
    A scale given in [scales] that would draw off any paper or too small to see raises a
    SceneError (key ``scales.mu_*``)."""
    mech = motion.mechanism
    pts = np.stack([motion.position(p) for p in mech.sketch], axis=1)  # (N, P, 2)
    v_ref = a_ref = None
    v_ext = a_ext = 0.0
    ref_point = mech.drive.tip if mech.drive.kind.angular else mech.drive.guide.label
    if motion.order >= 1 and not rest[0]:
        vel = np.stack([motion.velocity(p) for p in mech.sketch], axis=1)
        v_ref = float(np.max(np.linalg.norm(motion.velocity(ref_point), axis=1)))
        v_ext = max(_span(v) for v in vel)
    if motion.order >= 2 and not rest[1]:
        acc = np.stack([motion.acceleration(p) for p in mech.sketch], axis=1)
        a_ref = float(np.max(np.linalg.norm(motion.acceleration(ref_point), axis=1)))
        a_ext = max(_span(a) for a in acc)
    return choose_scales(extent=extent_of(pts), v_ref=v_ref, v_extent=v_ext, a_ref=a_ref, a_extent=a_ext,
                         overrides=scene.scales)


def _span(vectors: np.ndarray) -> float:
    """Largest width or height of a plan drawn at scale 1: the box of vectors (P, 2) and the
    pole (unlike extent_of, not raised to 1e-6: a plan's vectors may all be smaller)."""
    pts = np.concatenate([vectors, [[0.0, 0.0]]])
    return float(np.max(pts.max(axis=0) - pts.min(axis=0)))


def at_rest(motion: Motion) -> tuple[bool, bool]:
    """Whether every velocity, and every acceleration, is zero at every position: the drive
    stands (ω1 = 0 or v = 0; with ε1 = 0 or a = 0 too for the accelerations), or every
    computed vector is exactly zero."""
    mech = motion.mechanism
    still_v = still_a = False
    if motion.order >= 1:
        still_v = mech.drive.speed == 0.0 or all(not np.any(motion.velocity(p)) for p in mech.sketch)
    if motion.order >= 2:
        still_a = (still_v and mech.drive.rate == 0.0) or all(not np.any(motion.acceleration(p)) for p in mech.sketch)
    return still_v, still_a


def _empty_sheet(kind: str, heading: Heading, *, why: str, ident: str, style: Style) -> str:
    """A plan sheet with the pole alone: the plan of a mechanism at rest (every image at the
    pole), or a construction that cannot be drawn at this position; ``why`` is written below
    it, wrapped to the sheet. Any scale draws it the same; μ = 1 is written."""
    pole = "p" if kind == "velocity" else "π"
    plan = Plan(kind=kind, mu=1.0, pole=pole, points=(PlanPoint(pole, (0.0, 0.0)),), vectors=(), lines=(),
                similar=())
    return draw_plan(plan, heading, ident=ident, style=style, notes=(why,))




def _rest_note(motion: Motion, kind: str) -> str:
    """Why a plan of ``kind`` is the pole alone: the drive stands (ω1 = 0, and ε1 = 0 for the
    accelerations), or every computed vector is zero."""
    d = motion.mechanism.drive
    what = "velocities are" if kind == "velocity" else "accelerations are"
    if d.speed != 0.0 or (kind == "acceleration" and d.rate != 0.0):
        return f"all {what} zero at every position, every image is at the pole"
    drive = (f"ω{d.link} = 0" if d.kind.angular else "v = 0") if kind == "velocity" else \
        (f"ω{d.link} = 0, ε{d.link} = 0" if d.kind.angular else "v = 0, a = 0")
    what = "velocities are" if kind == "velocity" else "velocities and accelerations are"
    return f"the mechanism is at rest ({drive}): all {what} zero, every image is at the pole"


def _suffix(motion: Motion, i: int) -> str:
    """``-30``, ``-m22.5`` (m for minus) after a sheet's name when several positions are
    drawn: the drive's value with as few digits as keep every position's name distinct
    (6 significant digits, more when two values would print alike, e.g. 10.0000001)."""
    if len(motion) == 1:
        return ""
    values = [float(v) for v in motion.values]
    digits = next(d for d in range(6, 18) if len({f"{v:.{d}g}" for v in values}) == len(values))
    return "-" + f"{values[i]:.{digits}g}".replace("-", "m")


def _position_label(motion: Motion, i: int) -> str:
    v = motion.values[i]
    d = motion.mechanism.drive
    j = d.link
    return f"φ_{j} = {v:g}°, ω_{j} = {d.speed:g} rad/s, ε_{j} = {d.rate:g} rad/s²" if d.kind.angular else \
        f"s = {v:g} m, v = {d.speed:g} m/s, a = {d.rate:g} m/s²"


def report(scene: Scene, motion: Motion, scales: Scales, forces: Forces | None = None) -> dict:
    """The JSON report: structure and, per position, points, links, scales, conditioning,
    instantaneous centres and the special points of class III groups (SI), all read off
    ``motion`` (the special points as its second, special-point solution gives them); with
    ``forces``, the force analysis (:func:`_forces_at`)."""
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
            pos["centres"] = {name: _xy(c.at(i)) for name, c in ic.absolute.items()}
            pos["relative_centres"] = {f"{a}-{b}": _xy(c.at(i)) for (a, b), c in ic.relative.items()}
        if special_pts:
            pos["special_points"] = {g: {p.name: _special(p, i) for p in pts} for g, pts in special_pts.items()}
        if forces is not None:
            pos["forces"] = _forces_at(scene, forces, i)
        positions.append(pos)
    return {"title": scene.title, "structure": motion.structure.as_dict(), "positions": positions}


def _num(x) -> float | None:
    """A float for the JSON report, None for NaN (undefined)."""
    x = float(x)
    return None if math.isnan(x) else x


def _forces_at(scene: Scene, forces: Forces, i: int) -> dict:
    """The force analysis at position i (N, N·m, m): ``reactions`` ("i-j" → the force of link i
    on link j), ``prismatic`` (per prismatic pair, where its reaction acts), ``inertia``,
    ``gravity`` (when set), ``balance`` (group by group), ``power`` (the same element from the
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


#: The lever's balancing element must equal the group-by-group one to this fraction of the
#: lever's largest load moment (both are exact; the difference is rounding).
LEVER_RTOL = 1e-9


def _force_sheets(scene: Scene, motion: Motion, forces: Forces, levers: dict, own, stem: str,
                  style: Style) -> dict[str, str]:
    """The force-plan sheets (``-forces``; ``-forces-2`` … when one A3 sheet does not hold
    them) and Zhukovsky's lever (``-lever``, from ``levers``: position → lever) at the
    positions drawn on their own."""
    files: dict[str, str] = {}
    for i in own:
        sfx = _suffix(motion, i)
        label = _position_label(motion, i)
        if "forces" in scene.draw:
            sheets = draw_force_plans(group_force_plans(forces, i), Heading(scene.title, "Force plans", label),
                                      ident=f"forces{sfx or ''}", style=style)
            for k, svg in enumerate(sheets):
                files[f"{stem}-forces{sfx}{'' if k == 0 else f'-{k + 1}'}.svg"] = svg
        if i in levers:
            files[f"{stem}-lever{sfx}.svg"] = draw_lever(levers[i], Heading(scene.title, "Zhukovsky's lever", label),
                                                         ident=f"lever{sfx or ''}", style=style)
    return files


def _lever_at(motion: Motion, forces: Forces, i: int, mu_v: float, path: str):
    """The lever at position i, checked against the group-by-group balancing element."""
    plan = velocity_plan(motion, i, mu_v)
    mu = lever_plan_scale(plan)
    result = lever(motion, forces, i, plan if mu == mu_v else velocity_plan(motion, i, mu))
    scale = max([abs(f.moment) for f in result.forces] + [0.0]) / abs(result.unit_moment) \
        if result.unit_moment else 0.0
    if abs(result.result - float(forces.balance.value[i])) > LEVER_RTOL * max(scale, abs(result.result)):
        raise PlansError(f"{path}: Zhukovsky's lever gives {result.result:.12g} at {motion.values[i]:g}, the "
                         f"group-by-group analysis {float(forces.balance.value[i]):.12g} (please report this scene)")
    return result


def _lever_report(result, forces: Forces, i: int) -> dict:
    """``lever`` (the balancing element found on Zhukovsky's lever ``result`` at position i)
    and ``agreement``: the relative differences of the lever's and the power balance's
    figures from the group-by-group one."""
    value = float(forces.balance.value[i])
    ref = max(abs(value), 1e-300)
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


def render_scene(path: str | Path, style: Style = Style()) -> Rendered:
    """Compute every file of a scene file (nothing is written); the files are named after the
    file's stem.

    A mechanism at rest (the drive stands) gets, instead of each plan with nothing to draw, a
    sheet saying so, and a warning; so does Koshel's plan where its construction degenerates
    (:class:`~plans.errors.ConstructionError`) or fails its check. Every other sheet is drawn."""
    return _render(read_scene(path), stem=Path(path).stem, where=str(path), style=style)


def _render(scene: Scene, *, stem: str, where: str | None, style: Style) -> Rendered:
    """Every file of a scene already read, named ``<stem>…``; ``where`` (the scene's file, or
    None) locates error messages. Nothing here reads or writes a file."""
    path = where or f"scene {scene.title!r}"     # the prefix of the messages below
    try:
        motion, cycle = _solve(scene)
        rest = at_rest(motion)
        scales = _scales(scene, motion, rest)
        forces = _forces(scene, motion)
    except PlansError as exc:
        raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
    for name, worst in motion.triad_disagreement.items():
        if worst > CROSS_CHECK_RTOL:
            raise PlansError(f"{path}: group {name}: the special-point solution and the Jacobian solution differ "
                             f"by {worst:.2e} (relative) — please report this scene")
    files: dict[str, str] = {}
    warnings = []
    resting = [k for k, r in zip(("velocity", "acceleration"), rest) if r and k in scene.draw]
    if resting:
        warnings.append(f"{stem}: {_rest_note(motion, resting[-1])}; the {' and '.join(resting)} "
                        f"plan{'s are sheets' if len(resting) > 1 else ' is a sheet'} saying so")
    formula = motion.structure.formula
    unit = "°" if motion.mechanism.drive.kind.angular else " m"
    for i in range(len(motion)):
        for g, s in motion.sines.items():
            if abs(s[i]) < WARN_SIN:
                away = motion.singular_distance(g, i)
                where = "" if away is None else f", about {away:.3g}{unit} from it"
                warnings.append(f"{stem}: group {g} is near a singular position at {motion.values[i]:g}{unit} "
                                f"(condition {s[i]:.2e}{where}); values are exact but sensitive")
    own = range(len(motion)) if cycle is None else scene.cycle.at    # positions with sheets of their own
    for i in own:
        sfx = _suffix(motion, i)
        label = _position_label(motion, i)
        if "scheme" in scene.draw:
            sch = scheme(motion, i, scales.mu_l, senses=scene.senses)
            files[f"{stem}-scheme{sfx}.svg"] = draw_scheme(sch, Heading(scene.title, "Kinematic scheme", label),
                                                           formula=formula, ident=f"scheme{sfx or ''}", style=style)
        if "centres" in scene.draw:
            sheet = centres_sheet(motion, i)
            files[f"{stem}-centres{sfx}.svg"] = draw_centres(
                sheet, Heading(scene.title, "Instantaneous centres of velocity", label), formula=formula,
                ident=f"centres{sfx or ''}", style=style)
        if "velocity" in scene.draw:
            for g in (found.group for found in motion.special_points.values()):
                koshel = _koshel(motion, i, g, rest[0], title=scene.title, label=label, ident=f"koshel{sfx or ''}",
                                 style=style)
                if koshel is None:
                    continue
                files[f"{stem}-koshel{sfx}.svg"], why = koshel
                if why:
                    warnings.append(f"{stem}: Koshel's plan at {motion.values[i]:g}{unit} is not drawn: {why}")
        for kind, builder, mu, still in (("velocity", velocity_plan, scales.mu_v, rest[0]),
                                         ("acceleration", acceleration_plan, scales.mu_a, rest[1])):
            if kind not in scene.draw:
                continue
            heading = Heading(scene.title, f"{kind.capitalize()} plan", label)
            if still:
                files[f"{stem}-{kind}{sfx}.svg"] = _empty_sheet(kind, heading, ident=f"{kind}{sfx or ''}",
                                                                why=_rest_note(motion, kind), style=style)
                continue
            plan = builder(motion, i, mu)
            failures = check_plan(plan) + _similarity(motion, plan, i)
            if failures:
                raise PlansError(f"{path}: {kind} plan at {motion.values[i]:g} failed its geometric check: "
                                 f"{failures[0]} (please report this scene)")
            sym = "μ_V" if kind == "velocity" else "μ_a"
            files[f"{stem}-{kind}{sfx}.svg"] = draw_plan(plan, heading, ident=f"{kind}{sfx or ''}", style=style,
                                                         notes=tuple(n for n in scales.notes if n.startswith(sym)))
    # Zhukovsky's lever at every position (the report's figure), once: the sheets draw some
    levers = {i: _lever_at(motion, forces, i, scales.mu_v, path) for i in range(len(motion))} \
        if forces is not None and "lever" in scene.draw and scales.mu_v is not None else {}
    if forces is not None and {"forces", "lever"} & set(scene.draw):
        files.update(_force_sheets(scene, motion, forces, levers, own, stem, style))
    data = report(scene, motion, scales, forces)
    for i, result in levers.items():
        data["positions"][i]["forces"].update(_lever_report(result, forces, i))
    if cycle is not None:
        sheets, data["cycle"] = _cycle_sheets(scene, cycle, scales, stem, style)
        files.update(sheets)
    data = _no_negative_zero(data)
    files[f"{stem}.json"] = json.dumps(data, indent=1, ensure_ascii=False) + "\n"
    return Rendered(stem, files, motion, scales, tuple(warnings), forces)


def _cycle_sheets(scene: Scene, cycle: Cycle, scales: Scales, stem: str, style: Style) -> tuple[dict[str, str], dict]:
    """The cycle sheets the scene draws (positions, diagrams, velocities) and the report's
    ``cycle``: the positions, the output's extremes and, with velocities, the table of values
    (with diagrams, how far the graphical differentiation is from the exact values)."""
    c, motion, out = scene.cycle, cycle.motion, cycle.output
    d = motion.mechanism.drive
    unit = "m" if out.kind == "slider" else "rad"
    first = "extreme of link " + out.link if c.start == "extreme" else "angle"
    position = f"{c.positions} positions from φ_{d.link} = {cycle.start % 360.0:.6g}° ({first}), ω_{d.link} = " \
               f"{d.speed:g} rad/s"
    files: dict[str, str] = {}
    data: dict = {"positions": [float(v) for v in motion.values], "start": c.start, "step": cycle.step,
                  "output": {"link": out.link, "kind": out.kind, "point": out.point, "unit": unit}}
    ext = cycle.extreme_output
    if ext is not None:
        data["extremes"] = [{"angle": float(a) % 360.0, "s": float(s)}
                            for a, s in zip(cycle.extremes.values, ext.s)]
    if "positions" in scene.draw:
        sheet = positions_sheet(motion, cycle.extremes, cycle.dense, output=out.link, point=out.point,
                                kind=out.kind, extreme_s=None if ext is None else ext.s, trace=c.trace)
        notes = []
        if sheet.stroke is not None:
            a0, a1 = sheet.extreme_angles
            travel = f"H = {sheet.stroke:.4g} m, the stroke" if out.kind == "slider" else \
                f"ψ = {math.degrees(sheet.stroke):.4g}°, the swing"
            notes.append(f"{travel} of link {out.link} between its extreme positions {out.point}′ "
                         f"(φ_{d.link} = {a0:.2f}°) and {out.point}″ (φ_{d.link} = {a1:.2f}°), drawn thick")
        files[f"{stem}-positions.svg"] = draw_positions(
            sheet, Heading(scene.title, "Positions of the mechanism over one revolution", position),
            ident="positions", style=style, notes=tuple(notes))
    if "diagrams" in scene.draw:
        dn = cycle.dense_output
        dia = diagrams(start=cycle.start, step=cycle.step, positions=c.positions, every=cycle.every, omega=d.speed,
                       link=out.link, point=out.point, kind=out.kind, s=dn.s, v=dn.v, a=dn.a)
        g = {gr.quantity: gr for gr in dia.graphs}
        sym = ("v", "a") if out.kind == "slider" else ("ω", "ε")
        notes = (f"Solid: exact; dashed: graphical differentiation by chords ({sym[0]} at the middles of the intervals "
                 f"from the chords of the first graph, {sym[1]} at the positions from the chords of the second).",
                 f"Graphical {sym[0]} differs from the exact by at most {100 * g['v'].error:.2g} % of {sym[0]}_max, "
                 f"graphical {sym[1]} by at most {100 * g['a'].error:.2g} % of {sym[1]}_max; "
                 f"t = (φ_{d.link} − {cycle.start % 360.0:.6g}°)/ω_{d.link}, T = {dia.period:.4g} s.")
        files[f"{stem}-diagrams.svg"] = draw_diagrams(
            dia, Heading(scene.title, f"Kinematic diagrams of link {out.link}", position), ident="diagrams",
            style=style, notes=notes)
        data["diagrams"] = {"mu_t": dia.mu_t, "mu_phi": dia.mu_phi, "period": dia.period,
                            "mu": {gr.quantity: gr.mu for gr in dia.graphs},
                            "graphical_error": {gr.quantity: gr.error for gr in dia.graphs if gr.graphical}}
    if "velocities" in scene.draw:
        sheet = velocities_sheet(motion)
        for cell in sheet.cells:
            failures = check_plan(cell.plan)
            if failures:
                raise PlansError(f"{scene.file or scene.title}: velocity plan of position {cell.index} failed its "
                                 f"geometric check: {failures[0]} (please report this scene)")
        files[f"{stem}-velocities.svg"] = draw_velocities(
            sheet, Heading(scene.title, "Velocity plans of every position", position), ident="velocities", style=style)
        t = sheet.table
        data["table"] = {"points": list(t.points), "links": list(t.links), "mu_v": sheet.mu_v,
                         "rows": [{"position": int(r[0]), "angle": r[1],
                                   "v": dict(zip(t.points, r[2:2 + len(t.points)])),
                                   "omega": dict(zip(t.links, r[2 + len(t.points):]))} for r in t.rows]}
    return files, data


def _koshel(motion: Motion, i: int, g: ComplexGroup, still: bool, *, title: str, label: str, ident: str,
            style: Style) -> tuple[str, str] | None:
    """Koshel's sheet of class III group ``g`` at position i and why it is empty ("" when it
    is drawn); None when the construction does not apply to the group. A construction that
    degenerates here, or fails its check, gives a sheet that states why (the other sheets are
    unaffected); a mechanism at rest, a sheet saying so."""
    heading = Heading(title, "Velocity plan in an uncertain scale (Koshel)", label)
    try:
        plan = uncertain_plan(motion, i, g)
    except ConstructionError as exc:
        plan, why = None, str(exc)
    else:
        if plan is None:
            return None
        plan, segment = fit_segment(plan)
        failures = [] if still else check_plan(plan) + _similarity(motion, plan, i)
        why = f"the construction failed its geometric check: {failures[0]} (please report this scene)" \
            if failures else ""
    if still:       # the mechanism at rest: said once for the whole scene
        return _empty_sheet("velocity", heading, why=_rest_note(motion, "velocity"), ident=ident, style=style), ""
    if not why:
        try:
            sheet = koshel_sheet(motion, i, g, plan, segment)
        except ConstructionError as exc:
            why = str(exc)
    if why:
        return _empty_sheet("velocity", heading, why=f"not drawn at this position: {why}", ident=ident,
                            style=style), why
    heading = Heading(title, f"Koshel's method: centre P{g.base} and velocity plan in an uncertain scale", label)
    return draw_koshel(sheet, heading, ident=ident, style=style), ""


def _similarity(motion: Motion, plan, i: int, tol: float = 1e-9) -> list[str]:
    """Images of a link's points form a figure similar to the link (similarity theorem)."""
    out = []
    for link, labels in plan.similar:
        names = motion.mechanism.links[link].points
        figure = [tuple(motion.position(p)[i]) for p in names]
        image = [plan.point(l) for l in labels]
        if max(math.dist(image[0], q) for q in image) < 1e-9:
            continue  # the link is at rest on this plan: its image is one point
        dev = similarity_ratio(figure, image)
        if dev > 1e-6:
            out.append(f"images of link {link} are not similar to it (side ratios differ by {dev:.2e})")
    return out


# --- the Python API: plans.render ----------------------------------------------------------

#: Longest stem made from a title (characters).
MAX_STEM_CHARS = 60


@dataclass(frozen=True)
class Sheet:
    """One drawn sheet: ``name`` (``"velocity"``, ``"acceleration-30"``: the file name without
    the stem and ``.svg``), ``file`` (``"four_bar-velocity-30.svg"``) and ``svg`` (its text).
    Jupyter displays it (``_repr_svg_``)."""

    name: str
    file: str
    svg: str

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, folder: str | Path, formats: str | Sequence[str] = ("svg",), *,
             dpi: float = DEFAULT_DPI) -> list[Path]:
        """Write this sheet into ``folder`` in ``formats`` (see :meth:`Sheets.save`)."""
        return _save({self.file: self.svg}, folder, formats, dpi)


@dataclass(frozen=True)
class Sheets(Rendered):
    """What :func:`render` computed for one scene: ``files`` (file name → text: every sheet's
    SVG and the JSON report), ``motion`` (:class:`~plans.kinematics.Motion`), ``scales``,
    ``warnings`` and ``stem``; nothing is written until :meth:`save`.

    ``sheets`` maps a sheet's name (``"scheme"``, ``"velocity-30"``) to its :class:`Sheet`;
    ``sheets_[name]``, iteration and ``len`` go through them too. ``report`` is the JSON report
    as a dict. In Jupyter the result shows every sheet (``_repr_html_``), or the first one where
    only SVG is shown (``_repr_svg_``)."""

    @property
    def sheets(self) -> dict[str, Sheet]:
        prefix = f"{self.stem}-"
        return {name[len(prefix):-len(".svg")]: Sheet(name[len(prefix):-len(".svg")], name, text)
                for name, text in self.files.items() if name.endswith(".svg")}

    @property
    def json(self) -> str:
        """The JSON report's text (the file ``<stem>.json``)."""
        return self.files[f"{self.stem}.json"]

    @property
    def report(self) -> dict:
        """The JSON report, parsed: ``report["positions"][i]["points"]["B"]["v"]``."""
        return json.loads(self.json)

    def __getitem__(self, name: str) -> Sheet:
        return self.sheets[name]

    def __iter__(self) -> Iterator[Sheet]:
        return iter(self.sheets.values())

    def __len__(self) -> int:
        return sum(name.endswith(".svg") for name in self.files)

    def _repr_svg_(self) -> str | None:
        first = next(iter(self.sheets.values()), None)
        return None if first is None else first.svg

    def _repr_html_(self) -> str:
        """Every sheet, one below the other, each an ``<img>`` of its SVG (kept apart so that
        the ids of one sheet never meet another's), with its name above it."""
        parts = [f"<div><p><b>{html.escape(self.motion.mechanism.title)}</b> — {len(self)} sheets "
                 f"({html.escape(self.stem)})</p>"]
        for w in self.warnings:
            parts.append(f"<p>warning: {html.escape(w)}</p>")
        for sheet in self:
            data = base64.b64encode(sheet.svg.encode("utf-8")).decode("ascii")
            parts.append(f'<figure style="margin:0 0 1em 0"><figcaption>{html.escape(sheet.name)}</figcaption>'
                         f'<img src="data:image/svg+xml;base64,{data}" alt="{html.escape(sheet.file)}" '
                         f'style="max-width:100%"></figure>')
        return "".join(parts) + "</div>"

    def save(self, folder: str | Path, formats: str | Sequence[str] = ("svg",), *,
             dpi: float = DEFAULT_DPI) -> list[Path]:
        """Write the sheets in ``formats`` (``("svg", "png", "pdf")`` or ``"svg,png"``; PNG at
        ``dpi`` dots per inch) and the JSON report into ``folder`` (made if needed), as
        ``plans render --format`` does: all or nothing, nothing written on any error
        (:class:`~plans.errors.OutputError`). Returns the paths written."""
        return _save(self.files, folder, formats, dpi)


def _save(files: dict[str, str], folder: str | Path, formats: str | Sequence[str], dpi: float) -> list[Path]:
    wanted = parse_formats(formats if isinstance(formats, str) else ",".join(map(str, formats)))
    check_folder(folder)
    if set(wanted) - {"svg"}:
        require_cairo()
    return write_files(convert(files, wanted, dpi), folder)


def render(scene: Scene | str | os.PathLike, *, style: Style = Style(), stem: str | None = None) -> Sheets:
    """Render a scene: a :class:`~plans.scene.Scene` (from :func:`~plans.scene.read_scene` or
    :func:`~plans.scene.parse_scene`) or the path of a scene file. Nothing is read but that
    file, nothing is written (see :meth:`Sheets.save`).

    The files are named ``<stem>-<sheet>.svg`` and ``<stem>.json``: ``stem`` when given, else the
    scene file's stem (a Scene read from a file keeps it, so both ways give the same files byte
    for byte), else one made from the title (``"Crank-slider mechanism"`` → ``crank-slider_mechanism``).
    Errors are the :class:`~plans.errors.PlansError` of ``plans render``."""
    if isinstance(scene, (str, os.PathLike)):
        path = Path(scene)
        rendered = render_scene(path, style) if stem is None else \
            _render(read_scene(path), stem=_checked_stem(stem), where=str(path), style=style)
    elif isinstance(scene, Scene):
        name = _checked_stem(stem) if stem is not None else \
            Path(scene.file).stem if scene.file else stem_of(scene.title)
        rendered = _render(scene, stem=name, where=scene.file, style=style)
    else:
        raise TypeError(f"plans.render takes a Scene or the path of a scene file, not {type(scene).__name__}")
    return Sheets(rendered.stem, rendered.files, rendered.motion, rendered.scales, rendered.warnings, rendered.forces)


def stem_of(title: str) -> str:
    """A file stem from a title: lower case, every run of characters other than letters,
    digits, ``-`` and ``_`` one ``_``, at most :data:`MAX_STEM_CHARS` characters; ``mechanism``
    when nothing is left."""
    stem = re.sub(r"[^\w-]+", "_", title.strip().lower())[:MAX_STEM_CHARS].strip("_-")
    return stem or "mechanism"


def _checked_stem(stem: str) -> str:
    """``stem`` when it names files in one folder (no separator, not empty, ``.`` or ``..``)."""
    if not isinstance(stem, str) or not stem or stem in (".", "..") or re.search(r"[/\\\x00]", stem):
        raise OutputError(f"stem {stem!r} cannot name a file; give a plain name such as 'four_bar'", key="stem")
    return stem
