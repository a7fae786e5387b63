"""A flywheel problem alone (``[turning]`` and/or ``[operation]`` with ``[flywheel]``, no
``[points]``): its analysis, the JSON report and, when ``[plans] draw`` has ``"turning"``, the
turning-moment sheet (drawn by :mod:`.sheets.turning`, imported only then)."""

from __future__ import annotations

from typing import Any

from ..drawing import Style
from ..dynamics.turning import OperationAnalysis, TurningAnalysis, analyse_operation, analyse_turning
from ..errors import PlansError
from ..scene import Scene
from .json_report import report_text
from .result import Rendered

__all__ = ["render_flywheel", "turning_report", "rim_report", "operation_report"]


def turning_report(a: TurningAnalysis) -> dict[str, Any]:
    """The JSON ``turning`` (SI units, angles in degrees of the cycle from 0°): ``mean_torque`` (N·m),
    ``power`` (W), ``work_per_cycle`` (J), ``energy_fluctuation`` ΔE (J: the greatest minus the least
    of ∫(T − T_res) dθ), ``energy_coefficient`` (ΔE / work per cycle), ``delta``, ``inertia``
    (kg·m²), ``mass`` (kg, J/k² when [flywheel] gives the radius k), null when not known;
    ``speed_extremes`` {``max_at``, ``min_at``}; ``areas`` (J, signed, between 0°, the successive
    crossings of T and T_res and the period); ``acceleration`` (each ``at`` angle as written →
    (T − T_res)/J, rad/s²)."""
    return {"mean_torque": a.mean_torque, "power": a.power, "work_per_cycle": a.work_per_cycle,
            "energy_fluctuation": a.energy_fluctuation, "energy_coefficient": a.energy_coefficient,
            "delta": a.delta, "inertia": a.inertia, "mass": a.mass,
            "speed_extremes": {"max_at": a.energy_max_at, "min_at": a.energy_min_at},
            "areas": [float(x) for x in a.areas],
            "acceleration": {label: alpha for label, _, alpha in a.acceleration}}


def rim_report(a: TurningAnalysis) -> dict[str, float] | None:
    """The JSON ``flywheel.rim``: ``diameter`` (mean), ``width``, ``thickness`` (m), ``mass`` (kg)."""
    r = a.rim
    return None if r is None else {"diameter": r.diameter, "width": r.width, "thickness": r.thickness, "mass": r.mass}


def operation_report(o: OperationAnalysis) -> dict[str, Any]:
    """The JSON ``operation``: the motor's ``power`` (W), the flywheel's ``rpm_after`` the operation,
    the operations ``per_minute`` and the flywheel's ``mass`` (kg), null when not known."""
    return {"power": o.power, "rpm_after": o.rpm_after, "per_minute": o.per_minute, "mass": o.mass}


def render_flywheel(scene: Scene, *, stem: str, style: Style, where: str | None = None) -> Rendered:
    """The files of a flywheel problem alone: ``<stem>.json`` and, when drawn, the turning sheet."""
    turning = operation = None
    try:
        if scene.turning is not None:
            turning = analyse_turning(scene.turning, scene.flywheel)
        if scene.operation is not None:
            operation = analyse_operation(scene.operation, scene.flywheel)
    except PlansError as exc:
        raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
    files: dict[str, str] = {}
    if "turning" in scene.draw:
        from .sheets.turning import turning_sheets   # here: a scene that does not draw it never imports it
        files.update(turning_sheets(scene, turning, stem, style))
    data: dict[str, Any] = {"title": scene.title}
    if turning is not None:
        data["turning"] = turning_report(turning)
        if turning.rim is not None:
            data["flywheel"] = {"rim": rim_report(turning)}
    if operation is not None:
        data["operation"] = operation_report(operation)
    files[f"{stem}.json"] = report_text(data)
    return Rendered(stem, files, None, None, (), None, None)
