"""Gear trains (textbook §3): the structure of a train (links, meshes, W = 3n − 2p5 − p4), its
speeds solved exactly in fractions (Willis' formula per mesh), the geometry conditions of a
planetary train, and a train driving a linkage's crank.

Imports only plans.errors and plans.scene (and the standard library).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from ..scene import Scene
from ..scene.drive import check_train_speed
from ..scene.gears import GearTrain
from .geometry import TrainGeometry, assembly_number, internal_interference, planet_sets, train_geometry
from .involute import GearPair, gear_pair, inv, inv_inverse, min_shift
from .speeds import TrainSpeeds, Willis, carrier_ratio, central_links, exact, solve_train, tabular
from .train import GearLink, Mesh, PassivePlanet, TrainStructure, train_structure

__all__ = ["GearAnalysis", "analyse_train", "with_train", "TrainSpeeds", "TrainStructure", "TrainGeometry",
           "GearLink", "Mesh", "PassivePlanet", "Willis", "solve_train", "train_structure", "train_geometry", "tabular",
           "carrier_ratio", "central_links", "assembly_number", "planet_sets", "exact", "GearPair", "gear_pair", "inv",
           "inv_inverse", "min_shift"]


@dataclass(frozen=True)
class GearAnalysis:
    """A solved train: its speeds and, where modules are given, its geometry (None otherwise)."""

    speeds: TrainSpeeds
    geometry: TrainGeometry | None

    @property
    def warnings(self) -> tuple[str, ...]:
        """One line each: undercut wheels, and the geometry left unchecked (no modules, or a
        condition the checks do not cover, such as the assembly of a carrier's planets); without
        modules, an internal mesh's tip interference (refused when modules are given)."""
        if self.geometry is None:
            return ("the wheels have no module: the train is solved from its teeth alone, its geometry "
                    "(coaxial, assembly, neighbourhood, undercut) went unchecked",
                    *internal_interference(self.speeds.structure))
        return self.geometry.warnings + self.geometry.unchecked


def analyse_train(train: GearTrain) -> GearAnalysis:
    """Solve ``train`` and check its geometry (refusals are :class:`~plans.errors.StructureError`)."""
    speeds = solve_train(train)
    return GearAnalysis(speeds=speeds, geometry=train_geometry(speeds.structure))


def with_train(scene: Scene, analysis: GearAnalysis) -> Scene:
    """``scene`` with its crank's ω set from the train: ω of ``[gears] output`` (rad/s), refused
    where a written ``omega`` would be, at the train's input key (:func:`check_train_speed`)."""
    assert scene.gears is not None and scene.gears.output is not None and scene.drive is not None
    omega = analysis.speeds.omega(scene.gears.output)
    inputs = scene.gears.inputs
    name, rpm = inputs[0] if inputs else ("", 0.0)
    key = f"gears.input.{name}" if len(inputs) == 1 else "gears.input"
    check_train_speed(omega, scene.drive.rate, key, omega / rpm if len(inputs) == 1 and rpm != 0.0 else None)
    return dataclasses.replace(scene, drive=dataclasses.replace(scene.drive, speed=omega))
