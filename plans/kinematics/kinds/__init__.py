"""One solver per kind of group, behind one protocol (:class:`~plans.kinematics.kinds.base.GroupSolver`),
registered by the group's ``kind``.

A new kind of group is one new class (a module beside these) and one line in :data:`SOLVERS`;
its structural group carries ``kind``, the key (see :mod:`plans.structure`).
"""

from __future__ import annotations

from ...model import Mechanism
from ...structure import Structure
from .base import GroupSolver, Rates, Seed
from .complex import Complex
from .driven import Driven
from .dyad import Dyad

__all__ = ["SOLVERS", "GroupSolver", "Rates", "Seed", "solver", "chain"]

#: The solver class of each kind of group (the structural group's ``kind``).
SOLVERS: dict[str, type] = {
    "dyad": Dyad,           # class II: the five forms in closed form
    "complex": Complex,     # class III/IV: Newton's method, compiled
    "driven": Driven,       # the original mechanism of a drive inside the chain
}


def solver(mech: Mechanism, group) -> GroupSolver:
    """The solver of ``group`` (any kind) in ``mech``."""
    return SOLVERS[group.kind](mech, group)


def chain(mech: Mechanism, structure: Structure) -> list[GroupSolver]:
    """The solvers of the structure's groups in the order they are solved: the original
    mechanism of a drive inside the chain first (when there is one), then the Assur groups."""
    groups = ([structure.driven] if structure.driven is not None else []) + list(structure.groups)
    return [solver(mech, g) for g in groups]
