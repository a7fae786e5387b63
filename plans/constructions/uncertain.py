"""Koshel's velocity plan of a class III group in an "uncertain scale": an arbitrary first
vector from the base link's instantaneous centre, the scale found from a rod's outer pin.

Reads :class:`~plans.kinematics.Motion` only; must not import the plan assembly
(:mod:`.plans`).
"""

from __future__ import annotations

import numpy as np

from ..errors import ConstructionError
from ..kinematics import Motion
from ..kinematics.state import J
from ..scene import FRAME
from ..structure import ComplexGroup
from .plan_builder import _Builder
from .plan_values import Plan
from .. import linalg as la

__all__ = ["uncertain_plan", "UNCERTAIN_MM", "AT_REST"]


#: Length of the arbitrary first vector of Koshel's uncertain-scale plan, mm.
UNCERTAIN_MM = 60.0
#: A group whose base pin moves slower than this fraction of its driving pin's speed is at rest
#: for Koshel's construction (its velocities are then rounding noise, ~1e-16 of the driver's),
#: and a base link with |ω|·size below this fraction of its pin's speed translates.
AT_REST = 1e-9


def uncertain_plan(motion: Motion, i: int, g: ComplexGroup) -> Plan | None:
    """Koshel's velocity plan of a class III group in an "uncertain scale", at position i.

    The base link's centre P being known (found on the scheme), the velocity of the pin X of
    the rod driven from a known moving link is drawn first, of arbitrary length UNCERTAIN_MM,
    ⊥ PX. The rod's outer pin Y follows from two directions (⊥ XY through x, the known
    direction of v_Y through p), which fixes the scale K_V = V_Y / py; the base link's other
    pins follow by the similarity proportion |pc| = |px|·PC/PX, ⊥ PC. Returns None when the
    construction does not apply to the group (no rod pinned to a moving known link); raises
    :class:`~plans.errors.ConstructionError` at a position where it degenerates: the group
    momentarily at rest (every image at the pole: no segment to draw, no scale to find), or
    the base link translating (its centre P at infinity)."""
    mech = motion.mechanism
    rods = [r for r in g.rods if r.form == "RR" and r.outer.b != FRAME]
    if not rods:
        return None
    rod = rods[0]
    x_name, y_name, known = rod.inner.point, rod.outer.point, rod.outer.b
    v_x = motion.velocity(x_name, g.base)[i]
    v_y = motion.velocity(y_name, known)[i]
    omega = float(motion.links[g.base].omega[i])
    if la.norm(v_x) <= AT_REST * la.norm(v_y):
        raise ConstructionError(f"group {g.name} is momentarily at rest (|v_{x_name}| = {la.norm(v_x):.1e} m/s "
                                f"while |v_{y_name}| = {la.norm(v_y):.3g} m/s): every image of the group is "
                                "at the pole, so Koshel's arbitrary segment has nothing to scale")
    if abs(omega) * mech.size <= AT_REST * float(la.norm(v_x)):
        raise ConstructionError(f"base link {g.base} of group {g.name} translates at this position (ω{g.base} = "
                                f"{omega:.1e} rad/s): its instantaneous centre is at infinity, so Koshel's "
                                "construction from it does not apply")
    centre = motion.centre_from(g.base, x_name, i)     # P of the base link (ω ≠ 0 here)
    b = _Builder(motion, i, float(la.norm(v_x)) / UNCERTAIN_MM, "velocity")
    pole = b.put(("pole",), "p", (0.0, 0.0))
    x_img = b.image(x_name, g.base)
    b.line(pole, J(motion.position(x_name)[i] - centre), [x_img], f"v:{x_name}", f"{g.name}:P")
    b.vector(f"v:{x_name}", pole, x_img, float(la.norm(v_x)), "absolute")
    y_img = b.image(y_name, known)
    r = motion.position(y_name)[i] - motion.position(x_name)[i]
    b.line(x_img, J(r), [y_img], f"v:{y_name}/{x_name}", f"{g.name}:{y_name}")
    b.line(pole, v_y, [y_img], f"v:{y_name}", f"{g.name}:{y_name}")
    b.vector(f"v:{y_name}/{x_name}", x_img, y_img, float(la.norm(v_y - v_x)), "relative")
    b.vector(f"v:{y_name}", pole, y_img, float(la.norm(v_y)), "absolute")
    for pair in g.inner:
        if pair.kind == "R" and pair.point != x_name:
            img = b.image(pair.point, g.base)
            v = motion.velocity(pair.point, g.base)[i]
            b.line(pole, J(motion.position(pair.point)[i] - centre), [img], f"v:{pair.point}", f"{g.name}:P")
            b.vector(f"v:{pair.point}", pole, img, float(la.norm(v)), "absolute")
    points, final = b.plan_points()
    pins = {p.point for p in g.inner if p.kind == "R"}
    similar = ((g.base, tuple(final[b.image_key(p, g.base)] for p in mech.links[g.base].points)),) \
        if set(mech.links[g.base].points) <= pins else ()
    return Plan(kind="velocity", mu=b.mu, pole=final[("pole",)], points=points, vectors=tuple(b.vectors), lines=tuple(b.lines),
                similar=similar)
