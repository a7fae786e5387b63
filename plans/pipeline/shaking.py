"""The report's shaking force and moment over the cycle (``cycle.shaking``, and with
counterweights ``cycle.shaking_without``, ``cycle.reciprocating`` and the top-level
``counterweights``), read off a :class:`~plans.dynamics.shaking.ShakingAnalysis` (SI units;
x right, y up; moments CCW positive; angles in degrees).

Imports nothing of the pipeline's stages, sheets or API."""

from __future__ import annotations

import numpy as np

from ..dynamics.shaking import ShakingAnalysis, ShakingForces

__all__ = ["shaking_report", "counterweights_report"]


def _xy(a: np.ndarray) -> list[list[float]]:
    return [[float(p[0]), float(p[1])] for p in a]


def _list(a: np.ndarray) -> list[float]:
    return [float(x) for x in a]


def _forces(s: ShakingForces, about: str, origin: np.ndarray) -> dict:
    """One shaking: the mass (kg), per position the force (N), the moment about ``about`` (N·m)
    and the centre of mass (m), and the largest |force| and |moment| over the cycle."""
    size = np.hypot(s.force[:, 0], s.force[:, 1])
    return {"mass": float(s.mass), "about": about, "origin": [float(origin[0]), float(origin[1])],
            "force": _xy(s.force), "moment": _list(s.moment), "centre_of_mass": _xy(s.centre),
            "largest_force": float(size.max(initial=0.0)), "largest_moment": float(np.abs(s.moment).max(initial=0.0))}


def shaking_report(a: ShakingAnalysis) -> dict:
    """The keys the shaking adds to the report's ``cycle``: ``shaking`` (with the counterweights
    when there are any), ``shaking_without`` (the links alone; only with counterweights) and, for
    a crank-slider with its counterweight, ``reciprocating`` (the primary and secondary forces
    along the line of stroke, and the shaking force's components along and across it)."""
    out = {"shaking": _forces(a.shaking, a.about, a.origin)}
    if a.balanced is not None:
        out["shaking_without"] = _forces(a.without, a.about, a.origin)
    r = a.reciprocating
    if r is not None:
        u = r.stroke
        n = np.array([-u[1], u[0]])

        def along(f: np.ndarray, d: np.ndarray) -> list[float]:
            return _list(f[:, 0] * d[0] + f[:, 1] * d[1])

        out["reciprocating"] = {
            "fraction": r.fraction, "rod_at_pin": r.rod_at_pin, "rod_at_slider": r.rod_at_slider, "mass": r.mass,
            "crank": r.crank, "rod": r.rod, "n": r.n, "stroke": [float(u[0]), float(u[1])], "offset": r.offset,
            "theta": _list(r.theta), "omega": _list(r.omega), "primary": _list(r.primary),
            "secondary": _list(r.secondary), "primary_after": _list(r.primary_after),
            "transverse_after": _list(r.transverse_after), "exact": _list(r.exact),
            "along": {"without": along(a.without.force, u), "with": along(a.balanced.force, u)},
            "across": {"without": along(a.without.force, n), "with": along(a.balanced.force, n)}}
    return out


def counterweights_report(a: ShakingAnalysis) -> dict:
    """The top-level ``counterweights``: link → ``mass`` (kg), ``angle`` (deg, CCW from the link's
    line first point → second point, in [0, 360)), ``radius`` (m from ``pivot``), ``mr`` (kg·m)."""
    return {c.link: {"mass": c.mass, "angle": c.angle, "radius": c.radius, "pivot": c.pivot, "mr": c.mr}
            for c in a.counterweights}
