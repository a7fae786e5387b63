"""Every drawing constant in one place (paper millimetres, ISO 128 line weights)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Style:
    """Line weights, symbol sizes, text heights (mm) and the coordinate precision. The sheet's
    format, frame and title block are in :mod:`.sheet`, the font and its metrics in :mod:`.text`."""

    link: float = 0.7
    vector: float = 0.35
    thin: float = 0.25
    text: float = 3.5
    small_text: float = 2.5
    title_text: float = 5.0
    arrow_length: float = 3.5
    arrow_width: float = 1.2
    joint_radius: float = 1.3
    support_size: float = 5.0
    hatch_step: float = 1.8
    hatch_length: float = 2.2
    decimals: int = 3
    dash: str = "3 1.5"
    colour: str = "#000"
    vector_colour: str = "#1f3a93"
    component_colour: str = "#a12a2a"
    construction_colour: str = "#666"

    def __post_init__(self) -> None:
        for name in ("link", "vector", "thin", "text", "arrow_length", "arrow_width", "joint_radius"):
            if not getattr(self, name) > 0:
                raise ValueError(f"Style.{name} must be positive")
        if not 1 <= self.decimals <= 8:
            raise ValueError("Style.decimals must be between 1 and 8")

    @property
    def precision(self) -> float:
        """Largest rounding error of one written coordinate, mm."""
        return 0.5 * 10.0 ** -self.decimals
