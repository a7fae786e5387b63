"""The instantaneous-centres sheet at one position, as geometry in paper millimetres.

On the scheme, every moving link's absolute centre P_j is marked and joined (dashed) to the
link's points: each segment P_j–X is perpendicular to v_X, and its length × μl is |X P_j|,
which is what makes |v_X| = |ω_j|·|X P_j| readable from the sheet. Each segment is run on
through the pin X to the centre of the link on the other side of the pin, P_k, when that is
finite — the three centres P_j, P_jk = X, P_k lie on one line (Aronhold–Kennedy) — so the
sheet shows how each centre is found: the centre of a rod from the line of the crank and
the line through the base link's centre and the rod's pin (Koshel's variant 1); for a class
III group whose base link's centre cannot be found from two known velocity directions, from
the special points S (the lines through S ⊥ v_S; variant 2). Centres off the sheet or at
infinity are drawn as a direction from the link.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..kinematics.tolerances import REST_RTOL
from ..scene import FRAME
from .plan_builder import PRIME
from .plans import MIN_DRAWN_MM
from .scales import fitting_scale
from .scheme import Scheme, scheme
from .. import linalg as la

__all__ = ["CentreMark", "CentreRay", "CentresSheet", "centres_sheet", "centre_label", "rest_note", "REACH"]

#: Centres further than REACH mechanism sizes from the mechanism are drawn as directions.
REACH = 1.5
#: The sheet's drawing area (mm): the scheme plus every centre within reach.
SHEET_MM = (220.0, 170.0)
#: How far a construction line runs past the last point it joins, mm.
OVERRUN_MM = 8.0


@dataclass(frozen=True)
class CentreMark:
    """A centre: ``xy`` on the sheet (mm), or None and ``direction`` (unit) drawn from
    ``anchor`` when it is at infinity (``infinite``) or off the sheet."""

    name: str
    link: str
    xy: tuple[float, float] | None
    direction: tuple[float, float] | None
    anchor: tuple[float, float]
    infinite: bool


@dataclass(frozen=True)
class CentreRay:
    """A measured segment from centre ``name`` to scene point ``point``: its value is the
    distance |X P| in metres (drawn length × μl)."""

    quantity: str
    start: tuple[float, float]
    end: tuple[float, float]
    value: float


@dataclass(frozen=True)
class CentresSheet:
    """The scheme, the centres, the measured rays, the dashed construction lines and the
    special points of class III groups (name → mm) at one position; ``resting``: the moving
    links at rest there (to ``REST_RTOL`` of the mechanism's speed), which have no centre, and
    ``notes`` the lines the sheet writes about them (:func:`rest_note`)."""

    scheme: Scheme
    mu_l: float
    marks: tuple[CentreMark, ...]
    rays: tuple[CentreRay, ...]
    lines: tuple[tuple[tuple[float, float], tuple[float, float]], ...]
    special: tuple[tuple[str, tuple[float, float]], ...]
    resting: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


def _xy(v) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def _segment(points: list[np.ndarray]) -> tuple[tuple[float, float], tuple[float, float]]:
    """The segment covering collinear ``points`` (mm), run on by OVERRUN_MM at both ends."""
    pts = np.array(points)
    u = pts[-1] - pts[0]
    u = u / (la.norm(u) or 1.0)
    t = la.matmul(pts - pts[0], u)
    return _xy(pts[0] + (t.min() - OVERRUN_MM) * u), _xy(pts[0] + (t.max() + OVERRUN_MM) * u)


def centres_sheet(motion: Motion, i: int) -> CentresSheet:
    """The centres sheet at position ``i``: the motion's centres (:attr:`~plans.kinematics.Motion.centres`)."""
    mech = motion.mechanism
    ic = motion.centres
    world = {p: motion.position(p)[i] for p in mech.sketch}
    pts = np.array(list(world.values()))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    middle, size = (lo + hi) / 2.0, float(np.hypot(*(hi - lo))) or mech.size
    near = {}
    for name, c in ic.absolute.items():
        p = c.point[i]
        if not np.isnan(p[0]) and la.norm(p - middle) <= REACH * size:
            near[name] = p
    specials = _special_points(motion, i)
    reach = [v for v in specials.values() if la.norm(v[0] - middle) <= REACH * size]
    travel = [motion.position(p) for p in mech.sketch]   # every position: the scheme's guides cover the travel
    every = np.concatenate([np.concatenate(travel), np.array(list(near.values()) + [r[0] for r in reach]).reshape(-1, 2)])
    ext = every.max(axis=0) - every.min(axis=0)
    mu = max(fitting_scale(float(ext[0]) or size, SHEET_MM[0]), fitting_scale(float(ext[1]) or size, SHEET_MM[1]))
    sch = scheme(motion, i, mu)
    marks, rays, lines = [], [], []
    for name, c in ic.absolute.items():
        link_pts = [p for p in mech.links[name].points if p in world]
        anchor = np.mean([world[p] for p in link_pts], axis=0) / mu
        label = centre_label(mech, name)
        if name in near:
            marks.append(CentreMark(label, name, _xy(near[name] / mu), None, _xy(anchor), False))
            for p in link_pts:
                x = world[p]
                if la.norm(x - near[name]) / mu < 1e-9:
                    continue   # the centre is this point (a pivot on the frame)
                rays.append(CentreRay(f"r:{p}/{label}", _xy(near[name] / mu), _xy(x / mu),
                                      float(la.norm(x - near[name]))))
                through = [near[name] / mu, x / mu]
                other = _neighbour_centre(mech, name, p, near)
                if other is not None:
                    through.append(other / mu)
                lines.append(_segment(through))
            continue
        if c.at_rest(i):
            continue   # a link at rest: no centre to show (the sheet says so)
        infinite = np.isnan(c.point[i][0])
        if infinite:
            d = c.direction[i]
            if not np.any(d):
                continue   # no direction either (cannot happen off rest; kept as a guard)
        else:
            d = (c.point[i] - anchor * mu) / la.norm(c.point[i] - anchor * mu)
        marks.append(CentreMark(label, name, None, _xy(d), _xy(anchor), bool(infinite)))
    special_marks = []
    for label, (s, v) in specials.items():
        if la.norm(s - middle) > REACH * size:
            continue
        special_marks.append((label.split(":")[0], _xy(s / mu)))
        base = _base_of(motion, label)
        centre = near.get(base)
        # S–P_base ⊥ v_S, unless S is the centre itself (v_S = 0 up to rounding)
        if centre is not None and la.norm(s - centre) / mu > MIN_DRAWN_MM:
            lines.append(_segment([s / mu, centre / mu]))
    resting = tuple(name for name, c in ic.absolute.items() if c.at_rest(i))
    notes = (rest_note(resting, float(motion.rate_scale(1)[i])),) if resting else ()
    return CentresSheet(sch, mu, tuple(marks), tuple(rays), tuple(lines), tuple(special_marks), resting, notes)


def _exponent(x: float) -> str:
    """1e-9 as written on a sheet (not 1e-09)."""
    mantissa, _, power = f"{x:.0e}".partition("e")
    return f"{mantissa}e{int(power)}"


def centre_label(mech, link: str) -> str:
    """The name of link ``link``'s centre on a sheet and in its measured segments ``r:X/P…``:
    ``P<link>``, primed (P3′, P3″ …) while a scene point has that name, so that the centre
    is never taken for a point (a point named P3 beside the centre of link 3)."""
    name = f"P{link}"
    while name in mech.sketch:
        name += PRIME
    return name


def rest_note(resting: tuple[str, ...], speed: float) -> str:
    """What the sheet says of the links at rest; ``speed``: that of the mechanism's fastest
    point (m/s)."""
    names = resting[0] if len(resting) == 1 else f"{', '.join(resting[:-1])} and {resting[-1]}"
    which = f"Link {names} is" if len(resting) == 1 else f"Links {names} are"
    they = "it has" if len(resting) == 1 else "they have"
    if speed == 0.0:
        return f"{which} at rest at this position (the whole mechanism stands), so {they} no instantaneous centre."
    return (f"{which} at rest at this position: ω and every v are zero to rounding (at most {_exponent(REST_RTOL)} "
            f"of the fastest point's speed, {speed:.3g} m/s), so {they} no instantaneous centre.")


def _neighbour_centre(mech, link: str, point: str, near: dict[str, np.ndarray]) -> np.ndarray | None:
    """The absolute centre of another link pinned to ``link`` at ``point`` (the frame's
    pivot itself when that link is the frame), if it is on the sheet."""
    for name, l in mech.links.items():
        if name == link or point not in l.local:
            continue
        if name == FRAME:
            return None
        if name in near:
            return near[name]
    return None


def _special_points(motion: Motion, i: int) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The special points of every class III group at position i, as the motion gives them:
    label ``S1:<base link>`` → (S m, v_S m/s as a point of the base link)."""
    out = {}
    for found in motion.special_points.values():
        for p in found.points:
            if abs(float(p.sin[i])) < 1e-9:
                continue
            out[f"{p.name}:{found.group.base}"] = (p.position[i], p.v[i])
    return out


def _base_of(motion: Motion, label: str) -> str:
    return label.split(":")[1]
