"""The ``-balancing`` sheet of a rotor alone (:mod:`plans.constructions.balancing`,
:mod:`plans.drawing.balancing`): its masses' table and the couple and force polygons that give
the balancing masses.

Reads a solved :class:`~plans.dynamics.balancing.RotorBalance`; imports nothing of the pipeline."""

from __future__ import annotations

from ...constructions.balancing import balance_polygons, shaft_planes
from ...drawing import Style
from ...drawing.balancing import draw_balancing
from ...drawing.svg import Heading
from ...dynamics.balancing import RotorBalance
from ...scene import Scene

__all__ = ["balancing_sheets"]


def balancing_sheets(scene: Scene, b: RotorBalance, stem: str, style: Style) -> dict[str, str]:
    """The sheet (file name → SVG)."""
    polygons = balance_polygons(b)
    kind = "two planes L and M: dynamic balance" if b.dynamic else "one plane L: static balance only"
    notes = [f"Balanced in {kind}. m·r and m·r·l are vectors along each mass's angle θ (counter-clockwise from "
             f"θ = 0); l is measured from the reference plane L (at {b.reference_plane:g} m along the shaft)."]
    if b.dynamic:
        notes.append("The couple polygon of the masses' m·r·l closes with (m·r·l)_{M}, which gives the mass in plane M "
                     "(its l known); the force polygon of the masses' m·r and (m·r)_{M} closes with (m·r)_{L}, the "
                     "mass in plane L.")
    else:
        notes.append("The force polygon of the masses' m·r closes with (m·r)_{L}; the couple of the masses in other "
                     "planes stays (one plane balances forces only).")
    for name, p in zip(("L", "M"), b.balancing):
        notes.append(f"Plane {name} ({p.plane:g} m): m = {p.mass:.5g} kg at r = {p.radius:g} m, θ = {p.angle:.4g}°.")
    heading = Heading(scene.title, "Balancing of rotating masses", f"{len(b.masses)} masses" +
                      (f", n = {b.rpm:g} rpm" if b.rpm else ""))
    return {f"{stem}-balancing.svg": draw_balancing(b, polygons, shaft_planes(b), heading, ident="balancing",
                                                    style=style, notes=tuple(notes))}
