"""Drawing: constructions (paper mm geometry) → SVG text. Never solves kinematics."""

from .style import Style
from .svg import draw_centres, draw_plan, draw_scheme

__all__ = ["Style", "draw_centres", "draw_plan", "draw_scheme"]
