"""The kinematic scheme at one position, as geometry in paper millimetres (y up): world
coordinates divided by μl. Symbols (joints, blocks, supports) keep paper sizes."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kinematics import Motion
from ..scene import FRAME

__all__ = ["Scheme", "Block", "Guide", "scheme", "BLOCK_MM"]

#: Slider block size along and across its guide, mm.
BLOCK_MM = (12.0, 7.0)
#: How far a guide runs beyond the positions its slider takes, mm.
GUIDE_MARGIN_MM = 10.0


@dataclass(frozen=True)
class Block:
    """A slider block centred on the pair's point, turned to the guide's direction (deg)."""

    link: str
    center: tuple[float, float]
    angle: float


@dataclass(frozen=True)
class Guide:
    """A guide segment; ``fixed`` guides (on the frame) are hatched."""

    link: str
    start: tuple[float, float]
    end: tuple[float, float]
    fixed: bool


@dataclass(frozen=True)
class Scheme:
    """Everything the scheme drawing needs at one position."""

    mu_l: float
    points: dict[str, tuple[float, float]]
    links: tuple[tuple[str, tuple[str, ...]], ...]   # moving link → its points (drawn as bars / plates)
    joints: tuple[str, ...]                          # revolute pins
    supports: tuple[str, ...]                        # frame pivots
    blocks: tuple[Block, ...]
    guides: tuple[Guide, ...]
    drive_pivot: str | None
    omega: float


def _xy(v: np.ndarray) -> tuple[float, float]:
    return (float(v[0]), float(v[1]))


def scheme(motion: Motion, i: int, mu_l: float) -> Scheme:
    """The scheme at position ``i``; ``mu_l`` in m/mm."""
    mech = motion.mechanism
    points = {p: _xy(motion.position(p)[i] / mu_l) for p in mech.sketch}
    shared = [p for p in mech.sketch if sum(p in l.local for l in mech.links.values()) > 1]
    joints = tuple(p for p in shared if any(p in mech.links[l].local for l in mech.moving))
    supports = tuple(p for p in mech.links[FRAME].points if p in joints)
    blocks, guides = [], []
    for pr in mech.prismatics:
        state = motion.links[pr.guide]
        u = state.direction(pr.direction)
        angle = float(np.degrees(np.arctan2(u[i, 1], u[i, 0])))
        center = motion.position(pr.label)[i] / mu_l
        if len(mech.links[pr.slider].points) == 1:
            blocks.append(Block(pr.slider, _xy(center), angle))
        # the guide covers the slider's travel over every analysed position
        anchor = state.point(pr.anchor[pr.guide])[i] / mu_l
        travel = motion.position(pr.label) / mu_l
        anchors = state.point(pr.anchor[pr.guide]) / mu_l
        rel = [float(np.dot(travel[j] - anchors[j], u[j])) for j in range(len(travel))]
        # a frame guide runs past the travel; a moving guide (a slotted link) stays within it
        margin = BLOCK_MM[0] / 2 + (GUIDE_MARGIN_MM if pr.guide == FRAME else 0.0)
        t0 = min(rel + [0.0]) - margin
        t1 = max(rel + [0.0]) + margin
        guides.append(Guide(pr.guide, _xy(anchor + t0 * u[i]), _xy(anchor + t1 * u[i]), pr.guide == FRAME))
    links = tuple((name, mech.links[name].points) for name in mech.moving)
    d = mech.drive
    return Scheme(mu_l=mu_l, points=points, links=links, joints=joints, supports=supports,
                  blocks=tuple(blocks), guides=tuple(guides),
                  drive_pivot=d.pivot if d.kind == "rotary" else None, omega=d.speed)
