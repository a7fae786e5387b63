"""Sliding along the guides, and the angles of the links, at every position of a solved motion.

Pure numpy over the positions of a :class:`~plans.kinematics.state.Solution`: nothing here solves
anything, it reads the link states the solver produced.

For each prismatic pair (``slider`` translating along a line fixed in ``guide``):

* ``u`` (N, 2) is the guide's unit direction in the world: the direction the scene gives for
  the slider (``angle`` in degrees, or ``through = [P, Q]`` directed P → Q), fixed in the guide
  and turned with it (on the frame it never turns).
* ``s`` (N,) m, the signed sliding displacement: (X_slider − X_guide)·u, where X_guide is the
  guide's anchor (the guide link's point at the first ``through`` point it carries, else that
  point of the sketch, fixed in the guide) and X_slider the slider's anchor (the same for the
  slider link); both lie on the common line. It is 0 in the sketch when both anchors are the
  same sketch point, as they are unless ``[lengths]`` move one of them; positive when the
  slider stands ahead of the guide's anchor along u.
* ``v`` (N,) m/s, the signed sliding velocity σ = (v_S − v_G)·u: v_S and v_G the velocities of
  the slider's and of the guide's points now at the same place (any place: the two links
  turn together, so their relative velocity is the same everywhere and lies along u). σ =
  ds/dt; positive when the slider moves along +u relative to the guide.
* ``a`` (N,) m/s², σ̇ = dσ/dt = d²s/dt² (u turns, σ u does not only change in length): the
  relative acceleration along the guide, i.e. (a_S − a_G)·u — the coincident points'
  acceleration difference minus the Coriolis term, projected on u (the Coriolis term is ⊥ u).
* ``coriolis`` (N, 2) m/s², 2 ω_guide k × (σ u): the Coriolis acceleration of the slider's
  point relative to the guide's (zero on a guide that does not turn). So
  a_S = a_G + σ̇ u + coriolis at the pair.

``v`` and ``coriolis`` need velocities (``motion.order >= 1``), ``a`` accelerations
(``order == 2``); otherwise they are None.

A link's angle (:func:`link_angles`, degrees CCW from +x, in [0, 360)) is the direction of
its first point → its second point (scene order of ``[links]``): the sketch's direction plus
the link's rotation θ from the sketch, taken modulo one turn (a crank pivoted at its first
point reads the drive's φ modulo 360°). A link with one point (a block) has no such line:
its angle is its rotation from the sketch, θ (0 in the sketch), also in [0, 360). Its rate
is ω = dθ/dt whatever the reference line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .state import J, Solution

__all__ = ["Sliding", "sliding", "link_angles"]


@dataclass(frozen=True)
class Sliding:
    """The sliding of one prismatic pair over N positions (see the module for signs and units).

    ``key`` names the pair as ``"<slider>/<guide>"`` (``"<slider>/<guide>#<index>"`` when a
    scene has two pairs between the same links); ``point`` is the pair's point on plans."""

    key: str
    slider: str
    guide: str
    point: str
    u: np.ndarray
    s: np.ndarray
    v: np.ndarray | None = None
    a: np.ndarray | None = None
    coriolis: np.ndarray | None = None


def sliding(motion: Solution) -> dict[str, Sliding]:
    """Every prismatic pair of the motion's mechanism, in scene order (key → :class:`Sliding`)."""
    mech = motion.mechanism
    pairs = mech.prismatics
    count: dict[tuple[str, str], int] = {}
    for p in pairs:
        count[(p.slider, p.guide)] = count.get((p.slider, p.guide), 0) + 1
    out: dict[str, Sliding] = {}
    for p in pairs:
        key = f"{p.slider}/{p.guide}" + (f"#{p.index}" if count[(p.slider, p.guide)] > 1 else "")
        slider, guide = motion.links[p.slider], motion.links[p.guide]
        u = guide.direction(p.direction)
        x_s = slider.point(p.anchor[p.slider])
        x_g = guide.point(p.anchor[p.guide])
        s = _dot(x_s - x_g, u)
        v = a = cor = None
        if motion.order >= 1:
            v = _dot(slider.velocity(x_s) - guide.velocity(x_s), u)
            cor = 2.0 * guide.omega[:, None] * J(v[:, None] * u)
        if motion.order >= 2:
            a = _dot(slider.acceleration(x_s) - guide.acceleration(x_s), u)
        out[key] = Sliding(key, p.slider, p.guide, p.label, u, s, v, a, cor)
    return out


def link_angles(motion: Solution) -> dict[str, np.ndarray]:
    """Each link's angle at every position, degrees CCW from +x (link name → (N,)): the
    direction of its first → second point, or its rotation from the sketch for a one-point
    link; in [0, 360) (see the module)."""
    mech = motion.mechanism
    out = {}
    for name, state in motion.links.items():
        link = mech.links[name]
        base = 0.0
        if len(link.points) >= 2:
            d = link.local[link.points[1]] - link.local[link.points[0]]
            base = math.degrees(math.atan2(float(d[1]), float(d[0])))
        angle = np.mod(base + np.degrees(state.theta), 360.0)
        out[name] = np.where(angle >= 360.0, 0.0, angle)   # -1e-15 % 360 rounds to 360.0
    return out


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]
