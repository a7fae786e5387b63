"""Handouts for a class: one base scene, many variants, an assignment and an answer key each.

A *variants file* names a base scene and lists per-variant values::

    base = "six_link_press.toml"       # relative to the variants file
    title = "TMM homework 2"           # optional (default: the base scene's title)

    [[variant]]
    lengths = { OA = 0.1, AB = 0.36 }  # any of the base's [lengths]; the rest keep the base's values
    angle = 30.0                        # the drive's value(s), a number or a list (linear drive: displacement)
    omega = 10.0                        # ω1 (linear drive: velocity)
    epsilon = 0.0                       # optional ε1 (linear drive: acceleration)

Every key of a variant is optional (a missing one keeps the base's value). Instead of a file,
:func:`random_variants` draws N variants around a base scene from ``numpy.random.default_rng(seed)``:
the lengths link by link — a bar × U(1 − 20 %, 1 + 20 %) to three significant digits, the
lengths to the points on its line in the base (a centre of mass on its rod) in their base ratio
to it, every other length of the link drawn on its own (:func:`.draws.length_plan`) — a crank's
angle over the turn in 5° steps, ω1 from the series 1, 1.5, 2, 2.5, 3, 4, 5, 6, 8 × 10ᵏ within
½…2 × the base's (none for a crank the gear train turns); a draw that does not assemble, whose
condition figure (``Motion.sines``) is below :data:`MARGIN_SIN` at any asked position in any
group, that changes a link's shape, whose task has nothing to find, or (a forces assignment)
whose working force does not act at the drawn position (it is off its stroke), is drawn again.
A variant of a file that changes a link's shape or leaves its task nothing to find is refused
in one line; so is a base whose variants would all be at rest.

:func:`write_handout` writes, into the output folder, ``variant-NN/`` (the assignment sheet and
the answer key: every sheet the scene draws, SVG and PDF, the JSON values and the variant's
own scene file), ``variants.toml`` (the variants, reproducible: ``plans handout`` on it gives the
same keys), a copy of the base scene and ``index.html``. Only the public API is used:
:func:`plans.parse_scene`, :func:`plans.render`, :meth:`plans.Sheets.save`.

Five kinds of assignment (:mod:`.asked`): a linkage's kinematics, a loaded linkage's forces,
a gear train (its variants set ``teeth`` and ``input``, drawn keeping the coaxial, assembly and
neighbourhood conditions and no undercut), a machine's dynamics (the flywheel: marked against
the chord method at the cycle's positions, :mod:`.graphical`) and a rotor's balancing (its
variants set ``masses = [{ mass = …, radius = …, angle = …, plane = … }, …]``, drawn by
:mod:`.rotor`; the key is the -balancing sheet). With :func:`moodle_xml` a handout is also a
Moodle XML question bank (:mod:`.moodle`).

The package: :mod:`.graphical` (what a graphical task's method gives, and its drawing precision),
:mod:`.asked` (what each kind asks, from a report), :mod:`.variants` (the data, reading a
variants file), :mod:`.solving` (a variant solved, the margins), :mod:`.rotor` (a rotor's random
variants), :mod:`.draws` (random variants), :mod:`.toml_text` (TOML writer),
:mod:`.rotor_sheet` (a rotor's assignment sheet), :mod:`.assignment` (the assignment sheet, its
data and task), :mod:`.index` (``index.html``), :mod:`.moodle` (the question bank) and
:mod:`.writing` (the output folder). Each imports only modules before it in this list
(:mod:`.index` only :mod:`.asked`, :mod:`.rotor` and :mod:`.variants`); nothing here imports the
command line.
"""

from __future__ import annotations

from .asked import KINDS, Asked, asked, kind_of
from .assignment import assignment_sheets, assignment_svg, variant_asked
from .draws import random_variants
from .graphical import Chords, balancing_precision, chord_answers
from .moodle import DEFAULT_TOLERANCE, cloze_field, field_tolerance, moodle_xml, parse_tolerance
from .rotor import ANGLE_STEP_DEG as ROTOR_ANGLE_STEP_DEG
from .rotor import BALANCING_RANGE, MASS_SPREAD
from .solving import group_margins, solve_variant, variant_data, variant_scene, worst_sine
from .toml_text import to_toml
from .variants import (ANGLE_STEP_DEG, LENGTH_SPREAD, MARGIN_SIN, MAX_TRIES, MAX_VARIANTS,
                       SPEED_RANGE, SPEED_SERIES, Drawn, Handout, Variant, margin_text, read_base, read_variants)
from .writing import INDEX, VARIANTS, Progress, write_handout

__all__ = ["MARGIN_SIN", "LENGTH_SPREAD", "ANGLE_STEP_DEG", "SPEED_SERIES", "MAX_VARIANTS", "MAX_TRIES",
           "Variant", "Handout", "Drawn", "read_variants", "read_base", "random_variants", "variant_scene",
           "solve_variant", "write_handout", "Progress", "to_toml", "SPEED_RANGE", "INDEX", "VARIANTS",
           "margin_text", "variant_data", "worst_sine", "group_margins", "KINDS", "Asked", "asked", "kind_of",
           "assignment_svg", "assignment_sheets", "variant_asked", "DEFAULT_TOLERANCE", "cloze_field", "moodle_xml",
           "parse_tolerance", "field_tolerance", "Chords", "chord_answers", "balancing_precision", "BALANCING_RANGE",
           "MASS_SPREAD", "ROTOR_ANGLE_STEP_DEG"]
