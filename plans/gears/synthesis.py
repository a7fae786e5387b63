"""Planetary synthesis: the teeth of the four standard 2K-H schemes for a given ratio and number
of planets, under the coaxial, assembly and neighbourhood conditions, without undercut.

The schemes (one module, standard wheels ha* = 1, no profile shift; i is input → output):

- **A**: sun a → planet g → fixed ring b; input a, output H: i = 1 + z_b/z_a.
- **B**: sun a → planet block g–g2 → fixed ring b; input a, output H: i = 1 + z_g·z_b/(z_a·z_g2).
- **C**: ring b1 → planet block g–g2 → fixed ring b2; input H, output b1:
  i = 1/(1 − z_g·z_b2/(z_b1·z_g2)).
- **D**: sun a → planet block g–g2 → fixed sun b (all external); input H, output a:
  i = 1/(1 − z_g·z_b/(z_a·z_g2)).

Conditions: coaxial (one arm for both meshes), assembly (k equally spaced identical planets:
z_a·(1 − i_ab^H)·z_g2/(k·gcd(z_g, z_g2)) whole), neighbourhood (adjacent planets' tip circles
apart: 2·a_w·sin(π/k) > the largest planet's tip diameter), no undercut (external wheels at
least 17 teeth) and no internal interference (a ring at least 8 teeth more than its planet).

Every candidate the enumeration keeps is then built as a train and solved by
:func:`plans.gears.analyse_train`, whose ratio and geometry checks — not the formulas above —
decide what is printed.

Imports only plans.errors, plans.scene and plans.gears (and the standard library).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from ..errors import PlansError, SceneError
from ..scene.gears import GearTrain, Wheel
from . import analyse_train

__all__ = ["Candidate", "synthesize", "TYPES", "MIN_TEETH", "MAX_TEETH", "RING_MARGIN"]

#: The input speed of a found train (its ratio does not depend on it), rpm.
INPUT_RPM = 1000.0
#: The schemes.
TYPES = ("A", "B", "C", "D")
#: Teeth of an external wheel: at least MIN_TEETH (no undercut), at most MAX_TEETH.
MIN_TEETH, MAX_TEETH = 17, 100
#: A ring gear has at least RING_MARGIN more teeth than the planet inside it (no interference).
RING_MARGIN = 8
#: A ring gear has at most this many teeth.
MAX_RING = 250


@dataclass(frozen=True)
class Candidate:
    """One verified set of teeth: ``kind`` (A … D), ``teeth`` name → z, ``ratio`` (exact, from the
    solved train), ``size`` the largest pitch diameter in modules (the overall size), and the
    ``train`` as a scene would give it."""

    kind: str
    teeth: dict[str, int]
    ratio: Fraction
    size: int
    train: GearTrain

    @property
    def error(self) -> float:
        return float(self.ratio)


def _ratio(kind: str, z: tuple[int, ...]) -> Fraction | None:
    if kind == "A":
        za, zg, zb = z
        return 1 + Fraction(zb, za)
    a, g, g2, b = z
    u = Fraction(g * b, a * g2)
    if kind == "B":
        return 1 + u
    return None if u == 1 else 1 / (1 - u)


def _enumerate(kind: str, target: float, tolerance: float):
    """Teeth tuples of ``kind`` whose ratio (by the formula) is within ``tolerance`` of ``target``."""
    ext = range(MIN_TEETH, MAX_TEETH + 1)
    lo, hi = target * (1 - tolerance), target * (1 + tolerance)
    lo, hi = min(lo, hi), max(lo, hi)
    if kind == "A":
        for a in ext:
            for g in ext:
                b = a + 2 * g
                if b - g >= RING_MARGIN and b <= MAX_RING and lo <= 1 + b / a <= hi:
                    yield (a, g, b)
        return
    for g in ext:
        for g2 in ext:
            if kind == "C":
                for b1 in range(g + RING_MARGIN, MAX_RING + 1):
                    b2 = b1 - g + g2
                    if b2 - g2 < RING_MARGIN or b2 > MAX_RING or g * b2 == b1 * g2:
                        continue
                    if lo <= 1.0 / (1.0 - g * b2 / (b1 * g2)) <= hi:
                        yield (b1, g, g2, b2)
                continue
            for a in ext:
                b = a + g + g2 if kind == "B" else a + g - g2
                if kind == "B" and (b - g2 < RING_MARGIN or b > MAX_RING):
                    continue
                if kind == "D" and not MIN_TEETH <= b <= MAX_TEETH:
                    continue
                u = g * b / (a * g2)
                if kind == "B":
                    r = 1.0 + u
                elif g * b == a * g2:
                    continue
                else:
                    r = 1.0 / (1.0 - u)
                if lo <= r <= hi:
                    yield (a, g, g2, b)


def _quick_conditions(kind: str, z: tuple[int, ...], k: int) -> bool:
    """The assembly and neighbourhood conditions by their formulas (a filter; the train's own
    checks decide)."""
    if kind == "A":
        a, g, b = z
        return (a + b) % k == 0 and (a + g) * math.sin(math.pi / k) > g + 2
    a, g, g2, b = z
    i_ab = {"B": -Fraction(g * b, a * g2), "C": Fraction(g * b, a * g2), "D": Fraction(g * b, a * g2)}[kind]
    n = a * (1 - i_ab) * g2 / (k * math.gcd(g, g2))
    arm = (a - g) if kind == "C" else (a + g)
    return n.denominator == 1 and arm * math.sin(math.pi / k) > max(g, g2) + 2


def _train(kind: str, z: tuple[int, ...], k: int, module: float) -> GearTrain:
    if kind == "A":
        a, g, b = z
        wheels = (Wheel("a", a, module), Wheel("g", g, module, on="H"), Wheel("b", b, module, internal=True))
        return GearTrain(wheels=wheels, carriers=("H",), meshes=(("a", "g"), ("g", "b")), fixed=("b",), planets=k,
                         inputs=(("a", INPUT_RPM),))
    a, g, g2, b = z
    ring1, ring2 = kind == "C", kind in ("B", "C")
    names = ("b1", "g", "g2", "b2") if kind == "C" else ("a", "g", "g2", "b")
    wheels = (Wheel(names[0], a, module, internal=ring1), Wheel("g", g, module, on="H"),
              Wheel("g2", g2, module, on="H", shaft="g"), Wheel(names[3], b, module, internal=ring2))
    inputs = (("a", INPUT_RPM),) if kind == "B" else (("H", INPUT_RPM),)
    return GearTrain(wheels=wheels, carriers=("H",), meshes=((names[0], "g"), ("g2", names[3])), fixed=(names[3],),
                     planets=k, inputs=inputs)


def _verified(kind: str, z: tuple[int, ...], k: int, module: float) -> Candidate | None:
    """The candidate as the analysis finds it, or None when the solved train refuses it."""
    train = _train(kind, z, k, module)
    try:
        analysis = analyse_train(train)
    except PlansError:
        return None
    if analysis.geometry is None or analysis.geometry.warnings or analysis.geometry.unchecked:
        return None
    speeds = analysis.speeds
    src = "a" if kind in ("A", "B") else "H"
    dst = "H" if kind in ("A", "B") else train.wheels[0].name
    ratio = speeds.ratio(src, dst)
    if ratio is None:
        return None
    teeth = {w.name: w.teeth for w in train.wheels}
    return Candidate(kind=kind, teeth=teeth, ratio=ratio, size=max(teeth.values()), train=train)


def synthesize(ratio: float, kind: str, planets: int, *, tolerance: float = 0.01, module: float = 1.0,
               limit: int = 10) -> tuple[Candidate, ...]:
    """The best ``limit`` verified candidates of scheme ``kind`` for ``ratio`` (input → output,
    within ``tolerance``, relative) with ``planets`` equally spaced planets, smallest first
    (by the largest wheel, then by the ratio's error). Empty when the scheme cannot reach it."""
    if kind not in TYPES:
        raise SceneError(f"unknown scheme {kind!r}; one of {', '.join(TYPES)}", key="--type")
    if not (isinstance(ratio, (int, float)) and math.isfinite(ratio) and abs(ratio) > 1.0):
        raise SceneError(f"a reducer's ratio is a number beyond ±1, got {ratio!r}", key="--ratio")
    if not (isinstance(planets, int) and 2 <= planets <= 12):
        raise SceneError(f"planets is a whole number 2 … 12, got {planets!r}", key="--planets")
    if not (math.isfinite(tolerance) and 0.0 < tolerance <= 0.2):
        raise SceneError(f"tolerance is a fraction above 0 and at most 0.2 (0.01 = 1 %), got {tolerance!r}",
                         key="--tolerance")
    if not (math.isfinite(module) and 0.05 <= module <= 100.0):
        raise SceneError(f"module is 0.05 … 100 mm, got {module!r}", key="--module")
    pool = [z for z in _enumerate(kind, ratio, tolerance) if _quick_conditions(kind, z, planets)]
    pool.sort(key=lambda z: (max(z), abs(float(_ratio(kind, z)) - ratio), z))     # smallest first
    out: list[Candidate] = []
    for z in pool:
        c = _verified(kind, z, planets, module)
        if c is not None and abs(float(c.ratio) - ratio) <= tolerance * abs(ratio):
            out.append(c)
            if len(out) == limit:
                break
    return tuple(out)
