"""Exact kinematics: positions, velocities and accelerations, vectorised over drive positions."""

from .state import LinkState
from .motion import Motion
from .solve import analyse
from .tolerances import SINGULAR_SIN, WARN_SIN
from .sliders import Sliding, link_angles, sliding

__all__ = ["LinkState", "Motion", "analyse", "SINGULAR_SIN", "WARN_SIN", "Sliding", "link_angles", "sliding"]
