"""The scales of a scene's sheets: μl from the mechanism's extent, μV and μa from the largest
velocity and acceleration (or as ``[scales]`` gives them).

Reads a solved Motion; imports nothing of the pipeline's stages, sheets, report or API."""

from __future__ import annotations

import numpy as np

from ..constructions import Scales, choose_scales
from ..constructions.scales import extent_of
from ..kinematics import Motion
from ..scene import Scene
from .. import linalg as la

__all__ = ["scene_scales"]


def scene_scales(scene: Scene, motion: Motion, rest: tuple[bool, bool] = (False, False)) -> Scales:
    """μl, μV, μa for a scene (no μV, μa for plans that are at rest: ``rest`` from
    :func:`~plans.pipeline.rest.at_rest`).
    A scale given in [scales] that would draw off any paper or too small to see raises a
    SceneError (key ``scales.mu_*``)."""
    mech = motion.mechanism
    pts = np.stack([motion.position(p) for p in mech.sketch], axis=1)  # (N, P, 2)
    v_ref = a_ref = None
    v_ext = a_ext = 0.0
    ref_point = mech.drive.tip if mech.drive.kind.angular else mech.drive.guide.label
    if motion.order >= 1 and not rest[0]:
        vel = np.stack([motion.velocity(p) for p in mech.sketch], axis=1)
        v_ref = float(np.max(la.norm(motion.velocity(ref_point), axis=1)))
        v_ext = max(_span(v) for v in vel)
    if motion.order >= 2 and not rest[1]:
        acc = np.stack([motion.acceleration(p) for p in mech.sketch], axis=1)
        a_ref = float(np.max(la.norm(motion.acceleration(ref_point), axis=1)))
        a_ext = max(_span(a) for a in acc)
    return choose_scales(extent=extent_of(pts), v_ref=v_ref, v_extent=v_ext, a_ref=a_ref, a_extent=a_ext,
                         overrides=scene.scales)


def _span(vectors: np.ndarray) -> float:
    """Largest width or height of a plan drawn at scale 1: the box of vectors (P, 2) and the
    pole (unlike extent_of, not raised to 1e-6: a plan's vectors may all be smaller)."""
    pts = np.concatenate([vectors, [[0.0, 0.0]]])
    return float(np.max(pts.max(axis=0) - pts.min(axis=0)))
