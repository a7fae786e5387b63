"""The whole path for one scene: read → model → structure → kinematics → constructions →
SVG and JSON text → files. Nothing is written until everything has been computed and
checked, so a failing scene leaves no partial files behind.

This module only sequences the stages and collects the files: the solving in :mod:`.stages`,
the scales in :mod:`.scales`, the motion's checks and warnings in :mod:`.motion_checks`, each
family of sheets in :mod:`.sheets` (one module, one entry function each), the JSON report in
:mod:`.json_report`, the result types in :mod:`.result`, file stems in :mod:`.naming`.

:func:`render` (``plans.render``) is the Python API: a :class:`~plans.scene.Scene` or a scene
file in, :class:`Sheets` out — the sheets display themselves in Jupyter and ``.save`` writes
them (SVG, PNG, PDF and the JSON report), all or nothing."""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

from ..drawing import Style
from ..errors import PlansError
from ..gears import GearAnalysis, analyse_train, with_train
from ..gears.pair import analyse_pair
from ..gears.report import gears_report, synthesis_report, synthesize_scene
from ..scene import Scene, read_scene
from .json_report import report, report_text
from .motion_checks import check_triads, motion_warnings
from .naming import MAX_STEM_CHARS, checked_stem, file_stem, stem_of
from .rest import at_rest
from .rotor import render_rotor
from .turning import render_flywheel
from .result import Rendered, Sheet, Sheets
from .scales import scene_scales
from .sheets.assemblies import assembly_sheets
from .sheets.centres import centres_sheets
from .sheets.cycle import cycle_sheets
from .sheets.forces import LEVER_RTOL, force_sheets, force_warnings
from .sheets.gears import gear_sheets
from .sheets.koshel import koshel_sheets
from .sheets.page import Page
from .sheets.plans import plan_sheets
from .sheets.scheme import scheme_sheets
from .sheets.shaking import shaking_sheets
from .sheets.dynamics import dynamics_sheets, dynamics_warnings
from .sheets.gear_pair import pair_report, pair_sheets
from .stages import (assembly_analysis, force_analysis, machine_motion, machine_startup, record_stages, solve_motion,
                     solve_scene, true_speed_motion)
from .stages import shaking_forces
from .shaking import counterweights_report, shaking_report

__all__ = ["Rendered", "Sheet", "Sheets", "render", "render_scene", "report", "solve_scene", "record_stages",
           "stem_of", "at_rest", "read_scene", "LEVER_RTOL", "MAX_STEM_CHARS"]


def render_scene(path: str | Path, style: Style = Style()) -> Rendered:
    """Compute every file of a scene file (nothing is written); the files are named after the
    file's stem.

    A mechanism at rest (the drive stands) gets, instead of each plan with nothing to draw, a
    sheet saying so, and a warning; so does Koshel's plan where its construction degenerates
    (:class:`~plans.errors.ConstructionError`) or fails its check. Every other sheet is drawn."""
    scene = read_scene(path)                       # a missing file is told before its name
    return _render(scene, stem=file_stem(path), where=str(path), style=style)


def _render(scene: Scene, *, stem: str, where: str | None, style: Style) -> Rendered:
    """Every file of a scene already read, named ``<stem>…``; ``where`` (the scene's file, or
    None) locates error messages. Nothing here reads or writes a file."""
    if scene.rotor is not None:       # a rotor alone: its balancing
        return render_rotor(scene, stem=stem, style=style, where=where)
    if scene.flywheel_only:           # a flywheel problem alone: [turning], [operation]
        return render_flywheel(scene, stem=stem, style=style, where=where)
    path = where or f"scene {scene.title!r}"     # the prefix of the messages below
    train: GearAnalysis | None = None
    found = None
    if scene.synthesis is not None:
        try:
            found = synthesize_scene(scene)
        except PlansError as exc:
            raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
        scene = dataclasses.replace(scene, gears=found[0].train)
    if scene.gears is not None:
        try:
            train = analyse_train(scene.gears)
            if not scene.train_only:
                scene = with_train(scene, train)
        except PlansError as exc:
            raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
        if scene.train_only:
            return _render_train(scene, train, stem=stem, style=style, found=found, where=where)
    elif scene.train_only:            # a gear pair alone
        return _render_train(scene, None, stem=stem, style=style, where=where)
    try:
        motion, cycle = solve_motion(scene)
        machine = machine_motion(scene, cycle)
        if machine is not None and scene.dynamics.true_speed:
            motion, cycle = true_speed_motion(scene, cycle, machine)
        rest = at_rest(motion)
        scales = scene_scales(scene, motion, rest)
        forces = force_analysis(scene, motion, cycle)
        started = machine_startup(scene, machine)
        assembled = assembly_analysis(scene, motion)
        shaking = shaking_forces(scene, motion)
    except PlansError as exc:
        raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
    check_triads(motion, path)
    warnings = motion_warnings(scene, motion, rest, stem)
    files: dict[str, str] = {}
    own = range(len(motion)) if cycle is None else scene.cycle.at    # positions with sheets of their own
    for i in own:
        page = Page.at(scene, motion, i, stem, style)
        files.update(scheme_sheets(page, scales))
        files.update(centres_sheets(page))
        koshel, not_drawn = koshel_sheets(page, rest[0])
        files.update(koshel)
        warnings.extend(not_drawn)
        files.update(plan_sheets(page, scales, rest, path))
        if assembled is not None:
            files.update(assembly_sheets(page, assembled[i]))
    levers = {}
    if forces is not None:
        sheets, levers = force_sheets(scene, motion, forces, scales, own, stem=stem, path=path, style=style)
        files.update(sheets)
        warnings.extend(force_warnings(scene, motion, forces, levers, own, path))
    data = report(scene, motion, scales, forces, levers, assembled)
    if cycle is not None:
        sheets, data["cycle"] = cycle_sheets(scene, cycle, scales, stem, style, assembled)
        files.update(sheets)
    if shaking is not None:          # "shaking" needs the cycle (the scene's reader sees to it)
        data["cycle"].update(shaking_report(shaking))
        files.update(shaking_sheets(scene, shaking, stem, style))
        if shaking.balanced is not None:
            data["counterweights"] = counterweights_report(shaking)
    if machine is not None:
        sheets, data["cycle"]["dynamics"] = dynamics_sheets(scene, machine, forces, levers, stem, style, started)
        files.update(sheets)
        warnings.extend(f"{path}: {w}" for w in dynamics_warnings(machine))
    if train is not None:
        files.update(gear_sheets(scene, train, stem, style))
        data["gears"] = gears_report(train)
        warnings.extend(f"{path}: {w}" for w in train.warnings)
    files[f"{stem}.json"] = report_text(data)
    return Rendered(stem, files, motion, scales, tuple(warnings), forces, train)


def _render_train(scene: Scene, train: GearAnalysis | None, *, stem: str, style: Style, found=None,
                  where: str | None = None) -> Rendered:
    """The files of gears alone: the train's sheet (when drawn) and report (with the candidates
    of ``[synthesis]``, the first drawn), and the involute pair's (``[gear_pair]``)."""
    files = gear_sheets(scene, train, stem, style, found=found[0] if found else None) if train is not None else {}
    data: dict = {"title": scene.title}
    warnings = list(train.warnings) if train is not None else []
    if train is not None:
        data["gears"] = gears_report(train)
    if found is not None:
        data["synthesis"] = synthesis_report(scene.synthesis, found)
    if scene.gear_pair is not None:
        try:
            pair = analyse_pair(scene.gear_pair, scene.gears, meshing="meshing" in scene.draw or not scene.draw)
        except PlansError as exc:
            raise exc.in_file(where) if where and hasattr(exc, "in_file") else exc
        data["gear_pair"] = pair_report(pair)
        files.update(pair_sheets(scene, pair, stem, style))
        warnings += pair.warnings
    files[f"{stem}.json"] = report_text(data)
    at = scene.file or f"scene {scene.title!r}"
    return Rendered(stem, files, None, None, tuple(f"{at}: {w}" for w in warnings), None, train)


def render(scene: Scene | str | os.PathLike, *, style: Style = Style(), stem: str | None = None) -> Sheets:
    """Render a scene: a :class:`~plans.scene.Scene` (from :func:`~plans.scene.read_scene` or
    :func:`~plans.scene.parse_scene`) or the path of a scene file. Nothing is read but that
    file, nothing is written (see :meth:`Sheets.save`).

    The files are named ``<stem>-<sheet>.svg`` and ``<stem>.json``: ``stem`` when given, else the
    scene file's stem (a Scene read from a file keeps it, so both ways give the same files byte
    for byte), else one made from the title (``"Crank-slider mechanism"`` → ``crank-slider_mechanism``).
    Errors are the :class:`~plans.errors.PlansError` of ``plans render``."""
    if isinstance(scene, (str, os.PathLike)):
        path = Path(scene)
        rendered = render_scene(path, style) if stem is None else \
            _render(read_scene(path), stem=checked_stem(stem), where=str(path), style=style)
        source: str | None = os.path.abspath(path)
    elif isinstance(scene, Scene):
        name = checked_stem(stem) if stem is not None else \
            file_stem(scene.file) if scene.file else stem_of(scene.title)
        rendered = _render(scene, stem=name, where=scene.file, style=style)
        source = os.path.abspath(scene.file) if scene.file else None
    else:
        raise TypeError(f"plans.render takes a Scene or the path of a scene file, not {type(scene).__name__}")
    return Sheets(rendered.stem, rendered.files, rendered.motion, rendered.scales, rendered.warnings, rendered.forces,
                  rendered.train, source)
