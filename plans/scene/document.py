"""A whole scene from its TOML mapping: the top-level keys, title and description, then each
section by its reader, in the order a later section needs an earlier one (points, links,
sliders, drive, lengths, plans and the cycle, scales, loads).

Imports only plans.errors and modules of plans.scene (and the standard library).
"""

from __future__ import annotations

from typing import Any, Mapping

from ..errors import SceneError
from .checks import SHOW, subtable, text, whole
from .counterweights import read_counterweights
from .drive import read_drive
from .dynamics import read_period
from .laws import read_dynamics_with_laws
from .gear_pair import read_gear_pair
from .gears import read_gears, read_synthesis
from .loads import read_balance, read_forces, read_gravity, read_masses, read_moments
from .options import read_cycle, read_draw
from .rotor import read_rotor_scene
from .turning import read_flywheel_scene
from .scales import read_scales, refuse_scales
from .sketch import check_dimensions, read_lengths, read_links, read_points, read_sliders
from .gears import GearTrain
from .values import FRAME, MAX_TITLE_CHARS, Scene

_TOP_KEYS = {"title", "description", "points", "links", "sliders", "drive", "lengths", "plans", "scales",
             "masses", "forces", "moments", "gravity", "balance", "gears", "synthesis", "dynamics", "motor", "gear_pair",
             "rotor", "turning", "flywheel", "operation", "counterweights"}
#: The keys of a scene that is a gear train alone (no [points], [links], [drive]).
_TRAIN_KEYS = {"title", "description", "plans", "gears", "synthesis", "gear_pair"}
#: What a scene of gears alone draws: the train's sheet, the pair in mesh and its cutting.
_GEAR_SHEETS = ("gears", "meshing", "cutting")


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
    if "rotor" in data:           # a rotor alone: its masses and their balancing
        rotor, draw = read_rotor_scene(data)
        return Scene(title=title or "Rotor", points={}, links={}, sliders=(), drive=None, draw=draw,
                     description=description, file=file, rotor=rotor)
    if {"turning", "operation", "flywheel"} & set(data):     # a flywheel problem alone: no linkage
        turning, flywheel, operation, draw = read_flywheel_scene(data)
        return Scene(title=title or "Flywheel", points={}, links={}, sliders=(), drive=None, draw=draw,
                     description=description, file=file, turning=turning, flywheel=flywheel, operation=operation)
    if "synthesis" in data:
        if "gears" in data or {"points", "links", "drive"} & set(data):
            raise SceneError("[synthesis] finds a gear train of its own: a scene with it has no [gears] and no "
                             "linkage (put the found train into a scene of its own)", key="synthesis")
        return _train_only(data, title, description, None, file)
    gears = read_gears(data["gears"]) if "gears" in data else None
    if (gears is not None or "gear_pair" in data) and not {"points", "links", "drive"} & set(data):
        return _train_only(data, title, description, gears, file)
    if "gear_pair" in data:
        raise SceneError("[gear_pair] is drawn in a scene of gears alone (with or without [gears]); put it in a scene "
                         "without [points], [links], [drive]", key="gear_pair")
    if gears is not None and gears.output is None:
        raise SceneError("a scene with a gear train and a linkage names the wheel or carrier on the crank's shaft: "
                         "[gears] output = \"NAME\" (or put the train in a scene of its own)", key="gears.output")
    points = read_points(subtable(data, "points", required=True))
    links = read_links(subtable(data, "links", required=True), points)
    sliders = read_sliders(data.get("sliders", []), points, links)
    drive_table = subtable(data, "drive", required=True)
    cycle_keys = {k: drive_table[k] for k in ("positions", "start") if k in drive_table}
    drive_keys = {k: v for k, v in drive_table.items() if k not in cycle_keys}
    if gears is not None:
        if {"displacement", "velocity", "acceleration"} & set(drive_keys):
            raise SceneError("a gear train turns a crank, and this [drive] is linear; drive a link that turns "
                             "(angle) or remove [gears] output", key="gears.output")
        if "omega" in drive_keys:
            raise SceneError(f"the crank's ω comes from the gear train ([gears] output = {gears.output!r}); remove "
                             "omega from [drive]", key="drive.omega")
        drive_keys["omega"] = 1.0      # a placeholder: plans.gears.with_train sets the train's ω
    drive = read_drive(drive_keys, links, sliders, points, cycle=cycle_keys)
    if gears is not None and not set(links[drive.link]) & set(links[FRAME]):
        raise SceneError(f"a gear train turns a crank, a link pivoted on the frame, and link {drive.link} is a coupler "
                         "(no point on the frame); drive a link pinned to the frame or remove [gears] output",
                         key="gears.output")
    lengths = read_lengths(subtable(data, "lengths"), points, links)
    check_dimensions(points, links, sliders, lengths)
    plans_table = subtable(data, "plans")
    draw, senses = read_draw({k: v for k, v in plans_table.items() if k not in ("output", "trace", "at", "assembly")})
    assembly = read_assembly(plans_table.get("assembly"))
    if "balancing" in draw:
        raise SceneError('"balancing" balances a rotor\'s masses: put [rotor] in a scene of its own (no [points], '
                         '[links], [drive]) and remove it here', key="plans.draw")
    if gears is not None and "draw" not in plans_table:
        draw = (*draw, "gears")
    if gears is None and "gears" in draw:
        raise SceneError('"gears" draws a gear train, and the scene has no [gears]; remove it from draw',
                         key="plans.draw")
    cycle = read_cycle(cycle_keys, drive, plans_table, draw, points, links, sliders)
    scales = read_scales(subtable(data, "scales"))
    masses = read_masses(subtable(data, "masses"), links)
    if "shaking" in draw and not any(m.mass > 0.0 for m in masses.values()):
        raise SceneError('draw "shaking" sums the links\' inertia forces −m·a_S: give the moving links their masses '
                         '([masses.NAME] mass = …, centre = "S")', key="plans.draw")
    counterweights = read_counterweights(data["counterweights"], links, FRAME, draw) \
        if "counterweights" in data else {}
    forces = read_forces(data.get("forces", []), links)
    follows = next((f for f in forces if f.follows_output), None)
    if follows is not None and cycle is None:
        raise SceneError("a force with a law or a stroke follows the output link over the cycle: add [drive] "
                         "positions = N (and [plans] output, the slider or rocker it follows)",
                         key=f"forces[{follows.index}]")
    moments = read_moments(data.get("moments", []), links, read_period(data.get("dynamics")))
    gravity = read_gravity(data)
    balance = read_balance(data["balance"] if "balance" in data else None, drive, links, points)
    if "motor" in data and "dynamics" not in data:
        raise SceneError("[motor] drives the machine in [dynamics]: add [dynamics] (delta or flywheel, and "
                         'driving = "motor" or simulate)', key="motor")
    dynamics = read_dynamics_with_laws(data["dynamics"], data.get("motor")) if "dynamics" in data else None
    if "dynamics" in draw and dynamics is None:
        raise SceneError('draw "dynamics" shows the machine\'s motion under its loads: add [dynamics] with delta '
                         '(the allowed coefficient of speed fluctuation) or flywheel', key="plans.draw")
    if "startup" in draw and (dynamics is None or dynamics.simulate is None):
        raise SceneError('draw "startup" shows the motor start-up: add [motor] and [dynamics] simulate = '
                         '{ t_end = 10.0 }', key="plans.draw")
    if dynamics is not None:
        if cycle is None:
            raise SceneError("[dynamics] finds the machine's motion over a steady cycle: add [drive] positions = N "
                             "(e.g. 12)", key="dynamics")
        if dynamics.true_speed and "diagrams" in draw:
            raise SceneError('true_speed re-solves the positions at the true ω1(φ); the kinematic diagrams are drawn '
                             'against time at a constant ω1: draw one or the other', key="dynamics.true_speed")
        if drive.speed == 0.0 or drive.rate != 0.0:
            raise SceneError("[dynamics] starts from the crank turning at its mean speed: give omega ≠ 0 (the mean "
                             "ω_m) and epsilon = 0", key="drive.omega" if drive.speed == 0.0 else "drive.epsilon")
    return Scene(title=title or "Mechanism", points=points, links=links, sliders=sliders, drive=drive,
                 lengths=lengths, draw=draw, senses=senses, scales=scales, description=description, file=file,
                 cycle=cycle, masses=masses, forces=forces, moments=moments, gravity=gravity, balance=balance,
                 gears=gears, dynamics=dynamics, assembly=assembly, counterweights=counterweights)


#: Largest assembly number: a group has at most 10 real assemblies (a trigonometric polynomial of
#: degree ≤ 5); beyond 100 the number is a slip, refused here rather than after the kinematics.
MAX_ASSEMBLY = 100


def read_assembly(table: Any) -> dict[str, int]:
    """``[plans] assembly``: group name → the number of its assembly to draw at the first analysed
    position (as the ``-assemblies`` sheet numbers them, 1 …); the names are checked once the
    structure is known."""
    if table is None:
        return {}
    if not isinstance(table, Mapping) or not table:
        raise SceneError('assembly is a table of a group\'s name and its number, e.g. { "III(2-3-4-5)" = 2 }',
                         key="plans.assembly")
    out = {}
    for name, k in table.items():
        n = whole(k)
        if not str(name).strip():
            raise SceneError('name the group as its -assemblies sheet does, e.g. "III(2-3-4-5)" = 2',
                             key='plans.assembly.""')
        if n is None or not 1 <= n <= MAX_ASSEMBLY:
            raise SceneError(f"the assembly of {name!r} is a whole number from 1 to {MAX_ASSEMBLY} (its number on "
                             f"the -assemblies sheet), got {SHOW.repr(k)}", key=f"plans.assembly.{name}")
        out[str(name)] = n
    return out


def _train_only(data: Mapping[str, Any], title: str, description: str, gears: GearTrain | None,
                file: str | None) -> Scene:
    """A scene of gears alone: [gears] (or [synthesis], which finds it) and/or [gear_pair], with
    title, description, [plans] draw (and no scales: an empty [scales] at most)."""
    if "scales" in data:          # the gear sheets choose their own scales (see refuse_scales)
        refuse_scales(subtable(data, "scales"))
    extra = sorted(str(k) for k in set(data) - _TRAIN_KEYS - {"scales"})
    if extra:
        raise SceneError(f"[{extra[0]}] belongs to a linkage, but this scene has no [points], [links], [drive]; "
                         f"a gear train alone has {', '.join(sorted(_TRAIN_KEYS))}", key=extra[0])
    if gears is not None and gears.output is not None:
        raise SceneError("output names the wheel on a linkage's crank, but the scene has no linkage; remove it or "
                         "add the linkage ([points], [links], [drive])", key="gears.output")
    plans_table = subtable(data, "plans")
    extra = sorted(str(k) for k in set(plans_table) - {"draw"})
    if extra:
        raise SceneError(f"a gear train's [plans] has only draw, not {extra[0]!r}", key=f"plans.{extra[0]}")
    pair = read_gear_pair(data["gear_pair"]) if "gear_pair" in data else None
    default = (["gears"] if gears is not None or "synthesis" in data else []) + \
        (["meshing", "cutting"] if pair is not None else [])
    draw = plans_table.get("draw", default)
    if not isinstance(draw, list) or any(d not in _GEAR_SHEETS for d in draw):
        raise SceneError(f"a scene of gears alone draws {', '.join(repr(d) for d in _GEAR_SHEETS)} or [] (the report "
                         f"alone), got {SHOW.repr(draw)}", key="plans.draw")
    if "gears" in draw and gears is None and "synthesis" not in data:
        raise SceneError('"gears" draws a gear train, and the scene has no [gears]; remove it from draw',
                         key="plans.draw")
    if pair is None and ({"meshing", "cutting"} & set(draw)):
        raise SceneError('"meshing" and "cutting" draw an involute pair: add [gear_pair]', key="plans.draw")
    synthesis = read_synthesis(data["synthesis"]) if "synthesis" in data else None
    return Scene(title=title or ("Gear train" if pair is None or gears is not None else "Gear pair"), points={},
                 links={}, sliders=(), drive=None, draw=tuple(dict.fromkeys(draw)),
                 description=description, file=file, gears=gears,
                 synthesis=synthesis, gear_pair=pair)
