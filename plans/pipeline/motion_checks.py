"""What the pipeline says about a solved motion before drawing it: the class III groups'
cross-check (two solutions that disagree stop the render) and the warnings — a mechanism at
rest, a group near a singular position.

Reads a solved Motion; imports nothing of the pipeline's stages, sheets, report or API."""

from __future__ import annotations

from ..errors import PlansError
from ..kinematics import WARN_SIN, Motion
from ..kinematics.tolerances import CROSS_CHECK_RTOL
from ..scene import Scene
from .rest import rest_note

__all__ = ["check_triads", "motion_warnings"]


def check_triads(motion: Motion, path: str) -> None:
    """Raise a PlansError (prefixed ``path``) when a group's special-point solution and its
    Jacobian solution differ by more than CROSS_CHECK_RTOL (relative)."""
    for name, worst in motion.triad_disagreement.items():
        if worst > CROSS_CHECK_RTOL:
            raise PlansError(f"{path}: group {name}: the special-point solution and the Jacobian solution differ "
                             f"by {worst:.2e} (relative) — please report this scene")


def motion_warnings(scene: Scene, motion: Motion, rest: tuple[bool, bool], stem: str) -> list[str]:
    """The warnings, in order: the plans drawn as sheets saying the mechanism is at rest
    (``rest`` from :func:`~plans.pipeline.rest.at_rest`), then each position where a group's
    condition figure (the sine of its transmission angle, generalised: the same closeness to a
    dead position for every kind of group) is below WARN_SIN."""
    warnings = []
    resting = [k for k, r in zip(("velocity", "acceleration"), rest) if r and k in scene.draw]
    if resting:
        warnings.append(f"{stem}: {rest_note(motion, resting[-1])}; the {' and '.join(resting)} "
                        f"plan{'s are sheets' if len(resting) > 1 else ' is a sheet'} saying so")
    unit = "°" if motion.mechanism.drive.kind.angular else " m"
    for i in range(len(motion)):
        for g, s in motion.sines.items():
            if abs(s[i]) < WARN_SIN:
                away = motion.singular_distance(g, i)
                where = "" if away is None else f", about {away:.3g}{unit} from it"
                warnings.append(f"{stem}: group {g} is near a singular position at {motion.values[i]:g}{unit} "
                                f"(condition {s[i]:.2e}{where}); values are exact but sensitive")
    return warnings
