"""The involute pair's report (``gear_pair`` in the JSON) and its sheets (``-meshing``,
``-cutting``) when drawn.

Reads an analysed pair; imports nothing of the pipeline."""

from __future__ import annotations

import math
from typing import Any

from ...constructions.gear_pair import cutting, meshing
from ...constructions.gear_views import UNBOUNDED
from ...drawing import Style
from ...drawing.gear_pair import draw_pair_sheet
from ...drawing.svg import Heading
from ...gears.pair import PairAnalysis
from ...scene import Scene

__all__ = ["pair_report", "pair_sheets"]


def pair_report(a: PairAnalysis) -> dict[str, Any]:
    """The JSON ``gear_pair``: lengths in mm, angles in degrees, per wheel [wheel 1, wheel 2]; what
    a rack has not (its teeth, diameters, x_min, the line N1N2 ending at infinity) is null, a ring
    gear's x_min too. ``kind`` "external", "internal" or "rack"; the paths of approach and recess,
    the arc of contact (mm), ``angle_turned`` [pinion, wheel 2] in degrees (wheel 2's null for a
    rack, whose travel is ``rack_travel`` mm); with ``n1``, ``sliding_velocity`` in m/s."""
    p = a.pair
    two = lambda t: [_finite(v) for v in t]        # noqa: E731
    turned = [None if v is None else math.degrees(v) for v in p.angles_turned]
    out = {"wheels": list(a.names), "z": list(p.z), "module": p.module, "pressure_angle": math.degrees(p.alpha),
           "addendum": p.addendum if p.addenda is None else list(p.addenda), "clearance": p.clearance,
           "tip_radius": a.tip_radius, "shift_rule": a.rule,
           "x1": p.x[0], "x2": p.x[1], "x_min": two(p.x_min), "undercut": list(p.undercut),
           "working_pressure_angle": math.degrees(p.alpha_w), "reference_centre_distance": p.a,
           "centre_distance": p.a_w, "y": p.y, "delta_y": p.delta_y,
           "d": two(p.d), "db": two(p.db), "dw": two(p.dw), "da": two(p.da), "df": two(p.df),
           "p": p.p, "pb": p.pb, "s": two(p.s), "sa": two(p.sa),
           "line_of_action": _finite(p.line), "active_length": p.active, "contact_ratio": p.contact_ratio,
           "specific_sliding": {"wheel1_at_B2": _finite(p.sliding[0]), "wheel2_at_B1": _finite(p.sliding[1])},
           "kind": p.kind, "path_of_approach": p.approach, "path_of_recess": p.recess,
           "path_of_contact": p.active, "arc_of_contact": p.arc, "angle_turned": turned}
    if p.kind == "rack":
        out["rack_travel"] = p.arc
    if a.n1 is not None and a.sliding_velocity is not None:
        out["n1"] = a.n1
        out["sliding_velocity"] = {"engagement": a.sliding_velocity[0], "disengagement": a.sliding_velocity[1]}
    return out


def _finite(v: float) -> float | None:
    """None where a value is not defined: the sliding where the active line reaches past N
    (interference), a rack's diameters and its line N1N2, the x_min of a rack or a ring gear."""
    return float(v) if math.isfinite(v) else None


def _pair_text(v: tuple[float, float], digits: str = ".3f") -> str:
    """Two values "wheel 1/wheel 2"; a rack's infinite one left out."""
    return "/".join(f"{x:{digits}}" for x in v if math.isfinite(x))


def pair_sheets(scene: Scene, a: PairAnalysis, stem: str, style: Style) -> dict[str, str]:
    """The meshing and cutting sheets the scene draws (file name → SVG), of an external pair, an
    internal pair (wheel 2 a ring gear) or a pinion with a rack."""
    p = a.pair
    files: dict[str, str] = {}
    mate = {"external": f"{p.z[1]}", "internal": f"{p.z[1]} (ring gear)", "rack": "rack"}[p.kind]
    given = (f"z = {p.z[0]}/{mate}, m = {p.module:g} mm, α = {math.degrees(p.alpha):g}°, "
             f"x = {p.x[0]:.4g}/{p.x[1]:.4g} ({a.rule.replace('_', ' ')})")
    if "meshing" in scene.draw:
        s = meshing(a)
        centres = "a_w" if p.kind != "rack" else "O_1 to the rack's reference line"
        notes = (f"α_w = {math.degrees(p.alpha_w):.4f}°, {centres} = {p.a_w:.4f} mm, y = {p.y:.5f}, Δy = "
                 f"{p.delta_y:.5f}; d_w = {_pair_text(p.dw)}, d_a = {_pair_text(p.da)}, d_f = {_pair_text(p.df)}, "
                 f"d_b = {_pair_text(p.db)} mm.",
                 f"ε_α = B_1B_2/p_b = {p.active:.4f}/{p.pb:.4f} = {p.contact_ratio:.4f}; approach PB_2 = "
                 f"{p.approach:.4f} mm, recess PB_1 = {p.recess:.4f} mm; specific sliding at B_2 "
                 f"(wheel 1) {_text(p.sliding[0])}, at B_1 (wheel 2) {_text(p.sliding[1])}. s̄: chordal tooth "
                 "thickness on the reference (s̄) and tip (s̄_a) circles" + (" (a rack's: along its lines)."
                                                                           if p.kind == "rack" else "."))
        scales = f"detail {_ratio(s.k)} (μ = {1 / s.k:g} mm/mm); general view 1:{1 / s.k0:g} (μ = {1 / s.k0:g} mm/mm)"
        sheet = {"external": "Involute gear pair in mesh", "internal": "Internal involute pair in mesh",
                 "rack": "Involute pinion and rack in mesh"}[p.kind]
        files[f"{stem}-meshing.svg"] = draw_pair_sheet(
            s, Heading(scene.title, sheet, given), ident="meshing", style=style, notes=notes,
            scales=scales, contact_ratio=p.contact_ratio)
    if "cutting" in scene.draw:
        s = cutting(a)
        under = f"undercut (x < x_min = {p.x_min[0]:.4f})" if p.undercut[0] else \
            f"not undercut (x ≥ x_min = {p.x_min[0]:.4f})"
        notes = (f"Wheel {a.names[0]} ({p.z[0]} teeth) cut by the rack cutter shifted by x·m = {p.x[0] * p.module:.4g} mm "
                 f"from the pitch line (the cutter's tip rounded with ρ = {a.tip_radius:.4g} mm): the wheel is the blank "
                 f"less the cutter rolled over it; it is {under}.",)
        scales = f"{_ratio(s.k)} (μ = {1 / s.k:g} mm/mm)"
        files[f"{stem}-cutting.svg"] = draw_pair_sheet(
            s, Heading(scene.title, f"Generation of wheel {a.names[0]} by the rack cutter", given), ident="cutting", style=style,
            notes=notes, scales=scales)
    return files


def _text(v: float) -> str:
    if not math.isfinite(v):
        return "not defined (interference)"
    if abs(v) >= UNBOUNDED:
        return "unbounded (the other tip passes through N)"
    return f"{v:.3f}"


def _ratio(k: float) -> str:
    """A drawing scale k as written: 2:1 enlarged, 1:100 reduced."""
    return f"{k:g}:1" if k >= 1.0 else f"1:{1.0 / k:g}"
