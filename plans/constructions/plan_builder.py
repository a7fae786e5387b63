"""How a plan is collected and labelled: :class:`_Builder` keeps a plan's images (keyed by
what they are), vectors and lines, reads each image's v or a from the motion, leaves out a
segment drawn twice, and makes the printed labels unique (primes; ``n``/``k`` ends yield to
images printed with those letters).

**Quantity names.** The point of link L now at X (a block's pin on its guide) is named ``XL``
in the quantities (``v:A3/A2``), which ``plans check`` reads to join the ends of vectors.
Where that joined name would read like another thing — a scene point of that name (a point
``A3`` beside point A of link 3), or another point and link that join to the same text (A of
link 33 and A3 of link 3) — it is written ``X@L`` instead (``v:A@3/A2``; primed if even that
is a point's name), and its image's printed label gets a prime (``a3′`` beside the point's
``a3``). Scenes without such a clash keep their names (:func:`joined_names`).

Reads :class:`~plans.kinematics.Motion` only; must not import the relations or the
constructions that use the builder.
"""

from __future__ import annotations

from collections import Counter
from functools import lru_cache

import numpy as np

from ..kinematics import Motion
from ..kinematics.sliders import Sliding
from ..scene import FRAME
from .plan_values import EXTENSION_MM, MIN_DRAWN_MM, ConstructionLine, PlanPoint, PlanVector
from .. import linalg as la


def _label(motion: Motion, point: str, link: str) -> str:
    """``B`` when ``link`` carries B, else ``B3`` (the point of link 3 now at B)."""
    return point if point in motion.mechanism.links[link].local else f"{point}{link}"


#: Marks a plan label that would otherwise repeat another (a point named P beside the pole p).
PRIME = "′"
#: Joins a point's and a link's names where the plain join would be ambiguous (``A@3``).
JOIN = "@"


@lru_cache(maxsize=8)
def joined_names(points: tuple[str, ...], links: tuple[str, ...]) -> dict[tuple[str, str], str]:
    """The quantity name of the point of link L at X, for every scene point X and link L:
    ``XL``, unless that is a point's name or the join of another pair, then ``X@L`` (primed
    while that is taken). Each name names one pair and no point."""
    plain = {(x, l): x + l for x in points for l in links}
    count = Counter(plain.values())
    names = set(points)
    out = {k: n for k, n in plain.items() if count[n] == 1 and n not in names}
    taken = names | set(out.values())
    for (x, l), n in plain.items():
        if (x, l) in out:
            continue
        name = x + JOIN + l
        while name in taken:
            name += PRIME
        taken.add(name)
        out[(x, l)] = name
    return out
#: Kinds of component ends (image keys) and their letters: normal ``n``, Coriolis ``k``.
COMPONENT_ENDS = ("n", "k")


def _at_pole(xy) -> bool:
    return float(np.hypot(xy[0], xy[1])) <= MIN_DRAWN_MM


def _same(p, q) -> bool:
    return float(np.hypot(p[0] - q[0], p[1] - q[1])) <= MIN_DRAWN_MM


class _Builder:
    """Collects a plan's images, vectors and lines. Images are keyed by what they are (the
    pole, the image of point X of link L, an n or k end), never by their printed label, so a
    point named ``P`` or ``n_BA`` cannot land on the pole or on a component's end; labels are
    made unique only when the plan is finished (:meth:`plan_points`)."""

    def __init__(self, motion: Motion, i: int, mu: float, kind: str):
        self.motion, self.i, self.mu, self.kind = motion, i, mu, kind
        self.points: dict[tuple, tuple[float, float]] = {}
        self.names: dict[tuple, str] = {}
        self.vectors: list[PlanVector] = []
        self.lines: list[ConstructionLine] = []
        self.extra: dict[str, np.ndarray] = {}   # constructed points (special points S1…): world position
        self.optional: set[str] = set()          # relative vectors left out where an absolute one draws them

    def put(self, key: tuple, label: str, xy) -> tuple[float, float]:
        """Record an image (first one wins) under ``key``, printed as ``label``."""
        if key not in self.points:
            self.points[key] = tuple(float(c) for c in xy)
            self.names[key] = label
        return self.points[key]

    def image_key(self, point: str, link: str) -> tuple:
        if point in self.extra:
            return ("img", point, "")
        return ("img", point, "" if point in self.motion.mechanism.links[link].local else link)

    def plan_points(self) -> tuple[tuple[PlanPoint, ...], dict[tuple, str]]:
        """The images with unique labels (a repeat gets primes, in the order drawn) and the
        label each key got. The pole and the images of points are labelled first; the ends of
        components (keys ``n``, ``k``) then take a letter no image is printed with (n, else
        n′, n″ …; k likewise), so a printed letter never names two things."""
        taken: set[str] = set()
        final: dict[tuple, str] = {}
        ends = [k for k in self.points if k[0] in COMPONENT_ENDS]
        for key in self.points:
            if key[0] not in COMPONENT_ENDS:
                final[key] = self._unique(self.names[key], taken)
        printed = {label.partition("_")[0] for label in final.values()}   # as drawn: letter, subscript
        letters = {}
        for kind in COMPONENT_ENDS:
            letters[kind] = kind
            while letters[kind] in printed:
                letters[kind] += PRIME
        for key in ends:
            label = self.names[key]
            final[key] = self._unique(letters[key[0]] + label[len(key[0]):], taken)
        return tuple(PlanPoint(final[k], xy) for k, xy in self.points.items()), final

    @staticmethod
    def _unique(label: str, taken: set[str]) -> str:
        while label in taken:
            label += PRIME
        taken.add(label)
        return label

    def fixed(self, point: str, link: str) -> bool:
        """True when ``link``'s point at ``point`` is a pair with the frame (its image is the pole)."""
        links = self.motion.mechanism.links
        return point not in self.extra and link != FRAME and point in links[FRAME].local and point in links[link].local

    def world(self, point: str) -> np.ndarray:
        if point in self.extra:
            return self.extra[point]
        return self.motion.position(point)[self.i]

    def label(self, point: str, link: str) -> str:
        """How the point of ``link`` at ``point`` is printed (its image in lower case): ``B``
        when ``link`` carries B (or B is a constructed point), else :meth:`joined_label`."""
        if point in self.extra or point in self.motion.mechanism.links[link].local:
            return point
        return self.joined_label(point, link)

    def joined_label(self, point: str, link: str) -> str:
        """``B3`` for the point of link 3 at B, primed (``B3′``) where its quantity name is
        ``B@3`` (the plain join names something else too, :func:`joined_names`)."""
        plain = point + link
        return plain if self.joined(point, link) == plain else plain + PRIME

    def joined(self, point: str, link: str) -> str:
        """The quantity name of the point of ``link`` at ``point`` written with its link, as
        a sliding pair's ends are (``B3``; ``B@3`` on a clash, see :func:`joined_names`)."""
        mech = self.motion.mechanism
        return joined_names(tuple(mech.sketch), tuple(mech.links))[(point, link)]

    def name(self, point: str, link: str) -> str:
        """The quantity name of the point of ``link`` at ``point``: ``B`` when ``link`` carries
        B (or B is a constructed point such as S1), else :meth:`joined`."""
        if point in self.extra or point in self.motion.mechanism.links[link].local:
            return point
        return self.joined(point, link)

    def quantity(self, point: str, link: str) -> np.ndarray:
        """v (m/s) or a (m/s²) of the point of ``link`` now at ``point``, as the motion gives it."""
        at = self.motion.velocity_at if self.kind == "velocity" else self.motion.acceleration_at
        return at(link, self.world(point), self.i)

    def slide(self, slider: str, guide: str) -> Sliding:
        """The kinematics' sliding of ``slider`` along ``guide`` (the first such pair, as
        the plans take it)."""
        return next(s for s in self.motion.sliding.values() if s.slider == slider and s.guide == guide)

    def image(self, point: str, link: str) -> tuple[float, float]:
        key = self.image_key(point, link)
        if key in self.points:
            return self.points[key]
        return self.put(key, self.label(point, link).lower(), self.quantity(point, link) / self.mu)

    def vector(self, quantity: str, tail, head, value: float, kind: str, optional: bool = False) -> bool:
        """Draw a vector (not when shorter than MIN_DRAWN_MM: returns whether it is drawn);
        ``optional``: a relative vector left out if an absolute vector draws the same segment
        (:meth:`finish`)."""
        if np.hypot(head[0] - tail[0], head[1] - tail[1]) <= MIN_DRAWN_MM:
            return False
        self.vectors.append(PlanVector(quantity, tuple(tail), tuple(head), float(value), kind))
        if optional:
            self.optional.add(quantity)
        return True

    def finish(self) -> None:
        """Each segment drawn once: an optional relative vector that an absolute vector draws
        (y at the pole) is left out, and so is a relative vector into the pole (its point
        momentarily at rest) that an absolute vector draws the other way."""
        absolute = [v for v in self.vectors if v.kind == "absolute"]

        def redundant(v: PlanVector) -> bool:
            if v.kind != "relative":
                return False
            if v.quantity in self.optional and _at_pole(v.tail):
                return any(_same(w.head, v.head) for w in absolute)
            return _at_pole(v.head) and any(_same(w.head, v.tail) for w in absolute)

        self.vectors = [v for v in self.vectors if not redundant(v)]

    def line(self, through, direction: np.ndarray, reach, quantity: str, group: str) -> None:
        """A construction line through ``through`` with ``direction``, covering points ``reach``."""
        u = direction / la.norm(direction)
        t = [float(la.dot(np.subtract(r, through), u)) for r in reach] + [0.0]
        a = np.add(through, (min(t) - EXTENSION_MM) * u)
        b = np.add(through, (max(t) + EXTENSION_MM) * u)
        self.lines.append(ConstructionLine(tuple(map(float, a)), tuple(map(float, b)), quantity, group))
