"""Every tolerance of the kinematic solvers, with why it has its value.

Lengths are relative to the mechanism's size (its sketch's extent, m); sines are a group's
condition figure: of the angle between a class II group's two unknown directions (Cramer's
determinant normalised), the same sine generalised for class IV groups and a drive inside the
chain (:mod:`plans.kinematics.figure`), the rods' axes' determinant for class III groups (±1
well conditioned, 0 singular).
"""

from __future__ import annotations

__all__ = ["SINGULAR_SIN", "WARN_SIN", "JUMP_RATIO", "ASSEMBLY_RTOL", "PARALLEL_DET", "NEWTON_RTOL", "MAX_ITER",
           "COARSE_RTOL", "CROSS_CHECK_RTOL", "INFINITY_RTOL", "REST_RTOL"]

#: |sin| of a group's velocity equations below which the position is reported as singular.
#: At an exact dead centre rounding leaves |sin| ~ sqrt(machine eps) ~ 1e-8, so the bound
#: sits above that; 1° from a singular position |sin| is still ~1e-2.
SINGULAR_SIN = 1e-6
#: |sin| below which the position is reported as near-singular (a warning, values are kept):
#: there rounding errors are amplified a hundredfold in velocities, 1e4 in accelerations. For
#: every kind of group it means the same closeness: the group's links are about 0.01 rad
#: (0.57°) of relative turning from a dead position's alignment — a few thousandths of a
#: degree of crank (a few hundredths of a mm of stroke) from a limit position in the examples.
WARN_SIN = 1e-2
#: A class III/IV step whose points move more than JUMP_RATIO times the previous step (and
#: more than 1 % of the mechanism's size) is a jump to another assembly branch: along one
#: branch, neighbouring 1° steps move alike (a ratio near 1, a few near a limit position).
JUMP_RATIO = 8.0
#: A class II group still assembles when its closure misses by at most this × size: a limit
#: position sketched exactly (h = 0) comes out of the arithmetic at a few ulps either side.
ASSEMBLY_RTOL = 1e-12
#: Two guides whose directions' cross product is below this are parallel (PRP, RPP): unit
#: vectors, so 1e-12 is ~1e-10 degrees, far below any drawn angle.
PARALLEL_DET = 1e-12
#: Newton stops when the largest equation residual is below NEWTON_RTOL × size (m): a
#: hundredfold the rounding of a coordinate of size 1, so it is reached, and one more step
#: then polishes to rounding level.
NEWTON_RTOL = 1e-13
#: Newton iterations allowed per step before the step is halved.
MAX_ITER = 30
#: The coarse continuation's nodes are only seeds (the batched solve polishes every position
#: to NEWTON_RTOL), so their Newton stops at this residual × size.
COARSE_RTOL = 1e-9
#: Largest relative difference allowed between the special-point and the Jacobian solutions of
#: a class III group, relative to the speed (acceleration) of the mechanism's fastest point at
#: that position (:meth:`~plans.kinematics.state.Solution.rate_scale`): both are exact to rounding, which near a singular position (|sin| ~ 1e-2,
#: the warning bound) amplifies eps to ~1e-12; 1e-9 leaves a thousandfold margin and still
#: catches any wrong term (a missing Coriolis or normal term is of order 1).
CROSS_CHECK_RTOL = 1e-9
#: |ω_i − ω_j|·size ≤ INFINITY_RTOL·|relative velocity| puts an instantaneous centre at infinity
#: (it would lie more than 1e9 mechanism sizes away).
INFINITY_RTOL = 1e-9
#: A link (or two links relative to each other) is at rest when |ω|·size and the (relative)
#: speed of its first point are at most REST_RTOL × the speed of the mechanism's fastest point at
#: that position (:meth:`~plans.kinematics.state.Solution.rate_scale`): it then has no
#: instantaneous centre. At a stationary instant found by root-finding, rounding leaves
#: |ω|·size ~ 1e-16 of that speed (~1e-12 near a singular position); a link that really moves at
#: 1e-9 of it draws vectors of 1e-7 mm, nothing a plan can show. Koshel's AT_REST is as tight.
REST_RTOL = 1e-9
