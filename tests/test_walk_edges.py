"""Walking a mechanism to its positions at the edges: a class III crank that cannot turn fully
asked for angles on both sides of its sketch (a walk per side, the values the walk of each angle
alone gives), a drive inside the chain at its limit, a cycle of a coupler drive, and messages
that print angles as the scene gives them."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

import plans
from plans.kinematics import solve as solve_mod

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def _partial_crank():
    scene = plans.read_scene(EXAMPLES / "koshel_variant1.toml")
    o, a = np.array(scene.points["O"]), np.array(scene.points["A"])
    points = dict(scene.points, A=tuple(float(c) for c in o + 2.5 * (a - o)))
    return dataclasses.replace(scene, points=points, lengths={})


def test_a_crank_that_cannot_turn_is_walked_once_per_side_with_the_same_values(monkeypatch):
    scene = _partial_crank()
    angles = np.concatenate([np.arange(0.0, 171.0, 7.0), np.arange(275.0, 360.0, 7.0)])
    mech = plans.build_mechanism(dataclasses.replace(scene, drive=dataclasses.replace(scene.drive,
                                                                                       values=tuple(angles))))
    structure = plans.analyse_structure(mech)
    walks = []
    original = solve_mod._positions
    monkeypatch.setattr(solve_mod, "_positions", lambda *a, **k: walks.append(1) or original(*a, **k))
    motion = plans.analyse(mech, structure, order=0)
    assert len(walks) <= 1 + 2 * (1 + int(np.ceil(np.log2(len(angles)))))     # not one per angle
    for k in range(0, len(angles), 5):
        alone = solve_mod._one_way(mech, structure, float(angles[k]))
        for name, state in alone.items():
            assert np.allclose(state.origin[0], motion.links[name].origin[k], rtol=0, atol=1e-12)
            assert np.isclose(np.cos(state.theta[0]), np.cos(motion.links[name].theta[k]), rtol=0, atol=1e-12)
    crank = motion.links[mech.drive.link].theta         # the crank at the angles as given (whole turns kept)
    assert np.allclose(np.diff(crank), np.radians(np.diff(angles)), rtol=0, atol=1e-12)


def test_an_angle_the_crank_cannot_reach_is_reported_as_alone(tmp_path):
    scene = _partial_crank()
    values = (10.0, 200.0, 300.0)          # 200° lies beyond both limits
    s = dataclasses.replace(scene, drive=dataclasses.replace(scene.drive, values=values), draw=("scheme",))
    with pytest.raises(plans.AssemblyError) as err:
        plans.render(s, stem="x")
    mech = plans.build_mechanism(s)
    with pytest.raises(plans.AssemblyError) as alone:
        solve_mod._one_way(mech, plans.analyse_structure(mech), 200.0)
    assert str(err.value).endswith(str(alone.value))


def test_a_cylinder_beyond_its_limit_says_the_drive_reached_a_limit_position(tmp_path):
    text = (EXAMPLES / "hydraulic_boom.toml").read_text(encoding="utf-8")
    text = re.sub(r"displacement = \[[^\]]*\]", "displacement = [0.0, -0.5]", text)
    scene = tmp_path / "b.toml"
    scene.write_text(text, encoding="utf-8")
    with pytest.raises(plans.AssemblyError) as err:
        plans.render(scene)
    msg = str(err.value)
    assert "the drive reaches a limit position between" in msg and "falls apart" not in msg
    lo, hi = (float(x) for x in re.search(r"between (-?[0-9.]+) and (-?[0-9.]+) m", msg).groups())
    # the limit: the last stroke the group follows and the first it does not
    ok = dataclasses.replace(plans.read_scene(scene), draw=("scheme",))
    plans.render(dataclasses.replace(ok, drive=dataclasses.replace(ok.drive, values=(0.0, hi))), stem="x")
    with pytest.raises(plans.AssemblyError):
        plans.render(dataclasses.replace(ok, drive=dataclasses.replace(ok.drive, values=(0.0, lo))), stem="x")


def test_a_cycle_of_a_coupler_drive_is_refused_in_one_line(tmp_path):
    text = (EXAMPLES / "four_bar_coupler_drive.toml").read_text(encoding="utf-8")
    text = re.sub(r"angle = \[[^\]]*\]", "angle = 36.0\npositions = 12", text)
    scene = tmp_path / "c.toml"
    scene.write_text(text, encoding="utf-8")
    with pytest.raises(plans.SceneError) as err:
        plans.read_scene(scene) and plans.render(scene)
    assert err.value.key == "drive.positions" and "coupler" in str(err.value)


def test_the_walk_message_prints_the_sketch_as_drawn():
    from plans.kinematics.walk import Walk, failure

    scene = plans.read_scene(EXAMPLES / "four_bar.toml")
    mech = plans.build_mechanism(scene)
    g = plans.analyse_structure(mech).groups[0]
    sketch = mech.drive.sketch_value
    grid = np.array([sketch + 360.0, sketch + 359.0, sketch + 358.0])
    walk = Walk(grid=grid, sweeps=[np.array([0, 1, 2])], requested=np.array([sketch + 358.0]), index=np.array([2]))
    msg = str(failure(mech, g, walk, 1, "cannot assemble"))
    assert f"the walk from the sketch at {sketch:g}°, taken as {sketch + 360:g}°" in msg
