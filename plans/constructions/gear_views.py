"""The meshing sheet's specific-sliding diagram (below the detail) and general view (left of it),
for an external pair, an internal pair and a pinion with a rack (see :mod:`.gear_pair`).

Imports numpy, plans.gears and the pair sheet's geometry only.
"""

from __future__ import annotations

import math

import numpy as np

from ..gears.pair import PairAnalysis
from .pair_sheet import OVERVIEW_MM, REDUCTIONS, RIM, SLIDING_MM, SLIDING_SERIES, PairSheet, Tag, arc

__all__ = ["specific_sliding", "sliding_diagram", "overview", "LAMBDA_MAX"]

#: The largest |λ| drawn: near N1 or N2 the specific sliding grows without bound (a tip reaching
#: to the tangency point); the curves are cut at ±LAMBDA_MAX and an ordinate beyond it is written.
LAMBDA_MAX = 50.0
#: A |λ| beyond this is the rounding of a tip passing exactly through N (λ infinite there).
UNBOUNDED = 1e9


def specific_sliding(a: PairAnalysis, rho1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """λ1, λ2 at the points of the line of action ``rho1`` (mm) from N1, positive toward P:
    λ1 = 1 − ρ2/(u·ρ1), λ2 = 1 − u·ρ1/ρ2, u = z2/z1, ρ2 = N1N2 − ρ1 (external) or N1N2 + ρ1
    (internal: N1 lies between N2 and P); a rack's λ1 = 1 − PN1/ρ1, λ2 = 1 − ρ1/PN1 (the forms of
    :mod:`plans.gears.involute` and :mod:`plans.gears.contact`)."""
    p = a.pair
    rho1 = np.asarray(rho1, float)
    if p.kind == "rack":
        pn1 = p.d[0] / 2.0 * math.sin(p.alpha)
        return 1.0 - pn1 / rho1, 1.0 - rho1 / pn1
    u = p.z[1] / p.z[0]
    rho2 = p.line - rho1 if p.kind == "external" else p.line + rho1
    return 1.0 - rho2 / (u * rho1), 1.0 - u * rho1 / rho2


def sliding_diagram(sheet: PairSheet, a: PairAnalysis) -> None:
    """The specific-sliding diagram below the detail (see :mod:`.gear_pair`), its curves cut at
    ±:data:`LAMBDA_MAX`."""
    p = a.pair
    k = sheet.k
    _, y0, _, _ = sheet.bounds()
    pn1 = p.dw[0] / 2.0 * math.sin(p.alpha_w)
    rho_b2, rho_b1 = pn1 - p.approach, pn1 + p.recess       # B2 and B1 from N1, mm
    if not 0.0 < rho_b2 < rho_b1:
        return                                       # interference: the sliding is not defined there
    rho = np.linspace(rho_b2, rho_b1, 80)
    l1, l2 = (np.clip(v, -LAMBDA_MAX, LAMBDA_MAX) for v in specific_sliding(a, rho))
    top = float(max(np.max(np.abs(l1)), np.max(np.abs(l2)), 1.0))
    mu = min(m * 10.0 ** e for e in range(-3, 4) for m in SLIDING_SERIES if top / (m * 10.0 ** e) <= SLIDING_MM)
    sheet.mu_sliding = mu
    up = float(max(np.max(l1), np.max(l2), 0.0)) / mu
    base = y0 - 14.0 - up                            # the axis, below the detail
    marks = [("N_1", 0.0), ("B_2", rho_b2), ("P", pn1), ("B_1", rho_b1)]
    if p.kind == "external":
        marks.append(("N_2", p.line))
    elif p.kind == "internal":
        marks.insert(0, ("N_2", -p.line))
    lo, hi = marks[0][1], marks[-1][1]
    left = -(lo + hi) / 2.0 * k
    at = {name: left + r * k for name, r in marks}
    sheet.curves.append(("sliding-axis", "thin", np.array([[left + lo * k - 4.0, base], [left + hi * k + 4.0, base]])))
    for name, x in at.items():
        sheet.curves.append((f"sliding-tick-{name}", "thin", np.array([[x, base - 1.2], [x, base + 1.2]])))
        sheet.labels.append((name.replace("_", "_{") + "}" if "_" in name else name, (x, base - 1.2), (0.0, -1.0)))
    xs = left + rho * k
    for i, lam in enumerate((l1, l2)):
        sheet.curves.append((f"sliding{i + 1}", "thick" if i == 0 else "thickdash", np.column_stack([xs, base + lam / mu])))
        end = len(xs) - 1 if i == 0 else 0
        sheet.labels.append((f"λ_{{{i + 1}}}", (float(xs[end]), float(base + lam[end] / mu)), (1.0 if i == 0 else -1.0,
                                                                                             0.3)))
    for name, r in (("B2", rho_b2), ("B1", rho_b1)):
        v1, v2 = specific_sliding(a, np.array([r]))
        x = left + r * k
        for i, v in enumerate((float(v1[0]), float(v2[0]))):
            if abs(v) > LAMBDA_MAX:                  # the tip reaches (almost) to N: written, not drawn
                value = f"= {v:.4g}".replace("-", "−") if abs(v) < UNBOUNDED else \
                    f"→ {'−' if v < 0 else ''}∞ ({name[0]}_{{{name[1]}}} at N)"
                sheet.labels.append((f"λ_{{{i + 1}}}({name[0]}_{{{name[1]}}}) {value}, off the diagram",
                                     (x, base - 6.0 - 4.0 * i), (1.0, -1.0)))
                continue
            sheet.tags.append(Tag("sliding", f"λ{i + 1}:{name}", abs(v), (x + (i - 0.5) * 1.2, base),
                                  (x + (i - 0.5) * 1.2, base + v / mu), (f"axis-{name}", f"λ{i + 1}-{name}")))
    along = "N_{1}N_{2}" if p.kind != "rack" else "the line of action from N_{1}"
    sheet.labels.append((f"specific sliding λ_{{1}}, λ_{{2}} along {along} (μ_{{λ}} = {mu:g} 1/mm)",
                         (left + lo * k, base + up + 6.0), (1.0, 0.0)))


def overview(sheet: PairSheet, a: PairAnalysis) -> None:
    """The general view (both wheels whole, reduced k0:1) left of the detail, with a_w and radii; a
    ring gear drawn about the pinion inside it, a rack as its lines under the pinion's circles."""
    p = a.pair
    if p.kind == "external":
        height = p.a_w + p.da[0] / 2 + p.da[1] / 2
        width = max(p.da)
    elif p.kind == "internal":
        height = width = p.df[1] + 2.0 * RIM * p.module
    else:
        height, width = p.da[0] + 4.0 * p.module, p.da[0] * 1.4
    k0 = next((r for r in REDUCTIONS if height * r <= OVERVIEW_MM), REDUCTIONS[-1])
    sheet.k0 = k0
    left, low, _, _ = sheet.bounds()
    x0 = left - 25.0 - width / 2 * k0
    if p.kind == "internal":
        o2 = np.array([x0, low + (p.df[1] / 2 + RIM * p.module) * k0])
        o1 = o2 + np.array([0.0, p.a_w * k0])
    else:
        o1 = np.array([x0, low + p.da[0] / 2 * k0])
        o2 = o1 + np.array([0.0, p.a_w * k0])
    shown = (("working", "dash"), ("tip", "thin"), ("base", "thin")) + ((("root", "thin"),)
                                                                         if p.kind == "internal" else ())
    for i, centre in enumerate((o1, o2)):
        for name, kind in shown:
            d = {"working": p.dw, "tip": p.da, "base": p.db, "root": p.df}[name][i]
            if i == 1 and p.kind == "rack":
                continue
            if i == 1 and p.kind == "internal" and name == "root":
                continue
            sheet.curves.append((f"overview-{name}{i + 1}", kind, arc(centre, d / 2 * k0, 0.0, 2.0 * math.pi, 361)))
    if p.kind == "internal":
        sheet.curves.append(("overview-root2", "thin", arc(o2, p.df[1] / 2 * k0, 0.0, 2.0 * math.pi, 361)))
    elif p.kind == "rack":                           # its reference line (through o2), tip line and pitch line
        tips = p.addenda[1] if p.addenda is not None else p.addendum
        for name, y, kind in (("reference2", o2[1], "thin"), ("tip2", o2[1] - tips * p.module * k0, "thin"),
                              ("working2", o1[1] + p.d[0] / 2 * k0, "dash")):
            sheet.curves.append((f"overview-{name}", kind, np.array([[x0 - width / 2 * k0, y], [x0 + width / 2 * k0, y]])))
    sheet.points += [("O_1", tuple(o1))] + ([("O_2", tuple(o2))] if p.kind != "rack" else [])
    if p.kind == "rack":
        sheet.tags.append(Tag("overview", "aw", p.a_w, tuple(o1), tuple(o2), ("O1", "ref")))
    else:
        lower, upper = (o1, o2) if p.kind == "external" else (o2, o1)
        sheet.tags.append(Tag("overview", "aw", p.a_w, tuple(lower), tuple(upper), ("O1", "O2")))
    for i, centre in enumerate((o1, o2)):
        if i == 1 and p.kind == "rack":
            continue
        for j, (name, d) in enumerate((("ra", p.da[i]), ("rb", p.db[i]))):
            ang = math.radians((150.0 + 60.0 * j) if i == 0 else (30.0 - 60.0 * j) if p.kind == "external"
                               else (240.0 + 60.0 * j))
            end = centre + np.array([math.sin(ang), math.cos(ang)]) * d / 2 * k0
            sheet.tags.append(Tag("overview", f"{name}{i + 1}", d / 2, tuple(centre), tuple(end),
                                  (f"O{i + 1}", f"{name}{i + 1}")))
