"""The value types of a scene and the bounds it is read against.

Holds :class:`Scene` and its parts (sliders, the drive and its :class:`DriveKind`, the cycle,
masses, applied forces and moments, the balancing element), the frame's name :data:`FRAME`,
what may be drawn, the continuation walk's steps (STEP_DEG, LINEAR_STEPS_PER_SIZE) and every
MAX_*/MIN_* bound of a scene (SI units, angles in degrees). Nothing is read or checked here.
Imports only the standard library: no other module of plans.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Mapping

from .dynamics import Dynamics
from .gear_pair import GearPairSpec
from .gears import GearTrain, Synthesis
from .counterweights import CounterweightSpec
from .rotor import RotorSpec
from .turning import FlywheelSpec, OperationSpec, Torque, TurningSpec

#: The frame's name in [links] (a link name, a string).
FRAME = "0"
#: The sheets a scene may draw (``[plans] draw``), in the order they are drawn.
DRAWABLE = ("scheme", "velocity", "acceleration", "centres", "positions", "diagrams", "velocities", "forces", "lever",
            "gears", "dynamics", "startup", "meshing", "cutting", "assemblies", "balancing", "shaking")
#: What needs the force analysis (kinetostatics): the force plans and Zhukovsky's lever.
FORCE_SHEETS = ("forces", "lever")
#: Sheets of the whole cycle: they need ``[drive] positions = N``.
CYCLE_SHEETS = ("positions", "diagrams", "velocities", "dynamics", "startup", "shaking")
#: Fewest and most positions of a cycle (``[drive] positions``): three chords at least for the
#: graphical differentiation; one a degree at most (as MAX_POSITIONS).
MIN_CYCLE_POSITIONS = 3
#: Most positions whose velocity plans share one sheet (``draw = ["velocities"]``): 24 plans
#: on an A3 sheet are about 60 mm each, still readable.
MAX_VELOCITY_PLANS = 24
#: How the cycle's first position is chosen (``[drive] start``).
CYCLE_STARTS = ("angle", "extreme")
#: What a scene draws when [plans] says nothing.
DEFAULT_DRAW = ("scheme", "velocity", "acceleration")

# --- bounds of what a scene may ask for ------------------------------------------------------
#: Largest scene or variants file, bytes (4 MB): the examples are 1–4 kB and a variants file of
#: MAX_VARIANTS variants about 100 kB; a larger file (or /dev/zero) is refused before it is read.
MAX_FILE_BYTES = 4_000_000
#: Shortest dimension of a link, as a fraction of the mechanism's longest (the largest distance
#: between two points of one link, [lengths] included): every [lengths] value, every distance of
#: two points of one link in the sketch and the two points of a guide through = [P, Q] must be at
#: least this far apart. Measured: a crank of 2.5e-8 of the loaded press's longest link (1e-8 m)
#: draws a lever that fails plans check, one of 5e-9 of the crank-slider's (2e-9 m) a lever that
#: disagrees with the group-by-group analysis by 1e-8; 1e-300 divides by zero. 1e-6 keeps a
#: margin of 40 and is 0.24 µm on a 240 mm drawing: nothing a drawing can show. The longest link,
#: not the sketch's extent, is the reference, since a block's point where nearly parallel guides
#: meet lies far out (see MAX_COORD_M).
MIN_LENGTH_RATIO = 1e-6
#: Largest |coordinate| of a sketch point and largest length, m. Real linkages measure metres to
#: tens of metres, but a construction point where two nearly parallel guides meet lies about
#: size/angle away: 1e-13° from parallel that is ~1e16 m for a 1 m mechanism (the property tests
#: sketch such points). 1e20 m allows them and keeps ω·r ≤ 1e26 m/s, ω²·r ≤ 1e32 m/s² and their
#: squares (≤ 1e64, vector lengths are square roots of sums of squares) far from overflow (1e308);
#: a mechanism scaled by 1e300, or a coordinate of 1e308, is refused.
MAX_COORD_M = 1e20
#: Smallest size of the sketch (its bounding-box diagonal), m: finer than any micro-mechanism,
#: and the scale of the scheme is chosen for extents of at least 1e-6 m (extent_of).
MIN_SIZE_M = 1e-6
#: Largest |drive angle| and |guide angle|, degrees (about 2800 turns). Doubles near 1e6 are
#: 1.2e-10° apart, so reducing the angle by whole turns stays exact far beyond drawing precision;
#: near 1e20 neighbouring doubles are 16000° apart and the angle drawn would not be the one asked.
MAX_ANGLE_DEG = 1e6
#: Most continuation steps the solver may walk: it walks from the sketch to every requested value
#: in 1° steps (a linear drive: size/200, see kinematics/walk.py ``walk_to``), keeping every step's
#: pose. A class III group costs ~4 ms a step, so 7200 steps (20 turns: every position a crank
#: can take, many times over) take about 30 s; a class II mechanism, well under a second.
MAX_WALK_STEPS = 7200
#: The continuation walk's steps (kinematics/walk.py ``walk_to``), here so that the bound above
#: and the solver read the same numbers: a crank steps STEP_DEG, a slider size/LINEAR_STEPS_PER_SIZE.
STEP_DEG = 1.0
LINEAR_STEPS_PER_SIZE = 200.0
#: Most drive positions in one scene: one a degree over a turn; each writes up to five sheets.
MAX_POSITIONS = 360
#: Largest |ω| of a crank, rad/s (ultracentrifuges turn at ~1e4 rad/s); with lengths up to
#: MAX_COORD_M every velocity and acceleration, and its square, is an ordinary double.
MAX_OMEGA = 1e6
#: Largest |ε| of a crank, rad/s² (ω² at MAX_OMEGA).
MAX_EPSILON = 1e12
#: Largest |velocity| of a linear drive, m/s (as ω·r at MAX_OMEGA and r = 1 m).
MAX_SPEED = 1e6
#: Largest |acceleration| of a linear drive, m/s² (as ω²·r at MAX_OMEGA and r = 1 m).
MAX_ACCELERATION = 1e12
#: Smallest nonzero |ω| or |velocity| of the drive (rad/s, m/s): one turn in 200 years. Smaller
#: speeds give velocities whose squares underflow (|v|² < 1e-308 when |v| < 1e-154), so the
#: plans' vector lengths would read 0; 0 itself is allowed (the mechanism at rest). The same bound
#: holds for ε (or the drive's acceleration) of a drive at rest, then the only source of motion.
MIN_RATE = 1e-9
#: Longest title, characters: it is one line of every sheet's title block, shrunk to fit down to
#: 2 mm text and cut short with "…" beyond that (about 130 characters); the whole title stays
#: in the SVG's <title> and in the JSON report.
MAX_TITLE_CHARS = 200
#: Largest |force| (N), |moment| (N·m), mass (kg), moment of inertia (kg·m²) and |g| (m/s²) a
#: scene may give: far beyond any machine, and with coordinates up to MAX_COORD_M and
#: accelerations up to ω²·r their products (m·a·r ≤ 1e20·1e32·1e20) stay ordinary doubles.
MAX_LOAD = 1e20


@dataclass(frozen=True)
class Slider:
    """A prismatic pair: link ``link`` slides along a line fixed in link ``on``.

    ``through`` holds one point name (then ``angle`` is the line's direction in degrees)
    or two point names (the line through both sketch points, directed first → second).
    """

    link: str
    on: str
    through: tuple[str, ...]
    angle: float | None
    index: int

    @property
    def key(self) -> str:
        return f"sliders[{self.index}]"


class DriveKind(StrEnum):
    """How the drive moves: a crank turning about a frame pivot, a slider on a frame guide,
    a link not pivoted on the frame whose absolute angle is given (a coupler), or a linear
    motor between two moving links (a hydraulic cylinder: the rod slides in the cylinder)."""

    ROTARY = "rotary"
    LINEAR = "linear"
    COUPLER = "coupler"
    CYLINDER = "cylinder"

    @property
    def angular(self) -> bool:
        """True when the drive's values are angles (degrees; ω, ε), False for strokes (m; v, a)."""
        return self in (DriveKind.ROTARY, DriveKind.COUPLER)

    @property
    def unit(self) -> str:
        return "deg" if self.angular else "m"


@dataclass(frozen=True)
class Drive:
    """The driving link and its law of motion.

    ``kind`` is :attr:`DriveKind.ROTARY` or :attr:`DriveKind.COUPLER` (``values`` are angles in
    degrees, ``speed`` ω in rad/s, ``rate`` ε in rad/s², CCW positive; a coupler's angle is its
    absolute angle, of the line from its first point to its second) or :attr:`DriveKind.LINEAR` /
    :attr:`DriveKind.CYLINDER` (``values`` are displacements in metres of the link along its
    guide from the sketch position, ``speed`` in m/s, ``rate`` in m/s²; the guide is on the frame,
    or on link ``along`` for a cylinder, and the motion is relative to it).
    """

    link: str
    kind: DriveKind
    values: tuple[float, ...]
    speed: float
    rate: float
    along: str = FRAME

    @property
    def unit(self) -> str:
        return self.kind.unit


@dataclass(frozen=True)
class Cycle:
    """One revolution of a crank in ``positions`` equal steps (``[drive] positions = N``).

    ``start`` is ``"angle"`` (the first position is the drive's ``angle``) or ``"extreme"``
    (the first position is the one where the output link's displacement, or angle, is
    smallest: found by the kinematics). ``output`` names the output link (``[plans] output``,
    by default the last moving link); ``trace`` the points whose trajectories are drawn; ``at``
    the position numbers (0 … N−1) drawn on sheets of their own (scheme, plans, centres) — all of
    them when ``[plans] at`` is not given."""

    positions: int
    start: str = "angle"
    output: str = ""
    trace: tuple[str, ...] = ()
    at: tuple[int, ...] = ()


@dataclass(frozen=True)
class Mass:
    """The inertia of a moving link (``[masses.NAME]``): ``mass`` (kg), ``inertia`` (kg·m²,
    about the centre of mass, perpendicular to the plane) and ``centre``, the name of the
    link's point at its centre of mass."""

    link: str
    mass: float
    inertia: float
    centre: str


@dataclass(frozen=True)
class AppliedForce:
    """An external force (``[[forces]]``) on ``link`` at its point ``at``: ``vector`` (N) in
    the fixed x, y frame. ``index`` is its place in the list.

    A constant force has ``vector`` alone. One that follows the cycle has ``law``: (x, F)
    pairs, x strictly increasing — x the output link's travel from its extreme ``origin``
    (``"min"``: where its displacement or angle is smallest, ``"max"``) in m for a slider or
    degrees for a rocker, F in N, interpolated linearly, the end values held beyond the ends —
    and then ``vector`` is the unit direction. ``stroke``: ``"working"`` (acts only while the
    output moves away from ``origin``), ``"return"`` (only while it moves back) or ``"both"``.
    ``oppose``: its sense always against the velocity of its point ``at`` (``vector`` None:
    along that velocity, against it, of ``magnitude`` N or its law's value)."""

    link: str
    at: str
    vector: tuple[float, float] | None
    index: int
    law: tuple[tuple[float, float], ...] = ()
    stroke: str = "both"
    oppose: bool = False
    origin: str = "min"
    magnitude: float | None = None      # N, of a force against its point's velocity given no direction

    @property
    def follows_output(self) -> bool:
        """Whether the force reads the output link's travel (a law or a stroke)."""
        return bool(self.law) or self.stroke != "both"

    @property
    def constant(self) -> bool:
        """Whether the force is the same vector at every position."""
        return not self.follows_output and not self.oppose


@dataclass(frozen=True)
class AppliedMoment:
    """An external couple (``[[moments]]``) on ``link``: ``value`` (N·m, CCW positive), or ``law``
    its value (N·m, CCW positive) against the crank's turned angle θ (degrees from the cycle's
    first position, over ``[dynamics] period``; ``value`` is then 0), read by [dynamics] alone."""

    link: str
    value: float
    index: int
    law: Torque | None = None


@dataclass(frozen=True)
class Balance:
    """The balancing element on the driving link (``[balance]``): ``kind`` ``"moment"`` (a
    couple on the link), ``"force"`` (a force at its point ``at`` along the line at ``angle``°
    drawn in the sketch, which turns with the link as a slider's guide angle does) or
    ``"actuator"`` (a hydraulic cylinder's force along its guide: on the rod, and opposite on
    the cylinder). ``given``: False when the scene has no [balance] (the default element)."""

    link: str
    kind: str
    at: str | None = None
    angle: float | None = None
    given: bool = True


@dataclass(frozen=True)
class Scene:
    """A validated scene. ``lengths`` maps an unordered point pair to a distance in metres."""

    title: str
    points: Mapping[str, tuple[float, float]]
    links: Mapping[str, tuple[str, ...]]
    sliders: tuple[Slider, ...]
    drive: Drive | None           # None only in a gear train alone (:attr:`train_only`)
    lengths: Mapping[frozenset[str], float] = field(default_factory=dict)
    draw: tuple[str, ...] = DEFAULT_DRAW
    scales: Mapping[str, float] = field(default_factory=dict)
    senses: bool = False          # the scheme shows the senses of ω and ε of every moving link
    description: str = ""
    file: str | None = None
    cycle: Cycle | None = None    # [drive] positions = N: the whole revolution (cycle sheets)
    masses: Mapping[str, Mass] = field(default_factory=dict)      # link → its mass, inertia, centre
    forces: tuple[AppliedForce, ...] = ()
    moments: tuple[AppliedMoment, ...] = ()
    gravity: float | None = None  # g (m/s², acting −y) when given, else no gravity
    balance: Balance | None = None  # the balancing element when forces are computed
    gears: GearTrain | None = None  # [gears]: a train alone (no points, links, drive=None) or driving the crank
    synthesis: Synthesis | None = None  # [synthesis]: a planetary train to find (then gears is None)
    dynamics: Dynamics | None = None    # [dynamics]: the machine's motion under its loads (needs the cycle)
    assembly: Mapping[str, int] = field(default_factory=dict)   # [plans] assembly: group → its number to draw
    gear_pair: GearPairSpec | None = None   # [gear_pair]: one involute pair in mesh (a scene of gears alone)
    rotor: RotorSpec | None = None     # [rotor]: rotating masses to balance (a scene of a rotor alone)
    turning: TurningSpec | None = None      # [turning]: a crank torque over a cycle (a flywheel problem alone)
    flywheel: FlywheelSpec | None = None    # [flywheel]: the flywheel of [turning] or [operation]
    operation: OperationSpec | None = None  # [operation]: punching, riveting (a flywheel problem alone)
    counterweights: Mapping[str, CounterweightSpec] = field(default_factory=dict)  # link → its counterweight

    @property
    def train_only(self) -> bool:
        """Whether the scene is a gear train with no linkage."""
        return self.drive is None and self.rotor is None and not self.flywheel_only

    @property
    def flywheel_only(self) -> bool:
        """Whether the scene is a flywheel problem with no linkage ([turning] and/or [operation])."""
        return self.drive is None and (self.turning is not None or self.operation is not None)

    @property
    def wants_forces(self) -> bool:
        """Whether the force analysis runs: the force plans or the lever are drawn, or a
        [balance] is given."""
        return bool(set(FORCE_SHEETS) & set(self.draw)) or (self.balance is not None and self.balance.given)

    @property
    def wants_inertia(self) -> bool:
        """Whether the force analysis needs accelerations (a link has a mass or an inertia)."""
        return self.wants_forces and any(m.mass > 0.0 or m.inertia > 0.0 for m in self.masses.values())

    def links_of(self, point: str) -> tuple[str, ...]:
        """Names of the links that carry ``point``, in scene order."""
        return tuple(name for name, pts in self.links.items() if point in pts)
