"""Scene files: the TOML description of a mechanism, read and validated.

A scene gives a reference sketch (points in metres, x right, y up), the links as lists of
point names (``"0"`` is the frame), prismatic pairs (``[[sliders]]``), the drive, optional
exact lengths, scales and what to draw. Reading a scene checks every key and value and
raises :class:`~plans.errors.SceneError` naming the key and the fix; nothing is solved here.

One reader per section: :mod:`.sketch` (points, links, sliders, lengths, the shortest
dimension), :mod:`.drive`, :mod:`.options` ([plans] and the cycle), :mod:`.scales`, :mod:`.loads`
(masses, forces, moments, gravity, balance), :mod:`.gears` (a gear train, a planetary
synthesis), put together by :mod:`.document` (a mapping) and
:mod:`.file` (a TOML file; its bounded reader reads every file a user gives); :mod:`.checks`
holds the checks they share and :mod:`.values` the value types and bounds. The package imports
only plans.errors (and the standard library).
"""

from .values import (CYCLE_SHEETS, CYCLE_STARTS, DEFAULT_DRAW, DRAWABLE, FORCE_SHEETS, FRAME, LINEAR_STEPS_PER_SIZE,
                     MAX_ACCELERATION, MAX_ANGLE_DEG, MAX_COORD_M, MAX_EPSILON, MAX_FILE_BYTES, MAX_LOAD,
                     MAX_OMEGA, MAX_POSITIONS, MAX_SPEED, MAX_TITLE_CHARS, MAX_VELOCITY_PLANS, MAX_WALK_STEPS,
                     MIN_CYCLE_POSITIONS, MIN_LENGTH_RATIO, MIN_RATE, MIN_SIZE_M, STEP_DEG, AppliedForce,
                     AppliedMoment, Balance, Cycle, Drive, DriveKind, Mass, Scene, Slider)
from .checks import as_float
from .gears import GearTrain, Synthesis, Wheel
from .dynamics import Dynamics
from .document import parse_scene
from .file import parse_toml, read_bytes, read_scene, read_text

__all__ = ["Scene", "Dynamics", "GearTrain", "Wheel", "Synthesis", "Slider", "Drive", "DriveKind", "Cycle", "Mass", "AppliedForce", "AppliedMoment", "Balance",
           "read_scene", "parse_scene", "read_bytes", "read_text", "parse_toml", "as_float", "FRAME", "DRAWABLE",
           "DEFAULT_DRAW", "FORCE_SHEETS", "CYCLE_SHEETS",
           "CYCLE_STARTS", "MIN_CYCLE_POSITIONS", "MAX_VELOCITY_PLANS", "STEP_DEG", "LINEAR_STEPS_PER_SIZE",
           "MAX_COORD_M", "MIN_SIZE_M", "MAX_ANGLE_DEG", "MAX_WALK_STEPS", "MAX_POSITIONS", "MAX_OMEGA",
           "MAX_EPSILON", "MAX_SPEED", "MAX_ACCELERATION", "MIN_RATE", "MAX_TITLE_CHARS", "MAX_LOAD",
           "MAX_FILE_BYTES", "MIN_LENGTH_RATIO"]
