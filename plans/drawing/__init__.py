"""Drawing: constructions (paper mm geometry) → SVG text on standard sheets. Never solves kinematics."""

from .style import Style
from .svg import Heading, draw_centres, draw_plan, draw_scheme

__all__ = ["Style", "Heading", "draw_centres", "draw_plan", "draw_scheme"]
