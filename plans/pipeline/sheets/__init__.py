"""The families of sheets the pipeline draws, one module each with one entry function:
:mod:`.scheme` (the kinematic scheme), :mod:`.centres` (instantaneous centres), :mod:`.koshel`
(Koshel's plan), :mod:`.plans` (velocity and acceleration plans, checked), :mod:`.forces` (force
plans and Zhukovsky's lever) and :mod:`.cycle` (positions, diagrams and velocities over one
revolution). :mod:`.page` holds what the sheets of one position share (name suffix, heading).

A family builds its constructions from a solved Motion, checks them and draws them; it returns
SVG text by file name and computes no kinematics. It imports nothing of the pipeline but
plans.pipeline.rest, :mod:`.page` and (Koshel) the plans' similarity check; this package
imports none of its modules."""
