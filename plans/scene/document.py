"""A whole scene from its TOML mapping: the top-level keys, title and description, then each
section by its reader, in the order a later section needs an earlier one (points, links,
sliders, drive, lengths, plans and the cycle, scales, loads).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, subtable, text
from .drive import read_drive
from .loads import read_balance, read_forces, read_gravity, read_masses, read_moments
from .options import read_cycle, read_draw
from .scales import read_scales
from .sketch import check_dimensions, read_lengths, read_links, read_points, read_sliders
from .values import MAX_TITLE_CHARS, Scene

_TOP_KEYS = {"title", "description", "points", "links", "sliders", "drive", "lengths", "plans", "scales",
             "masses", "forces", "moments", "gravity", "balance"}


def parse_scene(data: Mapping[str, Any], *, file: str | None = None) -> Scene:
    """Validate a scene already loaded from TOML (a mapping) and build a :class:`Scene`;
    errors name ``file`` (when given) and the key."""
    try:
        return _parse(data, file)
    except SceneError as exc:
        if file is None or exc.file:
            raise
        raise exc.in_file(file) from None


def _parse(data: Mapping[str, Any], file: str | None) -> Scene:
    if not isinstance(data, Mapping):
        raise SceneError(f"a scene is a TOML document of tables, got {SHOW.repr(data)}", key="(top level)")
    unknown = sorted(str(k) for k in set(data) - _TOP_KEYS)
    if unknown:
        raise SceneError(f"unknown top-level key {unknown[0]!r}; allowed: {', '.join(sorted(_TOP_KEYS))}",
                         key=unknown[0])
    title = text(data.get("title", ""), "title", line=True)
    if len(title) > MAX_TITLE_CHARS:
        raise SceneError(f"title has {len(title)} characters; it is one line at the top of every sheet, keep it "
                         f"within {MAX_TITLE_CHARS} (put the rest in description)", key="title")
    description = text(data.get("description", ""), "description", line=False)
    points = read_points(subtable(data, "points", required=True))
    links = read_links(subtable(data, "links", required=True), points)
    sliders = read_sliders(data.get("sliders", []), points, links)
    drive_table = subtable(data, "drive", required=True)
    cycle_keys = {k: drive_table[k] for k in ("positions", "start") if k in drive_table}
    drive = read_drive({k: v for k, v in drive_table.items() if k not in cycle_keys}, links, sliders, points,
                       cycle=cycle_keys)
    lengths = read_lengths(subtable(data, "lengths"), points, links)
    check_dimensions(points, links, sliders, lengths)
    plans_table = subtable(data, "plans")
    draw, senses = read_draw({k: v for k, v in plans_table.items() if k not in ("output", "trace", "at")})
    cycle = read_cycle(cycle_keys, drive, plans_table, draw, points, links)
    scales = read_scales(subtable(data, "scales"))
    masses = read_masses(subtable(data, "masses"), links)
    forces = read_forces(data.get("forces", []), links)
    moments = read_moments(data.get("moments", []), links)
    gravity = read_gravity(data)
    balance = read_balance(data["balance"] if "balance" in data else None, drive, links, points)
    return Scene(title=title or "Mechanism", points=points, links=links, sliders=sliders, drive=drive,
                 lengths=lengths, draw=draw, senses=senses, scales=scales, description=description, file=file,
                 cycle=cycle, masses=masses, forces=forces, moments=moments, gravity=gravity, balance=balance)
