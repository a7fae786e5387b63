"""The vectors a relation draws on a plan: a rigid relation's relative velocity, or its
normal (ω²·XY) and tangential (ε·XY) acceleration components and their total; a sliding
relation's relative velocity, or its Coriolis (2·ω × v_rel) and relative sliding
components; and the sides still missing of every link's similar figure.

Must not import the plan assembly (:mod:`.plans`) or the class III routes.
"""

from __future__ import annotations

import numpy as np

from ..kinematics import Motion
from ..kinematics.state import J
from ..scene import FRAME
from .plan_builder import _Builder, _at_pole, _same
from .relations import Relation
from .. import linalg as la


def _rigid(b: _Builder, rel: Relation, sym: str) -> None:
    motion, link = b.motion, rel.link
    xl, yl = b.label(rel.x, link), b.label(rel.y, link)     # as printed
    xn, yn = b.name(rel.x, link), b.name(rel.y, link)       # as the quantities name them
    tail, head = b.image(rel.y, link), b.image(rel.x, link)
    r = b.world(rel.x) - b.world(rel.y)   # the link's segment Y → X, m
    state = motion.links[link]
    q = f"{sym}:{xn}/{yn}"
    if sym == "v" or not rel.pair:
        if rel.group == "I" and sym == "v":
            return  # the crank tip's velocity relative to the fixed pivot is its absolute velocity
        value = float(la.norm(b.quantity(rel.x, link) - b.quantity(rel.y, link)))
        b.vector(q, tail, head, value, "relative", optional=not rel.pair)
        if rel.pair:
            b.line(tail, J(r), [head], q, rel.line_group)
        return
    w, e = float(state.omega[b.i]), float(state.epsilon[b.i])
    normal = -w * w * r
    if rel.group == "I" and e == 0.0:
        return  # a crank turning uniformly: πa is the normal component itself
    n_xy = b.put(("n", xn, yn), f"n_{xl}{yl}", np.add(tail, normal / b.mu))
    both = b.vector(f"{q}:n", tail, n_xy, float(la.norm(normal)), "normal")
    both &= b.vector(f"{q}:t", n_xy, head, abs(e) * float(la.norm(r)), "tangential")
    b.line(n_xy, J(r), [head], f"{q}:t", rel.line_group)
    # the whole relative acceleration a→b beside its components (the textbook's a_BA); left
    # out where the absolute a:X draws that very segment (y at the pole), where one component
    # is zero (the other is the whole), and never from a special point (no side of the link)
    if both and rel.y not in b.extra:
        b.vector(q, tail, head, float(la.norm(b.quantity(rel.x, link) - b.quantity(rel.y, link))), "relative",
                 optional=True)


def _close_figures(b: _Builder, sym: str) -> None:
    """The sides still missing of every link's similar figure (three or more points): the
    polygon of its images in the link's order, each side a relative vector ``v:Q/P`` (from
    the earlier point, or from a fixed point: no side ends at the pole) unless a vector of
    the plan already joins the two images."""
    motion = b.motion
    drawn = {v.quantity for v in b.vectors}

    def joined(p, q) -> bool:
        return any((_same(v.tail, p) and _same(v.head, q)) or (_same(v.tail, q) and _same(v.head, p))
                   for v in b.vectors)

    for link in motion.mechanism.moving:
        pts = motion.mechanism.links[link].points
        if len(pts) < 3:
            continue
        for k, y in enumerate(pts):
            x = pts[(k + 1) % len(pts)]
            if b.fixed(x, link) or (_at_pole(b.image(x, link)) and not _at_pole(b.image(y, link))):
                x, y = y, x       # never a side into the pole
            tail, head = b.image(y, link), b.image(x, link)
            q = f"{sym}:{b.name(x, link)}/{b.name(y, link)}"
            if q in drawn or joined(tail, head):
                continue
            b.vector(q, tail, head, float(la.norm(b.quantity(x, link) - b.quantity(y, link))), "relative")
            drawn.add(q)


def _solved_before(motion: Motion, link: str, group: str) -> bool:
    """True when ``link`` is known before group ``group`` is solved (driver, frame, or a
    link of an earlier group)."""
    for g in motion.structure.groups:
        if g.name == group:
            return link not in g.links
    return True


def _slide(b: _Builder, rel: Relation, sym: str, pole) -> None:
    motion, slider, guide = b.motion, rel.link, rel.other
    pr = next(p for p in motion.mechanism.prismatics if p.slider == slider and p.guide == guide)
    u = motion.links[guide].direction(pr.direction)[b.i]
    if FRAME in (slider, guide):
        moving = slider if guide == FRAME else guide
        b.line(pole, u, [b.image(rel.x, moving)], f"{sym}:{b.name(rel.x, moving)}", rel.line_group)
        return
    # the construction starts from the image already known: the guide's when it was solved
    # before the group (a slider of the group on a known turning guide), the slider's when it
    # was; within the group, that of the link carrying the pair's point (the block pinned there)
    if _solved_before(motion, guide, rel.group):
        known, moving = guide, slider
    elif _solved_before(motion, slider, rel.group) or rel.x in motion.mechanism.links[slider].local:
        known, moving = slider, guide
    else:
        known, moving = guide, slider
    kl, ml = b.joined(rel.x, known), b.joined(rel.x, moving)       # as the quantities name them
    tail, head = b.image(rel.x, known), b.image(rel.x, moving)
    q = f"{sym}:{ml}/{kl}"
    if sym == "v":
        value = float(la.norm(b.quantity(rel.x, moving) - b.quantity(rel.x, known)))
        b.vector(q, tail, head, value, "relative")
        b.line(tail, u, [head], q, rel.line_group)
        return
    # a_moving = a_known + a^k + a^r: the kinematics gives the slider's Coriolis term relative
    # to the guide, 2 ω_guide × σu, and σ̇ along the guide; the guide relative to the slider
    # has both with the opposite sign
    slide = b.slide(slider, guide)
    sense = 1.0 if moving == slider else -1.0
    coriolis = sense * slide.coriolis[b.i]
    k_xy = b.put(("k", ml, kl), f"k_{b.joined_label(rel.x, moving)}{b.joined_label(rel.x, known)}",
                 np.add(tail, coriolis / b.mu))
    b.vector(f"{q}:cor", tail, k_xy, float(la.norm(coriolis)), "coriolis")
    b.vector(f"{q}:r", k_xy, head, abs(float(slide.a[b.i])), "sliding")
    b.line(k_xy, u, [head], f"{q}:r", rel.line_group)
