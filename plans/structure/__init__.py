"""Structural analysis: Chebyshev's W, Assur groups, their forms, the structural formula.

:mod:`.groups` holds the value types (pairs, groups, the structure), :mod:`.index` who is
joined to whom, :mod:`.search` the decomposition into Assur groups. The structure layer may
import only plans.errors, plans.scene and plans.model.
"""

from __future__ import annotations

from .groups import FORMS, ComplexGroup, DrivenGroup, Group, Joint, Pair, Rod, Structure
# the private names too, for code that reaches them through the old module (patch them in .search)
from .index import _Index
from .search import (MAX_DRIVEN_LINKS, _check_original_mechanism, _complex, _contour, _decompose, _driven_group,
                     _dyad, _dyad_fit, _first_complex, _first_dyad, _no_split, analyse_structure)

__all__ = ["Joint", "Group", "Pair", "Rod", "ComplexGroup", "DrivenGroup", "Structure", "analyse_structure", "FORMS",
           "MAX_DRIVEN_LINKS"]
