"""plans: velocity and acceleration plans of planar linkages, drawn to scale.

Data flows one way: scene → model → structure → kinematics → constructions → drawing →
checking. The names a mechanism engineer uses are the public API.
"""

from .errors import (AssemblyError, DrawingError, PlansError, SceneError, SingularPositionError,
                     StructureError)
from .kinematics import Motion, analyse
from .model import Mechanism, build_mechanism
from .scene import Scene, parse_scene, read_scene
from .structure import Structure, analyse_structure

__all__ = ["AssemblyError", "DrawingError", "PlansError", "SceneError", "SingularPositionError",
           "StructureError", "Motion", "analyse", "Mechanism", "build_mechanism", "Scene", "parse_scene",
           "read_scene", "Structure", "analyse_structure"]
__version__ = "0.1.0"
