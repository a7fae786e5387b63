"""The ``gears`` section of the JSON report: mobility (and the passive planets with the
constraints they add), links, speeds (rpm exact and float, ω), ratios as exact fractions, each
carrier's Willis equation with its residual, the tabular method, and the geometry.

Imports only plans.gears (and the standard library)."""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

from ..errors import SceneError
from ..scene import Scene
from ..scene.gears import Synthesis
from . import GearAnalysis
from .speeds import tabular
from .synthesis import Candidate, synthesize


def _frac(x: Fraction) -> str:
    return str(x)


def _willis_text(carrier: str, a: str, b: str, ratio: Fraction) -> str:
    sign = "−" if ratio < 0 else ""
    return f"(n_{a} − n_{carrier})/(n_{b} − n_{carrier}) = {sign}{abs(ratio)}"


def gears_report(analysis: GearAnalysis) -> dict[str, Any]:
    """The report of a solved train (plain JSON values; no NaN or infinity)."""
    speeds, s = analysis.speeds, analysis.speeds.structure
    train = s.train
    inputs = [name for name, _ in train.inputs]
    ratios: dict[str, dict[str, Any]] = {}
    for j in inputs:
        ratios[j] = {}
        for k in train.names:
            if k == j:
                continue
            r = speeds.ratio(j, k)
            ratios[j][k] = None if r is None else {"exact": _frac(r), "value": float(r)}
    out: dict[str, Any] = {
        "mobility": s.mobility,
        "count": {"n": s.n, "p5": s.p5, "p4": s.p4, "formula": s.formula},
        "passive": {"planets": train.planets, "extra_planet_links": s.passive_planets,
                    "redundant_constraints": s.redundant,
                    "written": [{"planet": p.name, "copy_of": p.copy_of, "carrier": p.carrier, "meshes": p.meshes}
                                for p in s.passive],
                    "count": {"n": s.n + s.passive_planets, "p5": s.p5 + s.passive_planets,
                              "p4": s.p4 + s.passive_meshes, "q": s.redundant, "formula": s.formula_with_passive}},
        "links": [{"name": link.name, "members": list(link.members),
                   "axis": "frame" if link.axis_on is None else link.axis_on, "fixed": link.fixed}
                  for link in s.links],
        "meshes": [{"wheels": [m.a, m.b], "external": m.external,
                    "seen_from": "frame" if m.reference is None else m.reference,
                    "ratio": {"exact": _frac(m.ratio), "value": float(m.ratio)}} for m in s.meshes],
        "inputs": {name: float(rpm) for name, rpm in train.inputs},
        "speeds": {name: {"rpm": float(n), "rpm_exact": _frac(n), "omega": speeds.omega(name)}
                   for name, n in speeds.rpm.items()},
        "ratios": ratios,
        "willis": [{"carrier": w.carrier, "central": [w.a, w.b], "ratio": {"exact": _frac(w.ratio),
                                                                           "value": float(w.ratio)},
                    "equation": _willis_text(w.carrier, w.a, w.b, w.ratio), "residual_rpm": w.residual}
                   for w in speeds.willis],
        "tabular": {c: [{"link": name, "carrier_held": _frac(rel), "with_carrier": _frac(nh), "total": _frac(n)}
                        for name, rel, nh, n in tabular(speeds, c)] for c in train.carriers},
    }
    g = analysis.geometry
    out["geometry"] = None if g is None else {
        "pitch_radius_mm": g.radius, "arm_mm": g.arm, "planet_arm_mm": g.planet_arm,
        "planet_angle_deg": {p: math.degrees(t) for p, t in g.planet_angle.items()}, "planet_sets": g.sets,
        "unchecked": list(g.unchecked)}
    out["warnings"] = list(analysis.warnings)
    return out


def synthesize_scene(scene: Scene) -> tuple[Candidate, ...]:
    """The candidates of the scene's ``[synthesis]`` (best first); none is refused in one line."""
    s = scene.synthesis
    assert s is not None
    found = synthesize(s.ratio, s.kind, s.planets, tolerance=s.tolerance, module=s.module)
    if not found:
        raise SceneError(f"type {s.kind} cannot reach i = {s.ratio:g} with {s.planets} planets within "
                         f"±{s.tolerance:g} (external wheels 17 … 100 teeth, rings up to 250); try another type",
                         key="synthesis.type")
    return found


def synthesis_report(s: Synthesis, found: tuple[Candidate, ...]) -> dict[str, Any]:
    """The asked ratio and each verified candidate (teeth, exact ratio, relative error, size)."""
    return {"ratio": s.ratio, "type": s.kind, "planets": s.planets, "tolerance": s.tolerance, "module": s.module,
            "candidates": [{"teeth": c.teeth, "ratio": {"exact": str(c.ratio), "value": float(c.ratio)},
                            "error": (float(c.ratio) - s.ratio) / s.ratio, "largest_teeth": c.size}
                           for c in found]}
