"""What a gear sheet writes out about its train: the ratio to each carrier and Willis' check
with the solved speeds (:func:`train_checks`), and, for a train found by planetary synthesis,
its four conditions with their numbers (:func:`synthesis_conditions`: coaxial, assembly,
neighbourhood, no undercut and no internal interference), in the sheets' label markup.

The conditions are those :mod:`plans.gears.synthesis` filters by, restated with the candidate's
teeth; the train's own analysis decided the candidate. Imports only plans.gears.
"""

from __future__ import annotations

import math
from fractions import Fraction

from .speeds import TrainSpeeds
from .synthesis import MIN_TEETH, RING_MARGIN, Candidate

__all__ = ["train_checks", "synthesis_conditions"]


def _n(x: Fraction | float) -> str:
    v = float(x)
    s = f"{v:.6g}"
    return s.replace("-", "−")


def train_checks(speeds: TrainSpeeds) -> tuple[str, ...]:
    """For each carrier H and each input j: i_jH = n_j/n_H with its numbers; for each Willis
    equation of the train: (n_a − n_H)/(n_b − n_H) with the solved speeds = i_ab(H) from the teeth
    (the ratio with the carrier H held)."""
    train = speeds.train
    rows = []
    for c in train.carriers:
        for j, _ in train.inputs:
            if j == c:
                continue
            r = speeds.ratio(j, c)
            if r is not None:
                rows.append(f"i_{{{j}{c}}} = n_{{{j}}}/n_{{{c}}} = {_n(speeds.rpm[j])}/{_n(speeds.rpm[c])} = {_n(r)}")
    for w in speeds.willis:
        na, nb, nh = speeds.rpm[w.a], speeds.rpm[w.b], speeds.rpm[w.carrier]
        rows.append(f"Willis: (n_{{{w.a}}} − n_{{{w.carrier}}})/(n_{{{w.b}}} − n_{{{w.carrier}}}) = "
                    f"({_n(na)} − {_n(nh)})/({_n(nb)} − {_n(nh)}) = "
                    f"{_n((na - nh) / (nb - nh)) if nb != nh else 'undefined'}; "
                    f"from the teeth i_{{{w.a}{w.b}}}({w.carrier}) = {str(w.ratio).replace('-', '−')}"
                    + ("" if w.ratio.denominator == 1 else f" ({_n(w.ratio)})"))
    return tuple(rows)


def synthesis_conditions(c: Candidate, planets: int) -> tuple[str, ...]:
    """The conditions of scheme ``c.kind`` with the candidate's teeth and k = ``planets``."""
    z, k = c.teeth, planets
    sin = math.sin(math.pi / k)
    if c.kind == "A":
        a, g, b = z["a"], z["g"], z["b"]
        arm = a + g
        return (f"coaxial: z_{{b}} = z_{{a}} + 2z_{{g}}: {b} = {a} + 2·{g}",
                f"assembly: (z_{{a}} + z_{{b}})/k = ({a} + {b})/{k} = {_n(Fraction(a + b, k))} (whole)",
                f"neighbourhood: (z_{{a}} + z_{{g}})·sin(π/k) > z_{{g}} + 2: {arm}·{sin:.4f} = {arm * sin:.3f} > {g + 2}",
                f"no undercut: z_{{a}} = {a}, z_{{g}} = {g} ≥ {MIN_TEETH}; no interference: z_{{b}} − z_{{g}} = "
                f"{b - g} ≥ {RING_MARGIN}")
    names = ("b1", "g", "g2", "b2") if c.kind == "C" else ("a", "g", "g2", "b")
    a, g, g2, b = (z[n] for n in names)
    A, B = names[0], names[3]
    i_ab = {"B": -Fraction(g * b, a * g2), "C": Fraction(g * b, a * g2), "D": Fraction(g * b, a * g2)}[c.kind]
    n = a * (1 - i_ab) * g2 / (k * math.gcd(g, g2))
    coax = {"B": (f"z_{{{A}}} + z_{{g}} = z_{{{B}}} − z_{{g2}}", f"{a} + {g} = {b} − {g2}", a + g),
            "C": (f"z_{{{A}}} − z_{{g}} = z_{{{B}}} − z_{{g2}}", f"{a} − {g} = {b} − {g2}", a - g),
            "D": (f"z_{{{A}}} + z_{{g}} = z_{{{B}}} + z_{{g2}}", f"{a} + {g} = {b} + {g2}", a + g)}[c.kind]
    arm = coax[2]
    rings = [(nm, zz, pl) for nm, zz, pl in ((A, a, g), (B, b, g2)) if (c.kind == "C" or (c.kind == "B" and nm == B))]
    external = [(nm, zz) for nm, zz in zip(names, (a, g, g2, b)) if nm not in {r[0] for r in rings}]
    rows = [f"coaxial: {coax[0]}: {coax[1]} = {arm}",
            f"assembly: z_{{{A}}}·(1 − i_{{{A}{B}}}(H))·z_{{g2}}/(k·gcd(z_{{g}}, z_{{g2}})) = "
            f"{a}·(1 − {_n(i_ab)})·{g2}/({k}·{math.gcd(g, g2)}) = {_n(n)} (whole)",
            f"neighbourhood: {arm}·sin(π/{k}) = {arm * sin:.3f} > max(z_{{g}}, z_{{g2}}) + 2 = {max(g, g2) + 2}",
            "no undercut: " + ", ".join(f"z_{{{nm}}} = {zz}" for nm, zz in external) + f" ≥ {MIN_TEETH}"
            + ("; no interference: " + ", ".join(f"z_{{{nm}}} − z_{{{'g' if zz == a else 'g2'}}} = {zz - pl} ≥ "
                                                  f"{RING_MARGIN}" for nm, zz, pl in rings) if rings else "")]
    return tuple(rows)
