"""The structural search on long chains: polynomial, independent of the order of [links].

The scenes are chains of parallelogram four-bars: a crank, then ``stages`` RRR dyads, dyad k
(coupler 2k, rocker 2k+1) pinned to the previous rocker (the crank for k = 1) and to the frame.
Every cell is a parallelogram (frame pivots 1 m apart, every rocker parallel to the crank), so
the sketch is an assembled position and every rocker turns with the crank. Couplers alternate
between two levels of the rockers (points Q at (k + 0.3, 1), R at (k + 0.6, 2)), so no pin
joins more than two links.

Timings are in ``benchmarks/structure_scale.py``; these tests check results and count work.
"""

from __future__ import annotations

import math
import random

import pytest

import plans.structure.search as structure
from plans.errors import StructureError
from plans.model import build_mechanism
from plans.scene import FRAME, parse_scene
from plans.structure import ComplexGroup, Group, analyse_structure

DX, DY = 0.3, 1.0        # the crank's direction (and every rocker's), per level


def chain_scene(stages: int, *, order: str = "forward", defect: str | None = None, at: int = 1,
                seed: int = 0) -> dict:
    """A crank followed by ``stages`` RRR dyads (1 + 2·stages moving links), as a scene dict.

    ``order``: ``"forward"`` (links 0, 1, 2, …), ``"reverse"`` (the whole [links] table
    reversed) or ``"shuffle"`` (a random order from ``seed``).

    ``defect`` breaks the chain:

    * ``"moved"`` — dyad ``at`` is unpinned from the previous rocker (its coupler gets a point
      of its own there) and the last rocker is pinned to the frame a second time (point S):
      W stays 1, but links from dyad ``at`` on do not split into Assur groups (they move
      without the drive, except the last rocker, which is locked);
    * ``"removed"`` — dyad ``at`` unpinned from the previous rocker only: W = 3;
    * ``"added"`` — the last rocker pinned to the frame a second time only: W = −1.
    """
    if stages < 1 or not 1 <= at <= stages:
        raise ValueError("need stages >= 1 and 1 <= at <= stages")
    level = {1: ("Q", 1.0), 2: ("R", 2.0)}

    def lv(k: int) -> int:     # the level of coupler k
        return 1 if k % 2 else 2

    points: dict[str, list[float]] = {}
    for k in range(stages + 1):
        points[f"P{k}"] = [float(k), 0.0]
        for n, (letter, f) in level.items():
            if (k >= 1 and lv(k) == n) or (k < stages and lv(k + 1) == n):
                points[f"{letter}{k}"] = [k + f * DX, f * DY]
    links: dict[str, list[str]] = {FRAME: [f"P{k}" for k in range(stages + 1)],
                                   "1": ["P0", f"{level[lv(1)][0]}0"]}
    for k in range(1, stages + 1):
        letter = level[lv(k)][0]
        start = f"{letter}{k - 1}"
        if defect in ("moved", "removed") and k == at:
            start = f"{letter}{k - 1}x"          # the coupler's own point where the pin was
            points[start] = list(points[f"{letter}{k - 1}"])
        links[str(2 * k)] = [start, f"{letter}{k}"]
        links[str(2 * k + 1)] = [f"P{k}", f"{letter}{k}"] + ([f"{level[lv(k + 1)][0]}{k}"] if k < stages else [])
    if defect in ("moved", "added"):
        # a second pin of the last rocker on the frame, at the middle of its arm (no coupler
        # there, so the locked rocker gives no dyad a known pin to start from)
        pivot, arm = points[f"P{stages}"], points[links[str(2 * stages + 1)][1]]
        points["S"] = [(pivot[0] + arm[0]) / 2, (pivot[1] + arm[1]) / 2]
        links[str(2 * stages + 1)].append("S")
        links[FRAME].append("S")
    elif defect not in (None, "removed"):
        raise ValueError(f"unknown defect {defect!r}")
    names = list(links)
    if order == "reverse":
        names.reverse()
    elif order == "shuffle":
        random.Random(seed).shuffle(names)
    elif order != "forward":
        raise ValueError(f"unknown order {order!r}")
    crank = level[lv(1)][0] + "0"
    angle = round(math.degrees(math.atan2(points[crank][1], points[crank][0])), 6)
    return {"title": f"Chain of {stages} four-bars", "points": points, "links": {n: links[n] for n in names},
            "drive": {"link": "1", "angle": [angle, angle + 1.0], "omega": 1.0, "epsilon": 0.0}}


def group_chain_scene(stages: int, kind: str, *, order: str = "forward", seed: int = 0) -> dict:
    """A crank followed by ``stages`` class III triads (``kind="triad"``: base and three rods,
    one rod pinned to the previous group, two to the frame) or class IV contours
    (``kind="contour"``: four links in a ring, one pinned to the previous group, the opposite
    one to the frame): 1 + 4·stages moving links. The sketch is random (seeded) in cells 3 m
    wide; as every length is taken from it, it is an assembled position."""
    rng = random.Random(seed)
    points: dict[str, list[float]] = {"O": [0.0, 0.0], "A": [0.2, 0.3]}
    links: dict[str, list[str]] = {FRAME: ["O"], "1": ["O", "A"]}

    def point(name: str, k: int) -> str:
        points[name] = [3.0 * k + rng.uniform(0.0, 3.0), rng.uniform(-1.0, 3.0)]
        return name

    prev, pin = "1", "A"             # the link the next group is pinned to, and the pin
    for k in range(1, stages + 1):
        a, b, c, d = (str(4 * k + i - 2) for i in range(4))
        if kind == "triad":              # base a; rods b (to the previous group), c, d (to the frame)
            links[a] = [point(f"a{k}", k), point(f"b{k}", k), point(f"c{k}", k)]
            links[b] = [pin, f"a{k}"]
            links[c] = [point(f"F{k}", k), f"b{k}"]
            links[d] = [point(f"G{k}", k), f"c{k}"]
            links[FRAME] += [f"F{k}", f"G{k}"]
            prev = a
        elif kind == "contour":          # ring a-b-c-d; a to the previous group, c to the frame
            links[a] = [pin, point(f"ab{k}", k), point(f"da{k}", k)]
            links[b] = [f"ab{k}", point(f"bc{k}", k)]
            links[c] = [f"bc{k}", point(f"cd{k}", k), point(f"F{k}", k)]
            links[d] = [f"cd{k}", f"da{k}"]
            links[FRAME].append(f"F{k}")
            prev = b
        else:
            raise ValueError(f"unknown kind {kind!r}")
        pin = point(f"n{k}", k)
        links[prev].append(pin)
    links[prev].remove(pin)              # the last group carries nothing further
    del points[pin]
    names = list(links)
    if order == "reverse":
        names.reverse()
    elif order == "shuffle":
        rng.shuffle(names)
    return {"title": f"Chain of {stages} {kind}s", "points": points, "links": {n: links[n] for n in names},
            "drive": {"link": "1", "angle": [56.3, 57.3], "omega": 1.0, "epsilon": 0.0}}


def structure_of(data: dict):
    return analyse_structure(build_mechanism(parse_scene(data)))


def _group_sets(st) -> list[frozenset[str]]:
    return [frozenset(g.links) for g in st.groups]


# --- the generator itself -------------------------------------------------------------------

def test_small_chain_is_a_chain_of_four_bars():
    st = structure_of(chain_scene(3))
    assert st.dof == 1 and st.moving == 7
    assert st.formula == "I(0-1) ← II(2-3) ← II(4-5) ← II(6-7)"
    assert all(isinstance(g, Group) and g.form == "RRR" for g in st.groups)


def test_sketch_is_assembled_parallelograms():
    """Every coupler is as long as the frame pitch and horizontal, every rocker parallel to
    the crank: each four-bar closes in the sketch."""
    data = chain_scene(6)
    pts = data["points"]
    for name, link in data["links"].items():
        if name in (FRAME, "1") or int(name) % 2:
            continue
        (x0, y0), (x1, y1) = pts[link[0]], pts[link[1]]
        assert (x1 - x0, y1 - y0) == pytest.approx((1.0, 0.0))
    for name, link in data["links"].items():
        if name != FRAME and (name == "1" or int(name) % 2):
            (x0, y0) = pts[link[0]]
            for p in link[1:]:
                x, y = pts[p]
                assert (x - x0) * DY == pytest.approx((y - y0) * DX)


def test_sketch_solves_at_a_second_position():
    """The chain moves: a short walk of the crank solves every dyad (kinematics untouched by
    the structural search, but the scenes must be real mechanisms)."""
    from plans.kinematics import analyse

    mech = build_mechanism(parse_scene(chain_scene(4)))
    motion = analyse(mech, analyse_structure(mech))
    assert motion is not None


# --- long valid chains --------------------------------------------------------------------

def test_200_links_in_order_and_reversed_give_the_same_groups():
    forward = structure_of(chain_scene(99))
    backward = structure_of(chain_scene(99, order="reverse"))
    assert forward.moving == backward.moving == 199 and forward.dof == backward.dof == 1
    assert len(forward.groups) == len(backward.groups) == 99
    assert _group_sets(forward) == _group_sets(backward)
    assert _group_sets(forward) == [frozenset((str(2 * k), str(2 * k + 1))) for k in range(1, 100)]
    assert forward.formula == "I(0-1) ← " + " ← ".join(f"II({2 * k}-{2 * k + 1})" for k in range(1, 100))
    # in reverse order each dyad is listed rocker first: the same group, named the other way
    assert backward.formula == "I(0-1) ← " + " ← ".join(f"II({2 * k + 1}-{2 * k})" for k in range(1, 100))
    assert all(g.form == "RRR" for g in forward.groups + backward.groups)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_shuffled_links_give_the_same_groups(seed):
    forward = structure_of(chain_scene(30))
    shuffled = structure_of(chain_scene(30, order="shuffle", seed=seed))
    assert _group_sets(shuffled) == _group_sets(forward)


@pytest.mark.parametrize("kind, klass, order", [("triad", 3, 3), ("contour", 4, 2)])
def test_200_links_of_class_iii_and_iv_groups_in_any_order(kind, klass, order):
    forward = structure_of(group_chain_scene(50, kind))
    assert forward.moving == 201 and forward.dof == 1 and forward.klass == klass
    assert all(isinstance(g, ComplexGroup) and (g.klass, g.order) == (klass, order) for g in forward.groups)
    assert _group_sets(forward) == [frozenset(str(4 * k + i - 2) for i in range(4)) for k in range(1, 51)]
    for other in ("reverse", "shuffle"):
        st = structure_of(group_chain_scene(50, kind, order=other))
        assert _group_sets(st) == _group_sets(forward)
        assert [g.base for g in st.groups] == [g.base for g in forward.groups]


# --- chains that do not split -------------------------------------------------------------

def test_200_links_that_do_not_split_are_refused_with_a_clear_message():
    data = chain_scene(99, defect="moved")
    with pytest.raises(StructureError) as info:
        structure_of(data)
    msg = str(info.value)
    assert "do not split into Assur groups" in msg and "attached to links 0, 1" in msg
    assert "198 links" in msg and len(msg) < 1000      # a long list of links is abbreviated
    assert "link 199 is held by 2 pairs on link 0 and cannot move (W = −1 of its own)" in msg


def test_refused_in_the_middle_names_what_was_attached():
    with pytest.raises(StructureError) as info:
        structure_of(chain_scene(99, defect="moved", at=50, order="reverse"))
    msg = str(info.value)
    assert "links 199, 198, 197, 196, 195, 194, …, 102, 101, 100 (100 links) do not split into Assur groups" in msg
    assert "attached to links 0, 1, 10, 11, 12, 13, …, 97, 98, 99 (100 links)" in msg and len(msg) < 1000


@pytest.mark.parametrize("defect, w", [("removed", "= 3"), ("added", "= -1")])
def test_a_pair_removed_or_added_changes_w(defect, w):
    with pytest.raises(StructureError, match=f"W = 3·199 − 2·[0-9]+ − 0 {w}"):
        structure_of(chain_scene(99, defect=defect))


# --- work grows polynomially --------------------------------------------------------------

class _Counter:
    """Counts the candidate checks (dyads, class III/IV fours) and the joint look-ups."""

    def __init__(self, monkeypatch):
        self.calls = 0
        for owner, name in ((structure, "_dyad_fit"), (structure, "_complex"), (structure._Index, "joints")):
            monkeypatch.setattr(owner, name, self._counted(getattr(owner, name)))

    def _counted(self, function):
        def counted(*args, **kwargs):
            self.calls += 1
            return function(*args, **kwargs)
        return counted


def _chain(kind: str, stages: int, order: str) -> dict:
    if kind == "dyads":
        return chain_scene(2 * stages, order=order)
    if kind == "refused":                   # half the chain attaches, then no group is found
        return chain_scene(2 * stages, order=order, defect="moved", at=stages)
    return group_chain_scene(stages, kind, order=order)


@pytest.mark.parametrize("order", ["forward", "reverse"])
@pytest.mark.parametrize("kind", ["dyads", "refused", "triad", "contour"])
def test_work_grows_at_most_quadratically(monkeypatch, kind, order):
    """Candidate checks and joint look-ups: a few per frontier link and step, however the
    links are listed (the old search tried every pair, then every four, of the remaining
    links at every step: ~n³/6 dyad and up to n⁵/24 pair look-ups). Doubling the chain at
    most quadruples the work."""
    counts = {}
    for stages in (5, 10, 20, 40):
        c = _Counter(monkeypatch)
        try:
            structure_of(_chain(kind, stages, order))
        except StructureError:
            assert kind == "refused"
        counts[stages] = c.calls
        n = 4 * stages + 1
        assert 0 < counts[stages] <= n * n
    assert all(counts[2 * s] <= 4.5 * counts[s] for s in (5, 10, 20)), counts


# --- the same answers as the exhaustive search ----------------------------------------------

def _exhaustive_original(ix, mech) -> tuple[str, ...]:
    """The original mechanism's links by the plain search: the driving link; for a drive
    inside the chain, the first set (fewest links, then [links] order) of links holding the
    driven ones, connected, touching the frame, with 3n − 2p = 1."""
    from itertools import combinations

    d = mech.drive
    if d.kind not in ("coupler", "cylinder"):
        return (d.link,)
    core = {d.link} | ({d.guide.guide} if d.kind == "cylinder" else set())
    for k in range(len(core), len(mech.moving) + 1):
        for links in combinations(mech.moving, k):
            pairs = ix.pairs_of(set(links), set(links) | {FRAME})
            if core <= set(links) and 3 * k - 2 * len(pairs) == 1 and len(ix.components(set(links))) == 1 \
                    and any(FRAME in (p.a, p.b) for p in pairs):
                return links
    raise AssertionError("no original mechanism")


def _exhaustive(mech):
    """The textbook search the indexed one replaces: the first pair (then four) of the
    remaining links, in [links] order, that forms a group on the known links."""
    from itertools import combinations

    ix = structure._Index(mech)
    known = {FRAME, *_exhaustive_original(ix, mech)}
    remaining = [n for n in mech.moving if n not in known]
    groups = []
    while remaining:
        group = next((structure._dyad(ix, known, a, b) for a, b in combinations(remaining, 2)
                      if structure._dyad_fit(ix, known, a, b)), None)
        if group is None:
            group = next((g for four in combinations(remaining, 4) if (g := structure._complex(ix, known, four))),
                         None)
        if group is None:
            return groups, False
        groups.append(group)
        known |= set(group.links)
        remaining = [r for r in remaining if r not in group.links]
    return groups, True


def _examples():
    from conftest import EXAMPLES
    return EXAMPLES


@pytest.mark.parametrize("path", _examples(), ids=lambda p: p.stem)
def test_examples_match_the_exhaustive_search(path):
    from plans.scene import read_scene

    mech = build_mechanism(read_scene(path))
    groups, ok = _exhaustive(mech)
    assert ok
    assert analyse_structure(mech).groups == tuple(groups)


def random_mechanism(rng: random.Random) -> dict:
    """A random scene built of Assur groups (dyads, triads, four-link contours with pins and
    sliders; outer pins often on a point already shared by other links), now and then with a
    point moved or added so it no longer splits, its [links] listed in a random order."""
    points: dict[str, list[float]] = {}

    def point() -> str:
        name = f"p{len(points)}"
        points[name] = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)]
        return name

    links: dict[str, list[str]] = {FRAME: [point(), point()]}
    links["1"] = [links[FRAME][0], point()]
    sliders: list[dict] = []
    known = [FRAME, "1"]

    def new_link() -> str:
        name = str(len(links))
        links[name] = []
        return name

    def join(a: str, b: str, slide: float = 0.15) -> None:
        """Pin (else slider, with probability ``slide``) ``a`` to ``b``."""
        if rng.random() < slide:
            if not links[a]:
                links[a].append(point())
            sliders.append({"link": a, "on": b, "through": [links[a][0]], "angle": rng.uniform(0.0, 180.0)})
            return
        shared = [p for p in links[b] if p not in links[a]]
        p = rng.choice(shared) if b in known and shared and rng.random() < 0.3 else point()
        for x in (a, b):
            if p not in links[x]:
                links[x].append(p)

    for _ in range(rng.randint(1, 4)):
        kind = rng.choice(["dyad", "dyad", "dyad", "triad", "contour"])
        if kind == "dyad":
            m, n = new_link(), new_link()
            join(m, rng.choice(known)), join(m, n), join(n, rng.choice(known))
            group = [m, n]
        elif kind == "triad":
            base, rods = new_link(), [new_link() for _ in range(3)]
            for r in rods:
                join(r, rng.choice(known)), join(r, base, slide=0.05)
            group = [base, *rods]
        else:
            ring = [new_link() for _ in range(4)]
            for a, b in zip(ring, ring[1:] + ring[:1]):
                join(a, b, slide=0.05)
            for a in rng.sample(ring, 2):
                join(a, rng.choice(known))
            group = ring
        for name in group:
            if not links[name]:
                links[name].append(point())
        known += group
    if rng.random() < 0.3:          # move or add a point: most such chains do not split
        moving = [k for k in links if k not in (FRAME, "1")]
        a, b = rng.sample(moving + [FRAME], 2)
        p = rng.choice(links[a])
        if p not in links[b]:
            links[b].append(p)
            if rng.random() < 0.5 and len(links[a]) > 1 and a != FRAME:
                links[a].remove(p)
    names = list(links)
    rng.shuffle(names)
    return {"points": points, "links": {k: links[k] for k in names}, "sliders": sliders,
            "drive": {"link": "1", "angle": [0.0], "omega": 1.0, "epsilon": 0.0}}


def test_random_mechanisms_match_the_exhaustive_search():
    """The indexed search attaches the very groups, in the very order and orientation, that
    the exhaustive one does — or refuses the same chains with the same error."""
    rng = random.Random(20240611)
    checked = split = refused = 0
    while checked < 300:
        try:
            mech = build_mechanism(parse_scene(random_mechanism(rng)))
        except Exception:       # not a valid scene (a moved drive pivot, a bent rod): not tested here
            continue
        checked += 1
        try:
            groups, ok = _exhaustive(mech)
        except StructureError as exc:           # a PPP dyad
            with pytest.raises(StructureError) as info:
                structure._decompose(structure._Index(mech), mech)
            assert str(info.value) == str(exc)
            continue
        if ok:
            split += 1
            assert structure._decompose(structure._Index(mech), mech) == groups
        else:
            refused += 1
            with pytest.raises(StructureError, match="do not split into Assur groups"):
                structure._decompose(structure._Index(mech), mech)
    assert split > 100 and refused > 20


def test_a_part_that_moves_on_its_own_is_named():
    """Below W: the decomposition itself says which links move without the drive."""
    mech = build_mechanism(parse_scene(chain_scene(5, defect="removed", at=3)))
    with pytest.raises(StructureError) as info:
        structure._decompose(structure._Index(mech), mech)
    assert str(info.value).endswith("attached to links 0, 1, 2, 3, 4, 5: links 6, 7, 8, 9, 10, 11 can move without "
                                    "the drive (W = 2 of their own) — a pair is misplaced")
