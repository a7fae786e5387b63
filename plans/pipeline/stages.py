"""The pipeline's computing stages for one scene: the motion, solved to the order its drawings
need (one analysis, or the revolution of ``[drive] positions``), and the force analysis; and
:func:`record_stages`, which records them as they run.

This is the pipeline's one kinematics step: of plans.kinematics it calls analyse and
solve_cycle only. It imports nothing of the pipeline's sheets, report or API."""

from __future__ import annotations

import contextlib
from dataclasses import replace
from typing import Iterator

import numpy as np

from ..dynamics import MachineDynamics, Startup, at_true_speed, machine_dynamics, startup
from ..dynamics.laws import check_laws, law_values
from ..dynamics.shaking import ShakingAnalysis, shaking_analysis
from ..kinematics import Motion, analyse
from ..errors import SceneError
from ..kinematics.assemblies import GroupAssemblies, assemblies, group_assemblies
from ..kinematics.cycle import Cycle, solve_cycle
from ..kinematics.walk import fmt
from ..kinetostatics import Forces, Travel, forces_following, solve_forces
from ..model import build_mechanism
from ..scene import Scene
from ..structure import analyse_structure

__all__ = ["record_stages", "solve_scene", "solve_motion", "force_analysis", "output_travel", "machine_motion",
           "assembly_analysis", "shaking_forces"]

#: The stages run, in order, while :func:`record_stages` is active (None otherwise).
_stages: list[str] | None = None
#: The kinematic stages an order of analysis runs.
_ORDER_STAGES = ("positions", "velocities", "accelerations")


@contextlib.contextmanager
def record_stages() -> Iterator[list[str]]:
    """Record the computing stages each render runs (``positions``, ``velocities``,
    ``accelerations``, ``forces``, ``dynamics``, ``shaking``), in order, into the list it yields."""
    global _stages
    previous, _stages = _stages, []
    try:
        yield _stages
    finally:
        _stages = previous


def _ran(*stages: str) -> None:
    if _stages is not None:
        _stages.extend(stages)


def solve_scene(scene: Scene) -> Motion:
    """Solve a scene to the order its drawings need (scheme only: positions; the senses of
    ω and ε on the scheme: accelerations)."""
    return solve_motion(scene)[0]


def solve_motion(scene: Scene) -> tuple[Motion, Cycle | None]:
    """The scene's motion and, with ``[drive] positions``, its solved revolution (the motion
    is then the revolution's N positions). With ``[plans] assembly``, the walk starts from the
    named assemblies at the first analysed position (:func:`with_assembly`)."""
    motion, cycle = _solve_motion(scene)
    if not scene.assembly:
        return motion, cycle
    return _solve_motion(with_assembly(scene, motion))


def with_assembly(scene: Scene, motion: Motion) -> Scene:
    """The scene sketched at the motion's first position with each group named in ``[plans]
    assembly`` in its assembly of that number (1 … n, as the ``-assemblies`` sheet and the JSON
    number them). Refused in one line: a name that is no group, a number beyond the group's count,
    a group with groups attached after it (they would have to be re-assembled too), a linear drive
    (its displacements count from the sketch)."""
    groups = {g.name: g for g in motion.structure.groups}
    if not motion.mechanism.drive.kind.angular:
        raise SceneError("choosing an assembly re-sketches the mechanism at its first position: the drive must turn "
                         "(its displacements count from the sketch)", key="plans.assembly")
    points = {p: tuple(float(c) for c in motion.position(p)[0]) for p in scene.points}
    value = fmt(motion.mechanism, float(motion.values[0]))
    for name, k in scene.assembly.items():
        g = groups.get(name)
        if g is None:
            raise SceneError(f"{name!r} is no group of this mechanism; its groups are {', '.join(groups)}",
                             key=f"plans.assembly.{name}")
        later = motion.structure.groups[motion.structure.groups.index(g) + 1:]
        mine = {p for link in g.links for p in motion.mechanism.links[link].points}
        if any(mine & {p for link in h.links for p in motion.mechanism.links[link].points} for h in later):
            raise SceneError(f"group {name} has groups attached after it, which would have to be re-assembled too; "
                             "only the last group's assembly (or a group nothing is attached to) can be chosen",
                             key=f"plans.assembly.{name}")
        found = group_assemblies(motion, g, 0)
        if not k <= found.count:
            raise SceneError(f"group {name} has {found.count} real assemblies at {value}, not {k}: see its "
                             "-assemblies sheet (draw = [..., \"assemblies\"])", key=f"plans.assembly.{name}")
        points.update(found.assemblies[k - 1].points)
    return replace(scene, points=points, assembly={})


def _solve_motion(scene: Scene) -> tuple[Motion, Cycle | None]:
    mech = build_mechanism(scene)
    structure = analyse_structure(mech)
    order = 2 if "acceleration" in scene.draw or scene.senses else \
        1 if {"velocity", "centres", "velocities"} & set(scene.draw) else 0
    if scene.wants_forces:      # the power balance needs velocities, inertia accelerations
        order = max(order, 2 if scene.wants_inertia else 1)
    if scene.dynamics is not None and scene.dynamics.true_speed:    # ε1 ≠ 0: accelerations at the true speed
        order = 2
    if "shaking" in scene.draw:     # the shaking force: the centres' accelerations
        order = 2
    _ran(*_ORDER_STAGES[:order + 1])
    c = scene.cycle
    if c is None:
        return analyse(mech, structure, order=order), None
    cycle = solve_cycle(mech, structure, positions=c.positions, output=c.output, order=order,
                        start=None if c.start == "extreme" else scene.drive.values[0],
                        dense_order=2 if "diagrams" in scene.draw else 0)
    return cycle.motion, cycle


def force_analysis(scene: Scene, motion: Motion, cycle: Cycle | None = None) -> Forces | None:
    """The force analysis when the scene asks for it (force plans, the lever, or [balance]);
    forces that follow the output read its travel over ``cycle``."""
    if not scene.wants_forces:
        return None
    _ran("forces")
    laws = None
    if any(m.law is not None for m in scene.moments):       # over one turn (check_laws): θ_k = k·|step|
        check_laws(scene)
        laws = law_values(scene, np.radians(abs(cycle.step)) * np.arange(len(motion)))
    return solve_forces(motion, scene, travel=output_travel(scene, cycle), laws=laws)


def output_travel(scene: Scene, cycle: Cycle | None) -> Travel | None:
    """The output link's travel at the cycle's positions, when a force follows it (a law or a
    stroke); None otherwise. A cycle whose output turns fully has no extremes to measure from:
    refused, naming the force."""
    if cycle is None or not forces_following(scene, cycle):
        return None
    out, ext = cycle.output, cycle.extreme_output
    return Travel(link=out.link, kind=out.kind, s=out.s, v=out.v, low=float(ext.s[0]), high=float(ext.s[1]),
                  scale=float(np.max(np.abs(out.v))))


def assembly_analysis(scene: Scene, motion: Motion) -> list[dict[str, GroupAssemblies]] | None:
    """Every group's real assemblies at every analysed position (position → group name →
    :class:`~plans.kinematics.assemblies.GroupAssemblies`) when the scene asks for them
    (``draw = [..., "assemblies"]``); None otherwise (then nothing is computed). They go into
    the JSON report and the ``-assemblies`` sheets (:mod:`.sheets.assemblies`)."""
    if "assemblies" not in scene.draw:
        return None
    if not motion.structure.groups:
        raise SceneError(f"draw \"assemblies\" lists the assemblies of each Assur group, and this mechanism has none "
                         f"(the drive closes the chain itself: {motion.structure.formula}); remove \"assemblies\" "
                         "from draw", key="plans.draw")
    _ran("assemblies")
    return [assemblies(motion, i) for i in range(len(motion))]


def machine_motion(scene: Scene, cycle: Cycle | None) -> MachineDynamics | None:
    """The machine's steady cycle under its loads, when the scene has ``[dynamics]``."""
    if scene.dynamics is None or cycle is None:
        return None
    _ran("dynamics")
    return machine_dynamics(scene, cycle)


def true_speed_motion(scene: Scene, cycle: Cycle, machine: MachineDynamics) -> tuple[Motion, Cycle]:
    """The cycle's positions at the crank's true ω1(φ), ε1(φ) (``[dynamics] true_speed``)."""
    _ran("true_speed")
    w = machine.sense * machine.omega(machine.theta)
    e = machine.sense * machine.epsilon(machine.theta)
    motion = at_true_speed(cycle.motion, w, e)
    return motion, replace(cycle, motion=motion)


def machine_startup(scene: Scene, machine: MachineDynamics | None) -> Startup | None:
    """The start-up by the motor in time, when ``[dynamics]`` asks to simulate it."""
    if machine is None or scene.dynamics.simulate is None:
        return None
    _ran("startup")
    return startup(machine, scene.dynamics.motor, scene.dynamics.simulate.t_end)


def shaking_forces(scene: Scene, motion: Motion) -> ShakingAnalysis | None:
    """The shaking force, moment and centre of mass over the cycle, with the counterweights of
    ``[counterweights]`` (:func:`plans.dynamics.shaking.shaking_analysis`), when ``draw`` holds
    ``"shaking"``; None otherwise (then nothing of it is computed)."""
    if "shaking" not in scene.draw:
        return None
    _ran("shaking")
    return shaking_analysis(motion, scene)
