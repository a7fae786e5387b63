"""The one-way data flow: kinematics → constructions → drawing. ``Motion`` carries everything
the kinematics knows (special points, centres, sliding, angles, the triads' cross-check); the
constructions and the pipeline read it and compute no kinematics themselves, and drawing and
checking do not see the kinematics at all. And what Motion carries is right: its centres and
special points against independent computations."""

from __future__ import annotations

import ast
import dataclasses
import importlib
import inspect
import tomllib
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from conftest import EXAMPLES
from plans.kinematics import analyse
from plans.kinematics.state import J, cross
from plans.model import build_mechanism
from plans.scene import FRAME, parse_scene
from plans.structure import analyse_structure

PACKAGE = Path(__file__).resolve().parent.parent / "plans"
KINEMATICS = "plans.kinematics"

#: What constructions may call of plans.kinematics besides Motion's own methods and the value
#: types (frozen dataclasses such as Motion, Axis, Sliding, Centres): plane geometry (k × v,
#: the z cross product) and which groups of a structure are class III — no kinematics.
CONSTRUCTIONS_MAY_CALL = {"plans.kinematics.state.J", "plans.kinematics.state.cross",
                          "plans.kinematics.special.supports", "plans.kinematics.special.triad_groups"}
#: The pipeline solves the scene (that is its kinematics step: one analysis, or the revolution
#: of ``[drive] positions``, and, when the scene asks, every assembly of its groups — of one group
#: at the first position when ``[plans] assembly`` chooses which to start from) and reads the
#: Motion it gets; ``walk.fmt`` only writes a drive's value in a message.
PIPELINE_MAY_CALL = {"plans.kinematics.solve.analyse", "plans.kinematics.cycle.solve_cycle",
                     "plans.kinematics.assemblies.assemblies", "plans.kinematics.assemblies.group_assemblies",
                     "plans.kinematics.walk.fmt"}
#: LinkState's methods that compute motion: called only on a Motion (``motion.velocity(…)``,
#: ``b.motion.velocity_at(…)``), never on a link state (``motion.links[l].velocity(x)``).
STATE_METHODS = {"velocity", "acceleration", "with_velocity", "with_acceleration", "take", "seeded"}


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def _imported(tree: ast.Module, module: str, is_package: bool = False) -> dict[str, str]:
    """Local name → dotted name of every name the module imports from anywhere."""
    package = module.split(".") if is_package else module.split(".")[:-1]
    out = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                out[a.asname or a.name.split(".")[0]] = a.name if a.asname else a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                base = ".".join(package[:len(package) - node.level + 1] + ([base] if base else []))
            for a in node.names:
                out[a.asname or a.name] = f"{base}.{a.name}"
    return out


def _dotted(node: ast.AST) -> list[str] | None:
    """``a.b.c`` as ["a", "b", "c"] (None for anything but names and attributes)."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if not isinstance(node, ast.Name):
        return None
    return [node.id] + parts[::-1]


def _resolve(dotted: str):
    """The object a dotted name of the package names, and its canonical dotted name."""
    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for p in parts[k:]:
            obj = getattr(obj, p)
        if isinstance(obj, ModuleType):
            return obj, obj.__name__
        name = f"{getattr(obj, '__module__', '')}.{getattr(obj, '__qualname__', parts[-1])}"
        return obj, name
    raise ImportError(dotted)


def _is_motion(node: ast.AST) -> bool:
    """True for an expression naming a Motion: ``motion``, ``self.motion``, ``b.motion``."""
    return (isinstance(node, ast.Name) and node.id == "motion") or \
        (isinstance(node, ast.Attribute) and node.attr == "motion")


def kinematics_uses(source: str, module: str, may_call: set[str]) -> list[str]:
    """Every place the source computes kinematics: a reference to a function (or a class that
    is not a value type) of plans.kinematics outside ``may_call``, or a LinkState method of
    :data:`STATE_METHODS` called on anything but a Motion."""
    tree = ast.parse(source)
    names = _imported(tree, module)
    out = []
    outer: set[int] = set()    # attribute chains already looked at as a whole
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in STATE_METHODS \
                and not _is_motion(node.func.value):
            out.append(f"line {node.lineno}: .{node.func.attr}(…) on {ast.unparse(node.func.value)}, not on a Motion")
        if not isinstance(node, (ast.Name, ast.Attribute)) or id(node) in outer:
            continue
        inner = node
        while isinstance(inner, ast.Attribute):
            outer.add(id(inner.value))
            inner = inner.value
        parts = _dotted(node)
        if not parts or parts[0] not in names:
            continue
        full = ".".join([names[parts[0]]] + parts[1:])
        if not (full == KINEMATICS or full.startswith(KINEMATICS + ".")):
            continue
        # the longest prefix that is an attribute of the package (``special.axes`` of ``special.axes(...).x``)
        obj, canonical = None, full
        for k in range(len(parts), 0, -1):
            try:
                obj, canonical = _resolve(".".join([names[parts[0]]] + parts[1:k]))
                break
            except (ImportError, AttributeError):
                continue
        if isinstance(obj, ModuleType) or canonical in may_call:
            continue
        if inspect.isclass(obj) and dataclasses.is_dataclass(obj):
            continue       # a value type: Motion, LinkState, Axis, SpecialPoint, Sliding, Centres …
        if callable(obj):
            out.append(f"line {node.lineno}: {ast.unparse(node)} ({canonical})")
    return out


def _sources(folder: str) -> list[Path]:
    return sorted((PACKAGE / folder).glob("*.py"))


#: Every module of the pipeline package (its sheet families included).
PIPELINE = PACKAGE / "pipeline"


def _pipeline_sources() -> list[Path]:
    return sorted(PIPELINE.rglob("*.py"))


def test_the_pipeline_package_is_found():
    assert PIPELINE / "__init__.py" in _pipeline_sources() and len(_pipeline_sources()) > 1


@pytest.mark.parametrize("path", _sources("constructions") + _pipeline_sources(),
                         ids=lambda p: p.relative_to(PACKAGE).as_posix())
def test_constructions_and_pipeline_compute_no_kinematics(path):
    """Constructions read the Motion (its methods and cached values) and call nothing of
    plans.kinematics but J, cross, special.supports and special.triad_groups; the pipeline calls
    analyse (its kinematics step) and reads the Motion."""
    may = PIPELINE_MAY_CALL if PIPELINE in path.parents else CONSTRUCTIONS_MAY_CALL
    # a package's __init__ resolves its relative imports from the package itself
    module = _module_name(path) + (".__init__" if path.name == "__init__.py" else "")
    assert kinematics_uses(path.read_text(encoding="utf-8"), module, may) == []


@pytest.mark.parametrize("path", _sources("drawing") + sorted(PACKAGE.glob("checking*.py")) + _sources("layout"),
                         ids=lambda p: p.relative_to(PACKAGE).as_posix())
def test_drawing_and_checking_import_nothing_of_kinematics(path):
    tree = ast.parse(path.read_text(encoding="utf-8"))
    bad = [f"{local} = {full}" for local, full in _imported(tree, _module_name(path), path.name == "__init__.py").items()
           if full == KINEMATICS or full.startswith(KINEMATICS + ".")]
    assert bad == []


@pytest.mark.parametrize("source, found", [
    ("from ..kinematics import special\ndef f(g, m, s):\n    return special.axes(g, m, s)[0]", "special.axes"),
    ("from ..kinematics.special import known_acceleration as k\nx = k", "k ("),
    ("from ..kinematics.centres import centres\ndef f(motion):\n    return centres(motion)", "centres"),
    ("import plans.kinematics.sliders\nf = plans.kinematics.sliders.link_angles", "link_angles"),
    ("def f(motion, i):\n    return motion.links['2'].take(i).velocity(0)", ".velocity(…) on motion.links['2'].take(i)"),
    ("def f(state, x):\n    return state.acceleration(x)", ".acceleration(…) on state"),
])
def test_the_rule_catches_kinematics_in_a_construction(source, found):
    uses = kinematics_uses(source, "plans.constructions.example", CONSTRUCTIONS_MAY_CALL)
    assert any(found in u for u in uses), uses


def test_the_rule_lets_constructions_read_motion():
    source = ("from ..kinematics import Motion, special\nfrom ..kinematics.state import J\n"
              "def f(motion: Motion, b, g, i):\n"
              "    ax: special.Axis = motion.special_points[g.name].axes[0]\n"
              "    return J(ax.direction[i]), motion.velocity('B')[i], b.motion.velocity_at('3', ax.pin[i], i), "
              "motion.centres.absolute['3'], special.triad_groups(motion.structure)")
    assert kinematics_uses(source, "plans.constructions.example", CONSTRUCTIONS_MAY_CALL) == []


# --- what Motion carries, against independent computations ---------------------------------

def _motion(path: Path, order: int = 2, values=None):
    mech = build_mechanism(parse_scene(tomllib.loads(path.read_text(encoding="utf-8"))))
    return analyse(mech, analyse_structure(mech), values, order=order)


FULL_TURN = np.arange(24) * 15.0 + 5.0


def test_motion_computes_its_derived_values_once_and_only_when_asked():
    motion = _motion(next(p for p in EXAMPLES if p.stem == "class3_six_link"))
    lazy = ("special_points", "triads", "triad_disagreement", "centres", "angles", "sliding")
    assert not set(lazy) & set(motion.__dict__)
    for name in lazy:
        assert getattr(motion, name) is getattr(motion, name)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_absolute_centres_are_where_the_normals_to_two_velocities_meet(path):
    """P_j from two points X, Y of link j: (P − X)·v_X = 0 and (P − Y)·v_Y = 0, solved here
    (X, Y: the link's first point and the link's points one size away from it along x and y,
    the pair whose velocities are the farthest from parallel); Motion.centre_from too."""
    motion = _motion(path, order=1)
    mech, size = motion.mechanism, motion.mechanism.size
    checked = 0
    for link in mech.moving:
        first = mech.links[link].points[0]
        x = motion.position(first)
        where = [x, x + [size, 0.0], x + [0.0, size]]
        vel = [motion.velocity_at(link, w) for w in where]
        centre = motion.centres.absolute[link].point
        omega = motion.links[link].omega
        for i in range(len(motion)):
            if abs(omega[i]) * size <= 1e-6 * max(np.linalg.norm(v[i]) for v in vel):
                assert np.isnan(centre[i, 0]) or np.linalg.norm(centre[i] - x[i]) > 1e3 * size
                continue      # the link (nearly) translates: its centre is at infinity (or very far)
            a, b = max(((a, b) for a in range(3) for b in range(a + 1, 3)),
                       key=lambda ab: abs(cross(vel[ab[0]][i], vel[ab[1]][i])))
            m = np.array([vel[a][i], vel[b][i]])
            p = np.linalg.solve(m, [vel[a][i] @ where[a][i], vel[b][i] @ where[b][i]])
            tol = 1e-9 * max(size, np.linalg.norm(p))
            assert np.allclose(centre[i], p, rtol=0, atol=tol), (link, i, centre[i], p)
            assert np.allclose(motion.centre_from(link, first, i), p, rtol=0, atol=tol)
            checked += 1
    assert checked > 0 or not mech.drive.speed


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_relative_centres_move_alike_on_both_links(path):
    """P_ij is the point with one velocity on links i and j (the frame's: zero)."""
    motion = _motion(path, order=1)
    size = motion.mechanism.size
    speed = max(float(np.max(np.abs(motion.velocity(q)))) for q in motion.mechanism.sketch)
    ic = motion.centres
    pairs = [((i, FRAME), c) for i, c in ic.absolute.items()] + list(ic.relative.items())
    for (i, j), c in pairs:
        finite = ~np.isnan(c.point[:, 0])
        if not finite.any():
            continue
        p = np.where(finite[:, None], c.point, 0.0)
        vi = motion.velocity_at(i, p)
        vj = np.zeros_like(vi) if j == FRAME else motion.velocity_at(j, p)
        gap = np.linalg.norm(vi - vj, axis=1)[finite]
        far = np.maximum(1.0, np.linalg.norm(p[finite], axis=1) / size)
        assert np.all(gap <= 1e-9 * speed * far), (i, j, float(np.max(gap / far)))


def _axis(motion, g, rod):
    """A rod's axis from the scene's points and the sliding direction (not special.axes):
    a point on it (N, 2) and its direction (N, 2)."""
    if rod.form == "RR":
        a, b = motion.position(rod.outer.point), motion.position(rod.inner.point)
        return a, b - a
    pr = rod.outer.prismatic if rod.form == "PR" else rod.inner.prismatic
    u = next(s.u for s in motion.sliding.values() if (s.slider, s.guide, s.point) == (pr.slider, pr.guide, pr.label))
    through = motion.position(rod.inner.point if rod.form == "PR" else rod.outer.point)
    return through, J(u)


@pytest.mark.parametrize("path", [p for p in EXAMPLES if "triad" in p.stem or "koshel" in p.stem
                                  or "class3" in p.stem], ids=lambda p: p.stem)
def test_special_points_lie_on_the_axes_and_move_as_the_triad_solution(path):
    """Each S of Motion.special_points lies on its two rods' axes (built here from the scene's
    points); v_S, a_S as points of the base link are those of the independent special-point
    solution (Motion.triads); v_S − v_S(k) and a_S − (a_K + c) are ⊥ each of the two axes."""
    motion = _motion(path, values=FULL_TURN)
    size = motion.mechanism.size
    v_scale = max(float(np.max(np.abs(motion.velocity(q)))) for q in motion.mechanism.sketch)
    a_scale = max(float(np.max(np.abs(motion.acceleration(q)))) for q in motion.mechanism.sketch)
    assert motion.special_points
    for name, found in motion.special_points.items():
        g = found.group
        solution = {p.name: p for p in motion.triads[name].points}
        for k, p in enumerate(found.points):
            ok = np.abs(p.sin) > 0.05                           # well away from parallel axes
            assert ok.any()
            s = p.position
            v_ref, a_ref = solution[p.name].v, solution[p.name].a
            far = np.maximum(1.0, np.linalg.norm(s - motion.position(g.rods[0].inner.point), axis=1) / size)[:, None]
            assert np.all(np.abs(p.v - v_ref)[ok] <= 1e-9 * v_scale * far[ok])
            assert np.all(np.abs(p.a - a_ref)[ok] <= 1e-9 * a_scale * far[ok])
            for r in p.rods:
                rod = g.rods[r]
                through, d = _axis(motion, g, rod)
                d = d / np.linalg.norm(d, axis=1, keepdims=True)
                far = np.maximum(1.0, np.linalg.norm(s - through, axis=1) / size)
                assert np.all(np.abs(cross(s - through, d))[ok] <= 1e-9 * size * far[ok]), (name, p.name, r)
                known = rod.outer.b
                v_rel = p.v - motion.velocity_at(known, s)
                assert np.all(np.abs(np.sum(v_rel * d, axis=1))[ok] <= 1e-9 * far[ok] * v_scale), r
                a_rel = p.a - found.known[(k, r)]
                assert np.all(np.abs(np.sum(a_rel * d, axis=1))[ok] <= 1e-9 * far[ok] * a_scale), r
