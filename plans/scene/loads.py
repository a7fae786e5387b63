"""Readers of the loads: ``[masses.NAME]`` (kg, kg·m², the centre of mass), ``[[forces]]``
(N, fixed in the x, y frame), ``[[moments]]`` (N·m, CCW positive), ``gravity`` (m/s², acting
−y) and ``[balance]`` (the balancing element on the driving link).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

import math
from typing import Any, Iterator, Mapping

from ..errors import SceneError
from .checks import SHOW, entry_key, link_ref, number
from .laws import read_law
from .values import (FRAME, MAX_ANGLE_DEG, MAX_LOAD, AppliedForce, AppliedMoment, Balance, Drive, DriveKind,
                     Mass)


def _moving_link(value: Any, key: str, links: Mapping[str, Any], what: str) -> str:
    """A moving link named by ``value`` (the frame carries no load that does anything)."""
    link = link_ref(value, key, links)
    if link == FRAME:
        raise SceneError(f"the frame does not move: {what} on it does nothing; name a moving link", key=key)
    return link


def _point_of(value: Any, key: str, link: str, links: Mapping[str, tuple[str, ...]]) -> str:
    """A point of ``link`` named by ``value``."""
    if not isinstance(value, str):
        raise SceneError(f"a point is named by a string, e.g. \"{links[link][0]}\"; got {SHOW.repr(value)}", key=key)
    if value not in links[link]:
        where = "an unknown point" if not any(value in pts for pts in links.values()) else "not a point of that link"
        raise SceneError(f"{value!r} is {where}; use a point of link {link} ({', '.join(links[link])}) "
                         "or add it there in [links]", key=key)
    return value


def read_masses(table: Mapping[str, Any], links: Mapping[str, tuple[str, ...]]) -> dict[str, Mass]:
    """``[masses.NAME]``: the mass (kg), inertia (kg·m²) and centre of mass of each moving link."""
    out = {}
    for name, entry in table.items():
        key = entry_key("masses", name)
        link = _moving_link(name, key, links, "a mass")
        if not isinstance(entry, Mapping):
            raise SceneError('[masses.NAME] is a table: mass = 2.0, inertia = 0.01, centre = "S2"', key=key)
        extra = sorted(str(k) for k in set(entry) - {"mass", "inertia", "centre"})
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; a link's mass has mass, inertia, centre", key=f"{key}.{extra[0]}")
        mass, inertia = (number(entry.get(k, 0.0), f"{key}.{k}", bound=MAX_LOAD, why=unit)
                         for k, unit in (("mass", " kg"), ("inertia", " kg·m²")))
        for k, x in (("mass", mass), ("inertia", inertia)):
            if x < 0.0:
                raise SceneError(f"a {k} cannot be negative, got {x:g}; give 0 or more", key=f"{key}.{k}")
        if "centre" not in entry:
            raise SceneError("a mass without a centre: add centre = \"NAME\", the link's point at its centre of mass",
                             key=f"{key}.centre")
        centre = _point_of(entry["centre"], f"{key}.centre", link, links)
        out[link] = Mass(link=link, mass=mass, inertia=inertia, centre=centre)
    return out


def _load_entries(items: Any, name: str, allowed: set[str], required: tuple[str, ...], has: str,
                  needs: str) -> Iterator[tuple[int, str, Mapping[str, Any]]]:
    """The entries of an array of tables ``[[name]]`` (index, key, table), each checked for
    unknown keys (``has`` says what an entry has) and the ``required`` ones (``needs``)."""
    if not isinstance(items, list):
        raise SceneError(f"{name} must be an array of tables [[{name}]]", key=name)
    for i, item in enumerate(items):
        key = f"{name}[{i}]"
        if not isinstance(item, Mapping):
            raise SceneError(f"each [[{name}]] entry must be a table", key=key)
        extra = sorted(str(k) for k in set(item) - allowed)
        if extra:
            raise SceneError(f"unknown key {extra[0]!r}; {has}", key=f"{key}.{extra[0]}")
        for k in required:
            if k not in item:
                raise SceneError(f"missing {k!r}; {needs}", key=key)
        yield i, key, item


#: The keys of a ``[[forces]]`` entry.
FORCE_KEYS = {"link", "at", "vector", "magnitude", "angle", "law", "stroke", "oppose", "from"}
#: Where a stroke-limited force acts (``stroke``).
STROKES = ("both", "working", "return")
#: Most (x, F) pairs of a law (an indicator diagram of a few hundred points is plenty).
MAX_LAW_POINTS = 2000


def read_forces(items: Any, links: Mapping[str, tuple[str, ...]]) -> tuple[AppliedForce, ...]:
    """``[[forces]]``: vector = [Fx, Fy] (N), or magnitude (N) with angle (°), at a point of a
    link; or a ``law`` of the output's travel (with angle, or vector giving the direction), with
    ``stroke``, ``oppose`` and ``from`` (see :class:`~plans.scene.values.AppliedForce`)."""
    out = []
    for i, key, item in _load_entries(items, "forces", FORCE_KEYS, ("link", "at"),
                                      "a force has link, at, and vector or magnitude with angle (or a law); "
                                      "stroke, oppose, from",
                                      "a force needs link, at, and vector = [Fx, Fy] (N)"):
        link = _moving_link(item["link"], f"{key}.link", links, "a force")
        at = _point_of(item["at"], f"{key}.at", link, links)
        oppose = item.get("oppose", False)
        if not isinstance(oppose, bool):
            raise SceneError(f"oppose is true or false, got {SHOW.repr(oppose)}", key=f"{key}.oppose")
        stroke = item.get("stroke", "both")
        if stroke not in STROKES:
            raise SceneError(f"stroke is \"working\" (only while the output moves away from its extreme \"from\"), "
                             f"\"return\" or \"both\"; got {SHOW.repr(stroke)}", key=f"{key}.stroke")
        origin = item.get("from", "min")
        if origin not in ("min", "max"):
            raise SceneError(f"from names the output's extreme where the working stroke starts and the law's travel "
                             f"is 0: \"min\" (smallest displacement or angle) or \"max\"; got {SHOW.repr(origin)}",
                             key=f"{key}.from")
        law = _law(item["law"], f"{key}.law") if "law" in item else ()
        if "from" in item and not law and stroke == "both":
            raise SceneError("from places the law's travel and the working stroke; give a law or a stroke, or "
                             "remove from", key=f"{key}.from")
        if "vector" in item:
            if "magnitude" in item or "angle" in item:
                raise SceneError("give either vector = [Fx, Fy] or magnitude with angle, not both", key=key)
            vec = item["vector"]
            if not isinstance(vec, list) or len(vec) != 2:
                raise SceneError(f"vector is [Fx, Fy] in newtons, got {SHOW.repr(vec)}", key=f"{key}.vector")
            fx, fy = (number(c, f"{key}.vector", bound=MAX_LOAD, why=" N") for c in vec)
            vector: tuple[float, float] | None = (fx, fy)
            if law:
                size = math.hypot(fx, fy)
                if size == 0.0 or not math.isfinite(size):
                    raise SceneError("with a law, vector gives the force's direction only: a nonzero [Fx, Fy]",
                                     key=f"{key}.vector")
                vector = (fx / size, fy / size)
        elif law:
            if "magnitude" in item:
                raise SceneError("a force with a law takes its magnitude from the law: remove magnitude", key=key)
            if "angle" not in item and not oppose:
                raise SceneError("a force with a law needs its direction: angle (°), or oppose = true (against the "
                                 "velocity of its point)", key=key)
            vector = None if "angle" not in item else _unit(item["angle"], f"{key}.angle")
        else:
            if "magnitude" not in item or ("angle" not in item and not oppose):
                raise SceneError("a force needs vector = [Fx, Fy] (N), or magnitude (N) with angle (°)", key=key)
            mag = number(item["magnitude"], f"{key}.magnitude", bound=MAX_LOAD, why=" N")
            if "angle" in item:
                ux, uy = _unit(item["angle"], f"{key}.angle")
                vector = (mag * ux, mag * uy)
            else:
                if mag < 0.0:
                    raise SceneError(f"a force against the velocity of its point has a magnitude of 0 or more, got "
                                     f"{mag:g} N", key=f"{key}.magnitude")
                vector = None
        out.append(AppliedForce(link=link, at=at, vector=vector, index=i, law=law, stroke=stroke, oppose=oppose,
                                origin=origin, magnitude=None if vector is not None or law else mag))
    return tuple(out)


def _unit(value: Any, key: str) -> tuple[float, float]:
    """The unit vector at the angle ``value`` (°, CCW from +x)."""
    ang = math.radians(number(value, key, bound=MAX_ANGLE_DEG, why="°"))
    return math.cos(ang), math.sin(ang)


def _law(value: Any, key: str) -> tuple[tuple[float, float], ...]:
    """A law: a list of at least two [x, F] pairs, x ≥ 0 strictly increasing."""
    if not isinstance(value, list) or len(value) < 2 or len(value) > MAX_LAW_POINTS:
        raise SceneError(f"law is a list of 2 to {MAX_LAW_POINTS} pairs [x, F] (x the output's travel from its "
                         f"extreme, m or °; F in N), e.g. [[0.0, 0.0], [0.05, 4000.0]]; got {SHOW.repr(value)}",
                         key=key)
    out = []
    for k, pair in enumerate(value):
        if not isinstance(pair, list) or len(pair) != 2:
            raise SceneError(f"each point of a law is a pair [x, F], got {SHOW.repr(pair)}", key=f"{key}[{k}]")
        x = number(pair[0], f"{key}[{k}]", bound=MAX_LOAD, why=" (m or °)")
        f = number(pair[1], f"{key}[{k}]", bound=MAX_LOAD, why=" N")
        if x < 0.0:
            raise SceneError(f"a law's travel x is measured from the output's extreme and is 0 or more, got {x:g}",
                             key=f"{key}[{k}]")
        if out and x <= out[-1][0]:
            raise SceneError(f"a law is not monotone in its travel: x = {x:g} after x = {out[-1][0]:g}; list the "
                             "pairs with x strictly increasing", key=f"{key}[{k}]")
        out.append((x, f))
    return tuple(out)


def read_moments(items: Any, links: Mapping[str, tuple[str, ...]],
                 period: float | None = None) -> tuple[AppliedMoment, ...]:
    """``[[moments]]``: a couple value (N·m, CCW positive) on a moving link, or its ``law`` in the
    crank's turned angle (degrees from the cycle's first position, N·m CCW positive; written as
    [turning] writes a torque) over the ``period`` of ``[dynamics]`` (None: no [dynamics])."""
    out = []
    for i, key, item in _load_entries(items, "moments", {"link", "value", "law"}, ("link",),
                                      "a moment has link and value (N·m, CCW positive) or law (in the crank angle)",
                                      "a moment needs link and value (N·m, CCW positive)"):
        link = _moving_link(item["link"], f"{key}.link", links, "a moment")
        if ("value" in item) == ("law" in item):
            raise SceneError("a moment needs value (N·m, CCW positive) or law (its value against the crank angle), "
                             "one of the two", key=key)
        if "value" in item:
            out.append(AppliedMoment(link=link, value=number(item["value"], f"{key}.value", bound=MAX_LOAD,
                                                             why=" N·m"), index=i))
            continue
        if period is None:
            raise SceneError("a moment's law in the crank angle is taken by the machine's dynamics over its cycle: add "
                             "[dynamics] (delta or flywheel), or give value", key=f"{key}.law")
        law = read_law(item["law"], f"{key}.law", period, "give value = … for a constant moment")
        out.append(AppliedMoment(link=link, value=0.0, index=i, law=law))
    return tuple(out)


def read_gravity(data: Mapping[str, Any]) -> float | None:
    """``gravity``: g in m/s² (acting −y) when the scene gives it, else None (no weights)."""
    return number(data["gravity"], "gravity", bound=MAX_LOAD, why=" m/s²") if "gravity" in data else None


def read_balance(table: Any, drive: Drive, links: Mapping[str, tuple[str, ...]],
                 points: Mapping[str, tuple[float, float]]) -> Balance:
    """The balancing element: [balance] when given, else the drive's default (a moment on a
    crank or a coupler, a force along the guide of a slider or a cylinder)."""
    if table is None:
        kind = "moment" if drive.kind.angular else "actuator" if drive.kind == DriveKind.CYLINDER else "force"
        return Balance(link=drive.link, kind=kind, given=False)
    if not isinstance(table, Mapping):
        raise SceneError("[balance] must be a table: moment_on = \"1\", or force_on = \"1\" with at and angle",
                         key="balance")
    extra = sorted(str(k) for k in set(table) - {"moment_on", "force_on", "at", "angle"})
    if extra:
        raise SceneError(f"unknown key {extra[0]!r}; [balance] has moment_on, or force_on with at and angle",
                         key=f"balance.{extra[0]}")
    if ("moment_on" in table) == ("force_on" in table):
        raise SceneError("give one balancing element: moment_on = \"1\" (a moment on the driving link) or "
                         "force_on = \"1\" with at and angle", key="balance")
    which = "moment_on" if "moment_on" in table else "force_on"
    link = link_ref(table[which], f"balance.{which}", links)
    if link != drive.link:
        raise SceneError(f"the balancing element belongs on the driving link {drive.link}, not on link {link}",
                         key=f"balance.{which}")
    if which == "moment_on":
        for k in ("at", "angle"):
            if k in table:
                raise SceneError(f"{k} places a balancing force; a moment has none: remove it", key=f"balance.{k}")
        if not drive.kind.angular:
            raise SceneError(f"link {link} slides and cannot turn, so a moment on it balances nothing: use "
                             "force_on with at and angle (the force along the guide)", key="balance.moment_on")
        return Balance(link=link, kind="moment")
    for k in ("at", "angle"):
        if k not in table:
            raise SceneError(f"a balancing force needs at (a point of link {link}) and angle (°, its line in the "
                             "sketch, turning with the link)", key=f"balance.{k}")
    at = _point_of(table["at"], "balance.at", link, links)
    angle = number(table["angle"], "balance.angle", bound=MAX_ANGLE_DEG, why="°")
    return Balance(link=link, kind="force", at=at, angle=angle)
