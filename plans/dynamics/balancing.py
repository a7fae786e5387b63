"""The balancing of rotating masses (``[rotor]``): the masses that balance a rotor in one plane
(static balance: Σ m·r = 0) or in two (dynamic balance: Σ m·r = 0 and Σ m·r·l = 0), found as
the textbook finds them with a reference plane (Khurmi & Gupta, *Theory of Machines*, ch.
"Balancing of Rotating Masses", several masses in different planes):

1. the reference plane R is the first balancing plane; every l is measured from it along the
   shaft (m, + the way the planes' coordinate grows), so R's balancing mass has no couple;
2. the couple polygon: the masses' m·r·l vectors in order, closed by the other balancing plane's
   m·r·l, which gives its mass and angle;
3. the force polygon: the masses' m·r vectors, then the other plane's just found, closed by the
   reference plane's m·r.

Every vector is a complex number x + i·y in the end view: x along the reference angle 0, y at
90° counter-clockwise (the sense the scene's angles are given in); the polygons are summed
exactly as vectors, nothing is measured. One plane: the force polygon alone; the couple stays
and is reported. Numeric; never draws.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..errors import SceneError
from ..scene.rotor import RotorSpec

__all__ = ["RotatingMass", "BalancingMass", "RotorBalance", "balance_rotor", "phasor", "angle_of", "SNAP"]

#: A balancing m·r (or m·r·l) within this fraction of its polygon's size (the sum of its sides'
#: lengths) is rounding: the rotor needs no mass there, reported as 0 kg at 0°. The sums' rounding
#: is a few 1e-16 of that size; 1e-13 leaves the residuals within 1e-12 of it.
SNAP = 1e-13


def phasor(magnitude: float, angle: float) -> complex:
    """``magnitude`` along ``angle`` (degrees, counter-clockwise from 0) as x + i·y; exact at
    whole multiples of 90° (a mass at 90° has x = 0, not 6e-17)."""
    a = angle % 360.0
    if a % 90.0 == 0.0:
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(a // 90.0) % 4]
    else:
        t = math.radians(a)
        c, s = math.cos(t), math.sin(t)
    return complex(magnitude * c, magnitude * s)


def angle_of(z: complex) -> float:
    """The direction of ``z`` in degrees, in [0, 360) (0 for the zero vector, of either sign)."""
    if z == 0:
        return 0.0
    a = math.degrees(math.atan2(z.imag, z.real)) + 0.0
    if a < 0.0:
        a += 360.0
    return 0.0 if a >= 360.0 else a


@dataclass(frozen=True)
class RotatingMass:
    """One of the rotor's masses: ``mass`` (kg), ``radius`` (m), ``angle`` (degrees, counter-
    clockwise from the reference angle 0, as given), ``plane`` (m along the shaft as given; None
    when the scene gives none: one balancing plane, the mass turns in it), ``l`` = plane − the
    reference plane (m; 0 for a mass without a plane), ``mr`` = m·r·e^{iθ} (kg·m) and ``mrl`` =
    mr·l (kg·m²): the sides of the force and the couple polygon."""

    mass: float
    radius: float
    angle: float
    plane: float | None
    l: float
    mr: complex
    mrl: complex


@dataclass(frozen=True)
class BalancingMass:
    """The mass that balances in one plane: ``plane`` (m along the shaft, as given), ``radius``
    (m, as given), ``mass`` (kg) and ``angle`` (degrees in [0, 360), counter-clockwise from the
    reference angle 0), ``l`` (m from the reference plane: 0 for the reference plane itself),
    ``mr`` (kg·m) and ``mrl`` (kg·m²) its vectors as the polygons close them."""

    plane: float
    radius: float
    mass: float
    angle: float
    l: float
    mr: complex
    mrl: complex


@dataclass(frozen=True)
class RotorBalance:
    """A rotor and the masses that balance it (see the module for the method and the signs).

    ``masses``: the rotor's masses in scene order. ``reference_plane`` (m): the first balancing
    plane, from which every l is measured. ``balancing``: one :class:`BalancingMass` a plane, in
    the scene's order (the reference plane's first). ``couple_polygon`` (kg·m²): the masses'
    m·r·l about the reference plane, in scene order (a mass in the reference plane adds a zero
    side); ``couple_closing`` (kg·m²): the vector that closes it, the other balancing plane's
    m·r·l (None with one plane: nothing balances the couple). ``force_polygon`` (kg·m): the
    masses' m·r in scene order, then (two planes) the other plane's m·r just found;
    ``force_closing`` (kg·m): the vector that closes it, the reference plane's m·r. ``rpm``: the
    shaft's speed (None: not given, no forces)."""

    masses: tuple[RotatingMass, ...]
    reference_plane: float
    balancing: tuple[BalancingMass, ...]
    couple_polygon: tuple[complex, ...]
    couple_closing: complex | None
    force_polygon: tuple[complex, ...]
    force_closing: complex
    rpm: float | None = None

    @property
    def dynamic(self) -> bool:
        """Balanced in two planes (forces and couples); False: one plane (forces only)."""
        return len(self.balancing) == 2

    @property
    def omega(self) -> float | None:
        """The shaft's angular speed ω = 2π·n/60, rad/s (None without rpm)."""
        return None if self.rpm is None else 2.0 * math.pi * self.rpm / 60.0

    @property
    def force_mr(self) -> complex:
        """Σ m·r of the rotor's masses before balancing, kg·m."""
        return sum((m.mr for m in self.masses), 0j)

    @property
    def couple_mrl(self) -> complex:
        """Σ m·r·l of the rotor's masses about the reference plane before balancing, kg·m²."""
        return sum((m.mrl for m in self.masses), 0j)

    @property
    def unbalanced_force(self) -> float | None:
        """|the centrifugal force| before balancing, ω²·|Σ m·r| (N); None without rpm."""
        return None if self.omega is None else self.omega ** 2 * abs(self.force_mr)

    @property
    def unbalanced_couple(self) -> float | None:
        """|the centrifugal couple about the reference plane| before balancing, ω²·|Σ m·r·l|
        (N·m); None without rpm. While a force is unbalanced the couple depends on the plane it is
        taken about; the reference plane is the textbook's (its couple polygon closes on it)."""
        return None if self.omega is None else self.omega ** 2 * abs(self.couple_mrl)

    def _balanced(self) -> tuple[complex, ...]:
        """Each balancing m·r as reported: rebuilt from its mass, radius and angle."""
        return tuple(phasor(b.mass * b.radius, b.angle) for b in self.balancing)

    @property
    def residual_mr(self) -> complex:
        """Σ m·r after balancing (kg·m): the masses and the balancing masses as reported; zero
        up to rounding."""
        return self.force_mr + sum(self._balanced(), 0j)

    @property
    def residual_mrl(self) -> complex:
        """Σ m·r·l about the reference plane after balancing (kg·m²): zero up to rounding in two
        planes; in one plane, the couple that stays (the same about every plane, the force being
        balanced)."""
        return self.couple_mrl + sum((u * b.l for u, b in zip(self._balanced(), self.balancing)), 0j)


def _snap(z: complex, size: float) -> complex:
    return 0j if abs(z) <= SNAP * size else z


def _mass_of(u: complex, plane: float, radius: float, l: float, mrl: complex) -> BalancingMass:
    """The balancing mass whose m·r is ``u`` (kg·m) at ``radius`` (m), in ``plane``."""
    mass = abs(u) / radius
    if not math.isfinite(mass):
        raise SceneError(f"the balancing mass in plane {plane:g} m would be too large to compute at radius "
                         f"{radius:g} m; give a larger radius", key="rotor.balance.radius")
    return BalancingMass(plane=plane, radius=radius, mass=mass, angle=angle_of(u), l=l, mr=u, mrl=mrl)


def balance_rotor(spec: RotorSpec) -> RotorBalance:
    """The masses that balance ``spec``'s rotor (one plane: static; two: dynamic), by the
    reference-plane method of the module."""
    ref = spec.planes[0]
    masses = []
    for m in spec.masses:
        l = 0.0 if m.plane is None else m.plane - ref
        mr = phasor(m.mass * m.radius, m.angle)
        masses.append(RotatingMass(mass=m.mass, radius=m.radius, angle=m.angle, plane=m.plane, l=l, mr=mr,
                                   mrl=mr * l))
    couple = tuple(m.mrl for m in masses)
    forces = [m.mr for m in masses]
    closing = None
    other = None
    if spec.dynamic:
        l_other = spec.planes[1] - ref
        closing = _snap(-sum(couple, 0j), sum(abs(c) for c in couple))
        other = _mass_of(closing / l_other, spec.planes[1], spec.radii[1], l_other, closing)
        forces.append(other.mr)
    force_closing = _snap(-sum(forces, 0j), sum(abs(f) for f in forces))
    first = _mass_of(force_closing, ref, spec.radii[0], 0.0, 0j)
    return RotorBalance(masses=tuple(masses), reference_plane=ref,
                        balancing=(first,) if other is None else (first, other), couple_polygon=couple,
                        couple_closing=closing, force_polygon=tuple(forces), force_closing=force_closing,
                        rpm=spec.rpm)
