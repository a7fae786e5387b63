"""Laws in the crank angle of a linkage's dynamics: the driving moment (``[dynamics] driving``) and
the loads' couples (``[[moments]] law``), written as ``[turning]`` writes a torque (a table,
harmonics, shapes: :func:`plans.scene.turning.read_torque`) and evaluated as :mod:`.turning`
evaluates it, against θ, the crank's turned angle in degrees from the cycle's first position
(0 … ``[dynamics] period``, growing in the crank's sense of rotation).

The machine's quadrature (:mod:`.machine`: 8 Gauss nodes a panel) is exact to ~1e-13 when every
point where a law kinks or jumps is a panel edge (:func:`law_edges`: table rows, shape ends and
apexes, semicircle centres), when the panels are short enough for the highest harmonic
(:func:`panel_deg`: k·Δθ ≤ 20°, whose degree-7 fit is within 5e-13 of a sine, its integral exact), and near a
semicircle's ends, where p·√(1 − u²) has an infinite slope, when the panels halve towards the end
(each panel's distance from the end is its width: the square root is then analytic in an ellipse
of ρ = 2 + √5 about it, and Gauss's error is ρ^−16 ≈ 1e-10 of that panel's own small part) down
to :data:`GRADE_DEG`, whose last panel holds ~1e-15 of the peak's work.

:func:`balanced` refuses a driving law whose work does not balance the loads'; :func:`check_laws`
what the laws and cycles of several turns cannot do yet.
"""

from __future__ import annotations

import functools

import numpy as np

from ..errors import SceneError
from ..scene import Scene
from ..scene.turning import Torque
from ..scene.values import DriveKind
from .piecewise import Piecewise
from .turning import STEADY_RTOL, _curve, _Pieces      # [turning]'s evaluator: one reading of a torque

__all__ = ["torque_at", "law_edges", "panel_deg", "law_values", "check_laws", "laws_of", "balanced", "GRADE_DEG",
           "SHEET_POSITIONS"]

#: The narrowest panel at a semicircle's end, degrees (2^-26°: wider than the 1e-12 rad the
#: machine merges edges within).
GRADE_DEG = 2.0 ** -26
#: A harmonic of order k gets panels of at most this many degrees / k.
PHASE_DEG = 20.0
#: Most positions over a cycle of several turns on the dynamics sheet: its φ axis (190 mm) numbers
#: them 5.3 mm apart, and its Wittenbauer curve labels each (48 crowd it: labels cross its lines).
SHEET_POSITIONS = 36


@functools.lru_cache(maxsize=64)
def _pieces(torque: Torque, period: float) -> _Pieces:
    return _Pieces(_curve(torque), np.array(sorted(_breaks(torque) | {0.0, period})))


def _breaks(torque: Torque) -> set[float]:
    """Where ``torque`` kinks or jumps (deg), as :func:`.turning.analyse_turning` takes them."""
    out = {x for x, _ in torque.table}
    for s in torque.shapes:
        out.update((s.start, s.end, 0.5 * (s.start + s.end)) if s.kind == "semicircle" else
                   (s.start, s.end) + ((s.apex,) if s.apex is not None else ()))
    return out


def torque_at(torque: Torque, period: float, theta: np.ndarray) -> np.ndarray:
    """``torque`` (N·m) at θ (``theta`` in degrees, 0 … ``period``); at a jump, the value after it."""
    return _pieces(torque, period).value(np.asarray(theta, dtype=float))


def laws_of(scene: Scene) -> list[Torque]:
    """The laws in the crank angle of ``scene``: the driving law, then the moments' laws."""
    dyn = scene.dynamics
    out = [dyn.torque] if dyn is not None and dyn.torque is not None else []
    return out + [m.law for m in scene.moments if m.law is not None]


def law_edges(scene: Scene) -> np.ndarray:
    """Panel edges (rad, in [0, period]) the laws need: every break, and at each semicircle's
    ends panels halving towards them from 1° to :data:`GRADE_DEG`."""
    out: set[float] = set()
    grade = 2.0 ** -np.arange(0, int(round(-np.log2(GRADE_DEG))) + 1)
    for law in laws_of(scene):
        out |= _breaks(law)
        for s in law.shapes:
            if s.kind == "semicircle":
                half = 0.5 * (s.end - s.start)
                out.update(float(s.start + g) for g in grade if g < half)
                out.update(float(s.end - g) for g in grade if g < half)
    return np.radians(np.array(sorted(out))) if out else np.array([])


def panel_deg(scene: Scene, longest: float) -> float:
    """The longest panel (deg): ``longest``, or shorter for the laws' highest harmonic."""
    orders = [k for law in laws_of(scene) for _, k, _ in law.harmonics]
    return min([longest] + [PHASE_DEG / k for k in orders])


def law_values(scene: Scene, theta: np.ndarray) -> dict[int, np.ndarray]:
    """Each moment with a law (its index in ``[[moments]]`` → N·m, CCW positive) at ``theta``
    (rad, the crank's turned angle from the cycle's first position, 0 … the period)."""
    deg = np.degrees(np.asarray(theta, dtype=float))
    return {m.index: torque_at(m.law, scene.dynamics.period, deg) for m in scene.moments if m.law is not None}


def check_laws(scene: Scene) -> None:
    """What the laws in the crank angle and a cycle of several turns cannot do yet, refused in one
    line: a law or a longer cycle on a drive that is not a crank; a moment's law with the force
    analysis over a cycle of several turns (a crank position is at several angles of the cycle);
    the dynamics sheet
    over a cycle of several turns with more than :data:`SHEET_POSITIONS` positions in it."""
    dyn = scene.dynamics
    moment = next((m for m in scene.moments if m.law is not None), None)
    key = "dynamics.driving" if dyn.torque is not None else f"moments[{moment.index}].law" if moment is not None \
        else "dynamics.period" if dyn.period != 360.0 else None
    if key is None:
        return
    if scene.drive.kind != DriveKind.ROTARY:
        raise SceneError(f"a law in the crank angle and a cycle of several turns need a crank (a rotary drive); link "
                         f"{scene.drive.link} is a {scene.drive.kind.value} drive", key=key)
    turns = round(dyn.period / 360.0)
    if moment is not None and scene.wants_forces and turns > 1:
        raise SceneError(f"over a cycle of {turns} turns a position of the crank is at {turns} angles of the cycle, "
                         "where a moment's law differs: the force plans, the lever and [balance] take a law over one "
                         'turn (period = 360); give value, or remove "forces" and "lever" from draw and [balance]',
                         key=f"moments[{moment.index}].law")
    if "dynamics" in scene.draw and turns > 1 and scene.cycle is not None \
            and scene.cycle.positions * turns > SHEET_POSITIONS:
        raise SceneError(f"the dynamics sheet numbers the cycle's {scene.cycle.positions} × {turns} positions along "
                         f"its φ axis and on Wittenbauer's curve: at most {SHEET_POSITIONS} over a cycle of several "
                         f"turns; give positions = {SHEET_POSITIONS // turns} or fewer, or remove \"dynamics\" from draw",
                         key="drive.positions")


def balanced(driving: Piecewise, moment: Piecewise, size: float, span: float) -> float:
    """The driving law's mean (N·m) when its work over the cycle balances the loads' (within
    :data:`~.turning.STEADY_RTOL` of the larger, or of ``size`` × the cycle: the largest moments);
    otherwise refused in one line with the two works and the factor on the law that balances them."""
    w_d, w_l = driving.total(), moment.total()
    if not w_d > 0.0:
        raise SceneError(f"the driving law does {w_d:.6g} J over the cycle: it must drive (its mean "
                         f"{w_d / span:.6g} N·m is not positive in the crank's sense of rotation)", key="dynamics.driving")
    if abs(w_d + w_l) <= STEADY_RTOL * max(w_d, abs(w_l), size * span):
        return w_d / span
    if not w_l < 0.0:
        raise SceneError(f"the loads do {w_l:+.6g} J over the cycle (they drive too, or do nothing), and the driving "
                         f"law {w_d:.9g} J: nothing takes their work (is the crank's sense of rotation the one meant?); "
                         "give driving = \"constant\" (the loads' mean)", key="dynamics.driving")
    raise SceneError(f"the driving law does {w_d:.9g} J over the cycle and the loads take {-w_l:.9g} J: the flywheel "
                     f"would gain or lose energy every cycle; scale the law by {-w_l / w_d:.12g} to balance them (or "
                     f"give driving = \"constant\", the loads' mean)", key="dynamics.driving")

