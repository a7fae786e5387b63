"""A scene of a rotor alone (``[rotor]``, no ``[points]``): its balancing (one plane: static; two:
dynamic), the JSON report and, when ``[plans] draw`` has ``"balancing"``, its sheet (drawn by
:mod:`.sheets.balancing`, imported only then)."""

from __future__ import annotations

from typing import Any

from ..drawing import Style
from ..dynamics.balancing import RotorBalance, balance_rotor
from ..errors import PlansError
from ..scene import Scene
from .json_report import report_text
from .result import Rendered

__all__ = ["render_rotor", "rotor_report"]


def _xy(z: complex) -> list[float]:
    return [z.real, z.imag]


def rotor_report(a: RotorBalance) -> dict[str, Any]:
    """The JSON ``rotor`` (SI units, angles in degrees counter-clockwise from the reference angle 0):
    ``kind`` "static" (one plane) or "dynamic" (two); ``reference_plane`` (m, the first balancing
    plane: every l and couple is taken about it); ``rpm`` and ``omega`` (rad/s), null when not
    given; ``masses`` as given with ``l`` (m from the reference plane), ``mr`` |m·r| (kg·m),
    ``mrl`` |m·r·l| (kg·m²) and their vectors ``mr_xy``, ``mrl_xy`` ([x, y]: x along angle 0);
    ``balancing``, one a plane: ``plane`` (m, as given), ``mass`` (kg), ``angle`` (degrees in
    [0, 360)), ``mr`` (kg·m); ``unbalanced`` before balancing, null without rpm: ``force``
    ω²·|Σ m·r| (N) and ``couple`` ω²·|Σ m·r·l| about the reference plane (N·m); ``residual``
    after balancing, from the balancing masses as reported: ``mr`` |Σ m·r| (kg·m) and ``mrl``
    |Σ m·r·l| (kg·m²), about 0 in two planes — in one plane ``mrl`` is the couple that stays —
    and with rpm ``force`` (N) and ``couple`` (N·m), ω² times them."""
    masses = [{"mass": m.mass, "radius": m.radius, "angle": m.angle, "plane": m.plane, "l": m.l,
               "mr": abs(m.mr), "mrl": abs(m.mrl), "mr_xy": _xy(m.mr), "mrl_xy": _xy(m.mrl)} for m in a.masses]
    balancing = [{"plane": b.plane, "mass": b.mass, "angle": b.angle, "mr": b.mass * b.radius} for b in a.balancing]
    residual: dict[str, float] = {"mr": abs(a.residual_mr), "mrl": abs(a.residual_mrl)}
    unbalanced = None
    if a.omega is not None:
        w2 = a.omega ** 2
        unbalanced = {"force": a.unbalanced_force, "couple": a.unbalanced_couple}
        residual.update(force=w2 * residual["mr"], couple=w2 * residual["mrl"])
    return {"kind": "dynamic" if a.dynamic else "static", "reference_plane": a.reference_plane, "rpm": a.rpm,
            "omega": a.omega, "masses": masses, "balancing": balancing, "unbalanced": unbalanced,
            "residual": residual}


def render_rotor(scene: Scene, *, stem: str, style: Style, where: str | None = None) -> Rendered:
    """The files of a rotor alone: ``<stem>.json`` and, when drawn, the balancing sheet."""
    try:
        analysis = balance_rotor(scene.rotor)
    except PlansError as exc:
        raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
    files: dict[str, str] = {}
    if "balancing" in scene.draw:
        from .sheets.balancing import balancing_sheets   # here: a scene that does not draw it never imports it
        files.update(balancing_sheets(scene, analysis, stem, style))
    files[f"{stem}.json"] = report_text({"title": scene.title, "rotor": rotor_report(analysis)})
    return Rendered(stem, files, None, None, (), None, None)
