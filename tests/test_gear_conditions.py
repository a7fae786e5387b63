"""What the gear sheet writes about its train: the ratio to the carrier and Willis' check with the
solved speeds, and a synthesised train's conditions with their numbers
(:mod:`plans.gears.conditions`), against hand computation from the teeth."""

from __future__ import annotations

from fractions import Fraction
from math import gcd

from plans.gears import analyse_train
from plans.gears.conditions import synthesis_conditions, train_checks
from plans.gears.synthesis import synthesize
from plans.scene import read_scene


def _train(stem: str):
    from plans.examples import __path__ as where
    return read_scene(f"{where[0]}/gears/{stem}.toml").gears


def test_the_ratio_to_the_carrier_and_willis_are_written_with_the_speeds():
    """Planetary 1-2-3-H, z = 20/30/80 (the ring fixed): i_1H = 1 + 80/20 = 5, so n_H = 1450/5 = 290;
    Willis: (1450 − 290)/(0 − 290) = −4 = −z3/z1."""
    train = _train("planetary_1_21")
    z = {w.name: w.teeth for w in train.wheels}
    assert Fraction(z["3"], z["1"]) == 4
    rows = train_checks(analyse_train(train).speeds)
    assert "i_{1H} = n_{1}/n_{H} = 1450/290 = 5" in rows
    assert any(r.startswith("Willis: (n_{1} − n_{H})/(n_{3} − n_{H}) = (1450 − 290)/(0 − 290) = −4;") and
               r.endswith("from the teeth i_{13}(H) = −4") for r in rows), rows


def test_a_synthesised_train_writes_its_conditions_with_the_numbers():
    """Scheme C, i = 60, three planets: the first candidate's conditions recomputed here from its
    teeth (coaxial b1 − g = b2 − g2; assembly b1·(1 − g·b2/(b1·g2))·g2/(k·gcd(g, g2)) whole;
    neighbourhood (b1 − g)·sin(π/k) > max(g, g2) + 2)."""
    import math
    c = synthesize(60.0, "C", 3, tolerance=0.01, module=2.0)[0]
    b1, g, g2, b2 = (c.teeth[n] for n in ("b1", "g", "g2", "b2"))
    assert b1 - g == b2 - g2
    n = Fraction(b1) * (1 - Fraction(g * b2, b1 * g2)) * g2 / (3 * gcd(g, g2))
    assert n.denominator == 1
    rows = synthesis_conditions(c, 3)
    assert rows[0] == f"coaxial: z_{{b1}} − z_{{g}} = z_{{b2}} − z_{{g2}}: {b1} − {g} = {b2} − {g2} = {b1 - g}"
    assert rows[1].endswith(f"= {int(n)} (whole)")
    assert f"{(b1 - g) * math.sin(math.pi / 3):.3f} > max(z_{{g}}, z_{{g2}}) + 2 = {max(g, g2) + 2}" in rows[2]
    assert f"z_{{g}} = {g}, z_{{g2}} = {g2} ≥ 17" in rows[3] and f"z_{{b1}} − z_{{g}} = {b1 - g} ≥ 8" in rows[3]
