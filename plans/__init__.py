"""plans: velocity and acceleration plans of planar linkages, drawn to scale.

Data flows one way: scene → model → structure → kinematics → constructions → drawing →
checking. The names a mechanism engineer uses are the public API; ``plans.render(scene)``
renders a scene (or a scene file) to :class:`Sheets`, which Jupyter displays and ``.save``
writes.
"""

from .errors import (AssemblyError, DrawingError, OutputError, PlansError, SceneError, SingularPositionError,
                     StructureError)
from . import gears
from .kinematics import Motion, analyse
from .model import Mechanism, build_mechanism
from .pipeline import Sheet, Sheets, render
from .scene import Scene, parse_scene, read_scene
from .structure import Structure, analyse_structure

__all__ = ["AssemblyError", "DrawingError", "OutputError", "PlansError", "SceneError", "SingularPositionError",
           "StructureError", "Motion", "analyse", "Mechanism", "build_mechanism", "Scene", "parse_scene",
           "read_scene", "Sheet", "Sheets", "render", "Structure", "analyse_structure"]
def _version() -> str:
    """The installed distribution's version (pyproject.toml's), or pyproject.toml's own beside an
    uninstalled checkout."""
    from importlib import metadata
    from pathlib import Path

    here = Path(__file__).resolve().parent.parent / "pyproject.toml"
    if here.is_file():                      # a checkout: its pyproject is the truth
        import tomllib

        try:
            project = tomllib.loads(here.read_text(encoding="utf-8")).get("project", {})
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            project = {}
        if project.get("name") == "plans" and isinstance(project.get("version"), str):
            return project["version"]       # not another project's pyproject beside a copied package
    try:
        return metadata.version("plans")
    except metadata.PackageNotFoundError:   # pragma: no cover - neither installed nor a checkout
        return "0+unknown"


__version__ = _version()
