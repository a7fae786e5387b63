"""The reader of ``[counterweights]``: the links of a linkage that carry a counterweight and the
radius of each (m, from the link's first point, its pivot on the frame); on a crank-slider's
crank also ``reciprocating``, the fraction of the reciprocating masses its counterweight
balances (default :data:`DEFAULT_RECIPROCATING`).

What each counterweight weighs and where it points is found by the dynamics
(:mod:`plans.dynamics.counterweights`), which knows the mechanism; here only the table is read:
names, numbers, and that each link turns about a frame pivot listed first.

Imports only plans.errors and plans.scene.checks (and the standard library).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, entry_key, link_ref, number

__all__ = ["CounterweightSpec", "read_counterweights", "DEFAULT_RECIPROCATING", "MAX_RADIUS"]

#: The fraction of a crank-slider's reciprocating masses the crank's counterweight balances when
#: ``reciprocating`` is not given: one half, the textbooks' usual compromise between the primary
#: force left along the line of stroke and the one brought in across it.
DEFAULT_RECIPROCATING = 0.5
#: Largest counterweight radius, m (as MAX_COORD_M of a sketch).
MAX_RADIUS = 1e20
_KEYS = {"radius", "reciprocating"}


@dataclass(frozen=True)
class CounterweightSpec:
    """A counterweight asked for on ``link``: at ``radius`` (m) from its ``pivot`` (the link's
    first point, on the frame); ``reciprocating`` the fraction (0 … 1) of the reciprocating
    masses it balances, None when not given (a crank-slider's crank then takes
    :data:`DEFAULT_RECIPROCATING`; a four-bar's links take none)."""

    link: str
    radius: float
    pivot: str
    reciprocating: float | None = None


def read_counterweights(table: Any, links: Mapping[str, tuple[str, ...]], frame: str,
                        draw: tuple[str, ...]) -> dict[str, CounterweightSpec]:
    """``[counterweights]``: link name → ``{ radius = r }`` (m), and on a crank ``reciprocating``.
    Refused in one line naming the key: no ``"shaking"`` in draw (the counterweights balance the
    shaking force), an empty table, an unknown link or the frame, a link whose first point is not
    on the frame, a radius ≤ 0, a fraction outside 0 … 1, an unknown key."""
    if not isinstance(table, Mapping):
        raise SceneError('[counterweights] is a table of links, e.g. "1" = { radius = 0.1 }', key="counterweights")
    if "shaking" not in draw:
        raise SceneError('[counterweights] balance the shaking force over the cycle: add "shaking" to [plans] draw '
                         "(with [drive] positions = N and the links' [masses])", key="counterweights")
    if not table:
        raise SceneError('[counterweights] names at least one link, e.g. "1" = { radius = 0.1 }',
                         key="counterweights")
    on_frame = set(links.get(frame, ()))
    out: dict[str, CounterweightSpec] = {}
    for name, entry in table.items():
        key = entry_key("counterweights", name)
        link = link_ref(name, key, links)
        if link == frame:
            raise SceneError("the frame does not move: a counterweight on it balances nothing; name a link pivoted "
                             "on the frame", key=key)
        if not isinstance(entry, Mapping):
            raise SceneError(f"a counterweight is a table, e.g. \"{link}\" = {{ radius = 0.1 }} (m from the link's "
                             f"pivot); got {SHOW.repr(entry)}", key=key)
        extra = sorted(str(k) for k in set(entry) - _KEYS)
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a counterweight has radius (and on a crank-slider's crank "
                             "reciprocating)", key=f"{key}.{extra[0]}")
        if "radius" not in entry:
            raise SceneError("a counterweight needs radius (m from the link's pivot on the frame)", key=f"{key}.radius")
        radius = number(entry["radius"], f"{key}.radius", positive=True, bound=MAX_RADIUS, why=" m")
        pts = links[link]
        if not set(pts) & on_frame:
            raise SceneError(f"link {link} is not pivoted on the frame (none of its points {', '.join(pts)} is a point "
                             "of the frame): its counterweight could not balance the mechanism's centre of mass "
                             "about a fixed pivot; put counterweights on the links pivoted on the frame", key=key)
        if pts[0] not in on_frame:
            pivot = next(p for p in pts if p in on_frame)
            raise SceneError(f"a counterweight's radius and angle are measured from the link's first point, its "
                             f"pivot on the frame, and link {link}'s first point is {pts[0]}; list its pivot {pivot} "
                             "first in [links]", key=key)
        frac = None
        if "reciprocating" in entry:
            frac = number(entry["reciprocating"], f"{key}.reciprocating", bound=1.0,
                          why=" (a fraction of the reciprocating masses, 0 to 1)")
            if frac < 0.0:
                raise SceneError(f"reciprocating is the fraction of the reciprocating masses balanced, 0 to 1; got "
                                 f"{frac:g}", key=f"{key}.reciprocating")
        out[link] = CounterweightSpec(link=link, radius=radius, pivot=pts[0], reciprocating=frac)
    return out
