"""The gear sheet as pure geometry, in millimetres of paper (y up): the train's scheme in the
textbook's side view (shafts along x, radii along y), beside it the linear-velocity picture on
the same radius axis, and below that the angular-velocity picture (Smirnov's method).

- **Side view**, to μl: each wheel a segment of its pitch diameter across its axis, in the
  plane (x) of its meshes; shafts along x at their axes' heights; each carrier an arm from the
  central axis to its planets' axle. The planets and their carrier are drawn mirrored below the
  central axis too, as the textbook draws a planetary train.
- **Linear-velocity picture**, to μV: a point at height y of link L moves (perpendicular to the
  drawing) at v = ω_L·(y − y_L) + v_L, where y_L is L's axis and v_L = ω_H·y_L the velocity of
  that axis (0 on the frame). Each link's velocities are a straight line through its point of
  zero velocity; at each pitch point the two wheels share one vector (drawn from the radius
  axis, + to the right).
- **Angular-velocity picture**: from a pole at distance h below a horizontal line, a ray
  parallel to each link's line cuts the line at h·tan ψ_L = h·ω_L·μl/μV from the foot of the
  pole, so ω_L = segment·μω with μω = μV/(μl·h).

Without modules the wheels are drawn with a nominal module of 1 mm (``nominal``). A passive
planet written out (a copy of another on its carrier) is drawn in the end view only, at its
place among the equally spaced planets, and named in a note; its speed is in the table.

Reads a solved train (plans.gears); nothing here draws.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ..gears import GearAnalysis
from .scales import standard_scale

__all__ = ["GearSheet", "WheelMark", "ShaftMark", "CarrierMark", "LinkLine", "PitchVector", "OmegaSegment", "SpeedRow", "EndView",
           "gear_sheet", "PLANE_MM", "H_CHOICES_MM"]

#: Distance between the planes of meshes along the shafts in the side view, mm.
PLANE_MM = 22.0
#: Gap between the side view and the linear-velocity picture's radius axis, mm.
GAP_MM = 40.0
#: Pole distances tried for the angular-velocity picture, largest first, mm.
H_CHOICES_MM = (60.0, 50.0, 40.0, 30.0, 25.0, 20.0, 15.0, 10.0)
#: Longest ω segment allowed, mm (the picture's half width).
OMEGA_MAX_MM = 80.0
#: The end view's largest diameter, mm: drawn at the side view's scale, or at 1/2, 1/2.5, 1/4 … of it.
END_MAX_MM = 100.0
END_FACTORS = (1.0, 2.0, 2.5, 4.0, 5.0, 8.0, 10.0)
#: The end view stands this far left of the side view (its bearings and carrier included), mm.
END_GAP_MM, TICK_ROOM_MM = 30.0, 14.0
#: The side view's height is kept within this, mm; the velocity picture's half width within this.
SIDE_MAX_MM, VELOCITY_MAX_MM = 200.0, 110.0


@dataclass(frozen=True)
class WheelMark:
    """A wheel in the side view: ``x`` its plane, ``y`` its axis, ``r`` its pitch radius (mm),
    ``internal`` a ring gear, ``mirror`` drawn again below the central axis (a planet)."""

    name: str
    link: str
    x: float
    y: float
    r: float
    internal: bool
    fixed: bool
    mirror: bool
    sleeve: float = 0.0         # on a hollow shaft of this radius (mm): drawn from it outwards


@dataclass(frozen=True)
class ShaftMark:
    """A link's shaft from ``x0`` to ``x1`` at height ``y`` (mm); ``frame`` when its axis is fixed
    in the frame (drawn with a bearing), ``fixed`` when the link is held still; ``sleeve`` > 0: a
    hollow shaft of that radius round the central axis's solid shaft (drawn as two lines at
    ±sleeve, its bearing on it), leaving on the side opposite the solid shaft."""

    link: str
    x0: float
    x1: float
    y: float
    frame: bool
    fixed: bool
    mirror: bool
    sleeve: float = 0.0         # a hollow shaft of this radius round the central one (mm); 0: solid


@dataclass(frozen=True)
class CarrierMark:
    """Carrier ``name``: its arm as a polyline from its shaft on the central axis to the planets'
    axle (mm), drawn mirrored below the axis too."""

    name: str
    path: tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class LinkLine:
    """Link ``link``'s velocities in the linear-velocity picture: the segment from ``start`` to
    ``end`` (mm), ω (rad/s) its angular velocity, ``zero`` the height of its point at rest (mm,
    None when ω = 0: the link translates, or is at rest)."""

    link: str
    start: tuple[float, float]
    end: tuple[float, float]
    omega: float
    zero: float | None


@dataclass(frozen=True)
class PitchVector:
    """The common velocity of wheels ``a`` and ``b`` at their pitch point: ``v`` (m/s, + to the
    right: out of the drawing for a counter-clockwise ω at positive heights), drawn from ``tail``
    on the radius axis to ``head`` (mm)."""

    a: str
    b: str
    v: float
    tail: tuple[float, float]
    head: tuple[float, float]


@dataclass(frozen=True)
class OmegaSegment:
    """ω of ``link`` (rad/s) in the angular-velocity picture: from the foot of the pole ``tail``
    along the line to ``head`` (mm); its ray runs from the pole to ``head``."""

    link: str
    omega: float
    tail: tuple[float, float]
    head: tuple[float, float]


@dataclass(frozen=True)
class EndView:
    """The planetary part seen along the axis, to ``mu`` (m/mm: the side view's μl, or twice it
    when the view would be wider than END_MAX_MM):
    ``circles`` (wheel name, centre mm, pitch radius mm, ring gear?) of the central wheels and of
    every planet (``planets`` equally spaced copies), and each carrier's ``arms`` (mm)."""

    mu: float
    centre: tuple[float, float]
    circles: tuple[tuple[str, tuple[float, float], float, bool], ...]
    arms: tuple[tuple[tuple[float, float], tuple[float, float]], ...]


@dataclass(frozen=True)
class SpeedRow:
    """One row of the sheet's speed table: a wheel (``teeth``) or a carrier (None)."""

    name: str
    teeth: int | None
    rpm: float
    omega: float


@dataclass(frozen=True)
class GearSheet:
    """Everything the gear sheet draws (mm, y up) and its scales: μl (m/mm), μV ((m/s)/mm),
    h (mm) and μω = μV/(μl·h) ((rad/s)/mm)."""

    mu_l: float
    mu_v: float
    h: float
    wheels: tuple[WheelMark, ...]
    shafts: tuple[ShaftMark, ...]
    carriers: tuple[CarrierMark, ...]
    axis_x: float                       # the linear picture's radius axis (v = 0)
    lines: tuple[LinkLine, ...]
    pitch: tuple[PitchVector, ...]
    pole: tuple[float, float]
    omega: tuple[OmegaSegment, ...]
    nominal: bool                       # drawn with a nominal module (no module given)
    table: tuple[SpeedRow, ...] = ()
    end: EndView | None = None          # the planets seen along the axis (trains with carriers)
    notes: tuple[str, ...] = ()         # the passive planets written out, one line each

    @property
    def mu_omega(self) -> float:
        return self.mu_v / (self.mu_l * self.h)


def _planes(analysis: GearAnalysis) -> dict[str, int]:
    """The plane (index along the shafts) of each wheel: meshes that share a wheel share a plane."""
    train = analysis.speeds.train
    plane: dict[str, int] = {}
    groups: list[set[str]] = []
    for a, b in train.meshes:
        hit = [g for g in groups if a in g or b in g]
        merged = {a, b}.union(*hit)
        groups = [g for g in groups if g not in hit] + [merged]
    order = [w.name for w in train.wheels]
    groups.sort(key=lambda g: min(order.index(n) for n in g))
    for k, g in enumerate(groups):
        for n in g:
            plane[n] = k
    for w in train.wheels:
        plane.setdefault(w.name, len(groups) + len([n for n in plane if plane[n] >= len(groups)]))
    return plane


def _heights(analysis: GearAnalysis, radius: dict[str, float]) -> dict[str, float]:
    """The height of each link's axis, m: the central axis 0, planets at their carrier's arm,
    fixed-axis wheels placed by their frame meshes (the next wheel above, a ring around)."""
    s = analysis.speeds.structure
    height: dict[str, float] = {}
    for link in s.links:
        if link.carrier or any(m.reference is not None and link.name in (m.link_a, m.link_b)
                               for m in s.meshes if link.axis_on is None):
            height[link.name] = 0.0
    if not height:
        height[s.links[0].name] = 0.0
    for _ in range(len(s.meshes) + 1):
        for m in s.meshes:
            if m.reference is not None:
                continue
            ra, rb = radius[m.a], radius[m.b]
            if m.link_a in height and m.link_b not in height:
                ya = height[m.link_a]
                height[m.link_b] = ya + ra + rb if m.external else ya + ra - rb
            elif m.link_b in height and m.link_a not in height:
                yb = height[m.link_b]
                height[m.link_a] = yb + rb + ra if m.external else yb + rb - ra
    arm = _arms(analysis, radius)
    for link in s.links:
        if link.axis_on is not None:
            height[link.name] = arm[link.axis_on]
        height.setdefault(link.name, 0.0)
    return height


def _arms(analysis: GearAnalysis, radius: dict[str, float]) -> dict[str, float]:
    """Each carrier's arm, m (from the geometry, or from the nominal radii)."""
    g = analysis.geometry
    s = analysis.speeds.structure
    train = s.train
    out = {}
    for c in train.carriers:
        if g is not None and c in g.arm:
            out[c] = g.arm[c] / 1000.0
            continue
        arms = []
        for m in s.meshes:
            for p, q in ((m.a, m.b), (m.b, m.a)):
                if train.wheel(p).on == c and s.link_of(q).axis_on is None:
                    arms.append(radius[q] - radius[p] if train.wheel(q).internal else radius[q] + radius[p])
        out[c] = max(arms) if arms else max(radius[n] for link in s.planets_of(c) for n in link.members) * 2
    return out


def gear_sheet(analysis: GearAnalysis, *, side_max: float = SIDE_MAX_MM) -> GearSheet:
    """The gear sheet of a solved train (see the module); ``side_max``: the side view's largest
    height, mm (smaller where the sheet would not fit A3 otherwise)."""
    speeds = analysis.speeds
    s, train = speeds.structure, speeds.train
    nominal = analysis.geometry is None
    radius = {w.name: (1.0 if nominal else w.module) * w.teeth / 2000.0 for w in train.wheels}   # m
    height = _heights(analysis, radius)
    plane = _planes(analysis)
    omega = {link.name: speeds.omega(link.name) for link in s.links}
    link_of = {m: s.link_of(m) for m in train.names}
    copies = {p.name for p in s.passive}                 # drawn in the end view only
    drawn = [link for link in s.links if link.name not in copies]
    carrier_of_link = {link.name: link.axis_on for link in s.links}

    def v_at(link: str, y: float) -> float:
        c = carrier_of_link[link]
        v_axis = 0.0 if c is None else omega[link_of[c].name] * height[link]
        return omega[link] * (y - height[link]) + v_axis

    top = max(abs(height[link_of[w.name].name]) + radius[w.name] for w in train.wheels)
    mirrored = bool(train.carriers)
    extent = 2.0 * top if mirrored else top + max(0.0, -min(height[link_of[w.name].name] - radius[w.name]
                                                         for w in train.wheels))
    mu_l = standard_scale(extent, window=(0.55 * side_max, side_max), limit=side_max, extent=extent)
    mm = 1.0 / mu_l                                      # paper mm per metre
    spans = _spans(analysis, radius, height)
    v_max = max(abs(v_at(link, y)) for link, (y0, y1) in spans.items() for y in (y0, y1))
    mu_v = standard_scale(v_max, window=(0.5 * VELOCITY_MAX_MM, VELOCITY_MAX_MM), limit=VELOCITY_MAX_MM,
                          extent=v_max) if v_max > 0 else 1.0
    x_of = {n: PLANE_MM * k for n, k in plane.items()}
    wheels = tuple(WheelMark(name=w.name, link=link_of[w.name].name, x=x_of[w.name],
                             y=height[link_of[w.name].name] * mm, r=radius[w.name] * mm, internal=w.internal,
                             fixed=link_of[w.name].fixed, mirror=w.on is not None) for w in train.wheels
                   if link_of[w.name].name not in copies)
    x_max = max(x_of.values())
    shafts, carriers = [], []
    bare: dict[str, tuple[float, float]] = {}           # each shaft's span over its own wheels and arm
    for link in drawn:
        xs = [x_of[n] for n in link.members if n in x_of]
        if link.carrier:
            planets = [x_of[n] for p in s.planets_of(next(m for m in link.members if m in train.carriers))
                       for n in p.members]
            xs += [min(planets) - PLANE_MM / 2, max(planets) + PLANE_MM / 2]
        if not xs:
            continue
        lo, hi = min(xs), max(xs)
        bare[link.name] = (lo, hi)
        on_frame = link.axis_on is None
        if on_frame:                                   # room for the bearing outside the wheels
            lo, hi = (lo - PLANE_MM * 0.6, hi) if lo <= 0.5 * x_max else (lo, hi + PLANE_MM * 0.6)
        shafts.append(ShaftMark(link=link.name, x0=lo, x1=hi, y=height[link.name] * mm, frame=on_frame,
                                fixed=link.fixed, mirror=not on_frame))
    shafts = _coaxial(shafts, bare, [w for w in train.wheels if w.internal], link_of, train)
    sleeve = {sh.link: sh.sleeve for sh in shafts}
    wheels = tuple(replace(w, sleeve=sleeve.get(w.link, 0.0)) if w.y == 0.0 and not w.internal else w for w in wheels)
    for c in train.carriers:
        planets = [x_of[n] for p in s.planets_of(c) for n in p.members]
        arm = _arms(analysis, radius)[c] * mm
        x_arm = min(planets) - PLANE_MM / 2
        hub = sleeve.get(link_of[c].name, 0.0)           # the carrier's arm starts on its own (hollow) shaft
        carriers.append(CarrierMark(name=c, path=((x_arm, hub), (x_arm, arm), (max(planets) + PLANE_MM / 2, arm))))
    axis_x = x_max + PLANE_MM + GAP_MM + VELOCITY_MAX_MM * 0.5
    lines = []
    for link in drawn:
        y0, y1 = spans[link.name]
        w = omega[link.name]
        zero = None if w == 0 else (height[link.name] - (v_at(link.name, height[link.name]) / w)) * mm
        lines.append(LinkLine(link=link.name, start=(axis_x + v_at(link.name, y0) / mu_v, y0 * mm),
                              end=(axis_x + v_at(link.name, y1) / mu_v, y1 * mm), omega=w, zero=zero))
    pitch = []
    for m in s.meshes:
        if m.link_a in copies or m.link_b in copies:
            continue
        y = _pitch_height(m, radius, height, train)
        v = v_at(m.link_a, y)
        pitch.append(PitchVector(a=m.a, b=m.b, v=v, tail=(axis_x, y * mm), head=(axis_x + v / mu_v, y * mm)))
    w_max = max(abs(w) for w in omega.values())
    h = next((h for h in H_CHOICES_MM if h * w_max * mu_l / mu_v <= OMEGA_MAX_MM), H_CHOICES_MM[-1])
    line_y = -0.25 * extent * mm if mirrored else min(0.0, min(ln.start[1] for ln in lines)) - 15.0
    pole = (axis_x, line_y - h)
    segments = tuple(OmegaSegment(link=link.name, omega=omega[link.name], tail=(axis_x, line_y),
                                  head=(axis_x + h * omega[link.name] * mu_l / mu_v, line_y))
                     for link in drawn if not link.fixed)
    return GearSheet(mu_l=mu_l, mu_v=mu_v, h=h, wheels=wheels, shafts=tuple(shafts), carriers=tuple(carriers),
                     axis_x=axis_x, lines=tuple(lines), pitch=tuple(pitch), pole=pole, omega=segments,
                     nominal=nominal, end=_end_view(analysis, radius, height, mu_l, wheels),
                     table=tuple(SpeedRow(n, train.wheel(n).teeth if n not in train.carriers else None,
                                                           float(speeds.rpm[n]), speeds.omega(n)) for n in train.names),
                     notes=_passive_notes(analysis))


#: Radius step of the hollow shafts round the central solid shaft, mm (the k-th: k × this).
SLEEVE_MM = 2.0


def _coaxial(shafts: list[ShaftMark], bare: dict[str, tuple[float, float]], rings, link_of, train
             ) -> list[ShaftMark]:
    """The moving links on the central axis (not a ring's: it has its own disc and hub): the
    input's (else the first's) shaft stays solid; every other gets a hollow shaft round it, k ×
    SLEEVE_MM, from its own wheels or arm (``bare``: their span) out past the others on the side
    the solid one does not leave by, with its bearing there."""
    ring_links = {link_of[w.name].name for w in rings}
    central = [sh for sh in shafts if sh.frame and sh.y == 0.0 and not sh.fixed and sh.link not in ring_links]
    if len(central) < 2:
        return shafts
    inputs = {link_of[n].name for n, _ in train.inputs if n in link_of} | {n for n, _ in train.inputs}
    solid = next((sh for sh in central if sh.link in inputs), central[0])
    xs = [v for sh in central for v in bare[sh.link]]
    left = solid.x0 < bare[solid.link][0] - 1e-9      # the solid shaft leaves to the left: the others to the right
    out, k = [], 0
    for sh in shafts:
        if sh not in central or sh is solid:
            out.append(sh)
            continue
        k += 1
        lo, hi = bare[sh.link]
        out.append(replace(sh, x0=lo, x1=max(xs) + PLANE_MM * 0.6 * k, sleeve=SLEEVE_MM * k) if left else
                   replace(sh, x0=min(xs) - PLANE_MM * 0.6 * k, x1=hi, sleeve=SLEEVE_MM * k))
    return out


def _passive_notes(analysis: GearAnalysis) -> tuple[str, ...]:
    """One line naming the passive planets written out and W counted with them, or none."""
    s = analysis.speeds.structure
    if not s.passive:
        return ()
    named = ", ".join(f"{p.name} repeats {p.copy_of} on {p.carrier}" for p in s.passive)
    return (f"passive planets: {named} (shown in the end view); counted with them, {s.formula_with_passive}",)


def _end_view(analysis: GearAnalysis, radius: dict[str, float], height: dict[str, float], mu_l: float,
              wheels: tuple[WheelMark, ...]) -> EndView | None:
    """The end view left of the side view (see :class:`EndView`), or None without carriers. Each
    planet link (a passive copy too) stands at its distance and angle from the geometry (or at its
    carrier's arm, a copy 2π·i/sets on from the planet it repeats), turned by 2π·j/planets."""
    s = analysis.speeds.structure
    train = s.train
    if not train.carriers:
        return None
    g = analysis.geometry
    planet_wheels = {w.name for w in train.wheels if w.on is not None}
    central = [w for w in train.wheels if w.on is None and any(
        (a == w.name and b in planet_wheels) or (b == w.name and a in planet_wheels) for a, b in train.meshes)]
    place: dict[str, tuple[float, float]] = {}          # planet link → (distance m, angle rad from the top)
    for c in train.carriers:
        planets = s.planets_of(c)
        sets = train.planets * (1 + max((len(s.copies(p.name)) for p in planets), default=0))
        for p in planets:
            d = g.planet_arm[p.name] / 1000.0 if g is not None and p.name in g.planet_arm else height[p.name]
            t = g.planet_angle.get(p.name, 0.0) if g is not None else 0.0
            place[p.name] = (d, t)
            for i, copy in enumerate(s.copies(p.name), start=1):
                place[copy] = (d, t + 2.0 * math.pi * i / sets)
    reach_m = max([radius[w.name] for w in central] + [place[s.link_of(w.name).name][0] + radius[w.name]
                                                        for w in train.wheels if s.link_of(w.name).name in place])
    factor = next((f for f in END_FACTORS if reach_m / (f * mu_l) <= END_MAX_MM / 2), END_FACTORS[-1])
    mu = factor * mu_l                  # the side view's scale, or a simple fraction of it
    mm = 1.0 / mu
    reach = reach_m * mm
    left = min(x for x in [w.x - TICK_ROOM_MM for w in wheels])
    cx, cy = left - END_GAP_MM - reach, 0.0

    circles, arms = [], []
    for w in central:
        circles.append((w.name, (cx, cy), radius[w.name] * mm, w.internal))
    k = train.planets
    for c in train.carriers:
        for j in range(k):
            for link in s.planets_of(c, passive=True):
                d, t0 = place[link.name]
                t = math.pi / 2 + t0 + 2.0 * math.pi * j / k
                p = (cx + d * mm * math.cos(t), cy + d * mm * math.sin(t))
                arms.append(((cx, cy), p))
                for n in link.members:
                    circles.append((n, p, radius[n] * mm, train.wheel(n).internal))
    return EndView(mu=mu, centre=(cx, cy), circles=tuple(circles), arms=tuple(arms))


def _spans(analysis: GearAnalysis, radius: dict[str, float], height: dict[str, float]) -> dict[str, tuple[float, float]]:
    """The heights (m) over which each link's velocity line is drawn: a central link from its axis
    to its largest wheel's pitch radius, a carrier to its arm, any other link across its wheels."""
    s = analysis.speeds.structure
    train = s.train
    arms = _arms(analysis, radius)
    out = {}
    for link in s.links:
        wheels = [n for n in link.members if n not in train.carriers]
        r = max((radius[n] for n in wheels), default=0.0)
        y = height[link.name]
        if link.carrier:
            c = next(m for m in link.members if m in train.carriers)
            out[link.name] = (0.0, max(arms[c], r))
        elif link.axis_on is None and y == 0.0 and train.carriers:
            out[link.name] = (0.0, r)
        else:
            out[link.name] = (y - r, y + r)
    return out


def _pitch_height(m, radius: dict[str, float], height: dict[str, float], train) -> float:
    """The height of mesh ``m``'s pitch point, m: between the axes (external), or on the ring's
    circle on the side of the inner wheel (internal)."""
    ya, yb = height[m.link_a], height[m.link_b]
    if m.external:
        return ya + radius[m.a] * (1.0 if yb >= ya else -1.0)
    ring, ry, other_y = (m.a, ya, yb) if train.wheel(m.a).internal else (m.b, yb, ya)
    return ry + radius[ring] * (1.0 if other_y >= ry else -1.0)
