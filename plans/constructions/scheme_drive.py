"""The scheme's drives as geometry in paper millimetres (y up): hydraulic cylinders drawn as a
barrel with a piston and a piston rod, and the input arrows of a linear drive (its speed v and,
when it is not zero, its acceleration a along the guide).

A cylinder is a prismatic pair between two bars lying on the pair's line: the guide bar (the
barrel, its ``pivot`` the one of its two points pinned to another link, the other its mouth)
and the sliding bar (the piston rod, its ``pin`` pinned to another link, the other its piston
head). The barrel runs from its pivot along the axis towards the rod's pin; its length is fixed
for the whole motion (the pivot–mouth distance, shortened or lengthened just enough that at
every analysed position the pin stays outside, so the rod always shows, and, when the strokes
allow it, the piston inside; where they do not, the piston is drawn at the barrel's mouth).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..scene import FRAME, DriveKind
from .. import linalg as la

__all__ = ["Cylinder", "DriveArrow", "cylinders", "drive_arrows", "BARREL_MM", "PISTON_ROOM_MM", "PIN_ROOM_MM"]

#: Width of a cylinder's barrel across its axis, mm.
BARREL_MM = 5.0
#: Least distance from the piston to either end of the barrel, mm.
PISTON_ROOM_MM = 1.5
#: Least distance from the barrel's mouth to the rod's pin (when the strokes allow it), mm.
PIN_ROOM_MM = 3.0
#: Length of the barrel's eye at the pivot (a bar from the pivot to the barrel's bottom), mm.
EYE_MM = 2.5
#: A point this close to a cylinder's axis (mm) lies on it.
ON_AXIS_MM = 1e-3
#: Input arrow of a linear drive: length, head, gap from the block or barrel and between arrows, mm.
ARROW_MM = 12.0
ARROW_HEAD_MM = 3.0
ARROW_GAP_MM = 3.0
ARROW_STEP_MM = 4.5

Point = tuple[float, float]


@dataclass(frozen=True)
class Cylinder:
    """A hydraulic cylinder at one position: ``barrel`` (closed rectangle, four corners),
    ``piston`` (a bar across inside the barrel at the piston head, or by the mouth where the
    head has left the barrel: see :func:`_barrel_length`), ``rod`` (from the piston's
    centre to the rod's pin) and ``eye`` (from the pivot to the barrel's bottom; None when the
    barrel starts at the pivot). ``axis`` is the unit direction pivot → pin."""

    barrel_link: str
    rod_link: str
    pivot: str
    pin: str
    head: str
    pair: str
    barrel: tuple[Point, Point, Point, Point]
    piston: tuple[Point, Point]
    rod: tuple[Point, Point]
    eye: tuple[Point, Point] | None
    axis: Point


@dataclass(frozen=True)
class DriveArrow:
    """An input arrow of a linear drive from ``start`` to ``end`` (mm; the head at ``end``):
    ``kind`` "v" (its speed) or "a" (its acceleration), labelled ``label`` (label markup)."""

    kind: str
    link: str
    start: Point
    end: Point
    label: str


def _xy(v) -> Point:
    return (float(v[0]), float(v[1]))


def _joints(motion: Motion) -> set[str]:
    mech = motion.mechanism
    return {p for p in mech.sketch if sum(p in link.local for link in mech.links.values()) > 1}


def _ends(points: tuple[str, ...], joints: set[str]) -> tuple[str, str] | None:
    """(the pinned point, the free one) of a bar, or None unless exactly one is pinned."""
    if len(points) != 2:
        return None
    pinned = [p for p in points if p in joints]
    if len(pinned) != 1:
        return None
    return pinned[0], next(p for p in points if p != pinned[0])


def cylinders(motion: Motion, i: int, mu_l: float) -> tuple[Cylinder, ...]:
    """The hydraulic cylinders of the mechanism at position ``i`` (``mu_l`` in m/mm)."""
    mech = motion.mechanism
    joints = _joints(motion)
    out = []
    for pr in mech.prismatics:
        if FRAME in (pr.guide, pr.slider):
            continue
        body, rod = _ends(mech.links[pr.guide].points, joints), _ends(mech.links[pr.slider].points, joints)
        if body is None or rod is None:
            continue
        (pivot, mouth), (pin, head) = body, rod
        at = {p: motion.position(p) / mu_l for p in (pivot, mouth, pin, head)}    # (N, 2) mm
        u_all = at[pin] - at[pivot]
        lengths = la.norm(u_all, axis=1)
        if np.any(lengths < 1e-9):
            continue
        u_all = u_all / lengths[:, None]

        def along(p: str) -> np.ndarray:
            return np.einsum("ij,ij->i", at[p] - at[pivot], u_all)

        def across(p: str) -> np.ndarray:
            d = at[p] - at[pivot]
            return np.abs(u_all[:, 0] * d[:, 1] - u_all[:, 1] * d[:, 0])

        if max(float(np.max(across(p))) for p in (mouth, head)) > ON_AXIS_MM:
            continue
        t_head, t_pin = along(head), along(pin)
        bottom = min(EYE_MM, max(float(np.min(t_head)) - PISTON_ROOM_MM, 0.0))
        length = _barrel_length(float(np.mean(along(mouth))), t_head, t_pin, bottom)
        c, u = np.asarray(at[pivot][i]), u_all[i]
        n = np.array([-u[1], u[0]])
        w = BARREL_MM / 2
        barrel = tuple(_xy(c + t * u + s * w * n) for t, s in ((bottom, -1), (length, -1), (length, 1), (bottom, 1)))
        # the piston at its head; where the head has left the barrel (a stroke longer than the
        # rod), at the mouth: a piston never leaves its barrel
        h = c + min(float(t_head[i]), length - PISTON_ROOM_MM) * u
        piston = (_xy(h - 0.8 * w * n), _xy(h + 0.8 * w * n))
        out.append(Cylinder(pr.guide, pr.slider, pivot, pin, head, pr.label, barrel, piston,
                            (_xy(h), _xy(at[pin][i])), (_xy(c), _xy(c + bottom * u)) if bottom > 0 else None, _xy(u)))
    return tuple(out)


def _barrel_length(mouth: float, t_head: np.ndarray, t_pin: np.ndarray, bottom: float) -> float:
    """The barrel's length from its pivot (mm), one for every position: the pivot–mouth distance
    ``mouth``, shortened or lengthened just enough that at every position the rod's pin (at
    ``t_pin`` from the pivot) stays PIN_ROOM_MM outside it, so the rod always shows, and, when
    the strokes allow it, the piston head (``t_head``) PISTON_ROOM_MM inside. The pin comes
    first: a stroke longer than the rod leaves the head outside at the longest positions, and
    the piston is drawn at the mouth there. Never shorter than the piston needs past the
    barrel's ``bottom``."""
    lo = float(np.max(t_head)) + PISTON_ROOM_MM
    hi = float(np.min(t_pin)) - PIN_ROOM_MM
    length = min(max(mouth, lo), hi)
    return max(length, bottom + 2.0 * PISTON_ROOM_MM)


def clearance(samples: np.ndarray, segments: np.ndarray) -> float:
    """The least distance (mm) from any of ``samples`` (k, 2) to any segment of ``segments``
    (m, 2, 2); infinite without segments."""
    if len(segments) == 0 or len(samples) == 0:
        return math.inf
    a, b = segments[:, 0][None], segments[:, 1][None]
    p = samples[:, None]
    ab = b - a
    t = np.clip(np.einsum("ijk,ijk->ij", p - a, ab) / np.maximum(np.einsum("ijk,ijk->ij", ab, ab), 1e-12), 0.0, 1.0)
    return float(np.min(la.norm(p - (a + t[..., None] * ab), axis=-1)))


def drive_arrows(motion: Motion, i: int, mu_l: float, block: tuple[Point, float] | None,
                 cyls: tuple[Cylinder, ...], segments: np.ndarray) -> tuple[DriveArrow, ...]:
    """The input arrows of a linear drive at position ``i``: v (and a, when not zero) along the
    guide in their senses, beside the driven block (``block``: its centre and half width across
    the guide, mm; on the side away from the frame guide's hatching) or beside the rod of the
    driven cylinder, on the side farther from the scheme's other lines (``segments``, mm)."""
    mech = motion.mechanism
    d = mech.drive
    if d.kind not in (DriveKind.LINEAR, DriveKind.CYLINDER) or d.guide is None:
        return ()
    pr = d.guide
    u = motion.links[pr.guide].direction(pr.direction)[i]
    u = u / la.norm(u)
    n = np.array([-u[1], u[0]])
    cyl = next((c for c in cyls if c.rod_link == d.link and c.barrel_link == pr.guide), None)
    if cyl is not None:
        a, b = np.asarray(cyl.barrel[1]), np.asarray(cyl.rod[1])
        t_mouth, t_pin = float(la.dot(a - cyl.rod[0], u)), float(la.dot(b - cyl.rod[0], u))
        mid = np.asarray(cyl.rod[0]) + 0.5 * (t_mouth + t_pin) * u
        base, sides = BARREL_MM / 2 + ARROW_GAP_MM, (1.0, -1.0)
    elif block is not None:
        mid = np.asarray(block[0])
        base, sides = block[1] + ARROW_GAP_MM, (1.0,)    # the hatching is on the other side
    else:
        mid = motion.position(pr.label)[i] / mu_l
        base, sides = ARROW_GAP_MM, (1.0,)
    # the side and shift along the guide (none first) that keep the arrows farthest from other lines
    best = None
    for shift in (0.0, ARROW_MM / 2, -ARROW_MM / 2):
        for side in sides:
            c = mid + shift * u + side * (base + ARROW_STEP_MM / 2) * n
            pts = c + np.linspace(-ARROW_MM / 2 - 2.0, ARROW_MM / 2 + 2.0, 9)[:, None] * u
            room = min(clearance(pts, segments), ARROW_STEP_MM / 2 + 2.5)   # enough room is enough
            if best is None or room > best[0] + 1e-9:
                best = (room, shift, side)
    _, shift, side = best
    mid = mid + shift * u
    sub = f"_{{{d.link}{pr.guide}}}" if d.kind == DriveKind.CYLINDER else f"_{{{d.link}}}"
    rates = motion.drive_rates(i)
    out, off = [], base
    for kind, value in (("v", rates[0]), ("a", rates[1])):
        if value == 0.0:
            continue
        s = math.copysign(1.0, value)
        centre = mid + side * off * n
        out.append(DriveArrow(kind, d.link, _xy(centre - s * ARROW_MM / 2 * u), _xy(centre + s * ARROW_MM / 2 * u),
                              kind + sub))
        off += ARROW_STEP_MM
    return tuple(out)
