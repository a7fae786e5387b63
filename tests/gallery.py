"""What the committed gallery (output/) promises, and how a fresh render is compared with it.

``plans`` computes with :mod:`plans.linalg` and its own DOP853 sums (no BLAS), so the same
scene gives the same bytes on any processor with the same numpy, SciPy and shapely. Another
version of those libraries may still round a last bit differently (a libm's sine, numpy's
pairwise sums). So the gallery tests compare what a user relies on:

- every byte that is not part of a number, exactly: a changed label, a new element, a
  reordered sheet, a missing or added file fails;
- every integer (no point, no exponent), exactly: ids, counts, angles in names;
- every other number within :data:`RTOL` of its magnitude, or within one unit of its last
  written digit (a coordinate written to 0.001 mm that rounds the other way), or, for a
  value that is rounding noise around zero, within :data:`ZERO_REL` of the largest number in
  the file (a velocity of 1e-18 m/s beside velocities of 1 m/s).

RTOL = 1e-7 is far below what a drawing or a check can see (0.01 mm in 100 mm is 1e-4; a
printed value has 4 significant digits) and far above what another rounding of the last bit
does to a value: a closed-form value moves by a few ulps (1e-15); one that comes out of an
iteration moves within that iteration's tolerance (Newton's NEWTON_RTOL = 1e-13 of the size;
the start-up's DOP853 keeps each step's error below rtol = 1e-10 of the value, and two runs
whose steps differ by rounding were measured 4e-9 apart over 21 000 evaluations); the direction of a nearly zero vector (a normal
acceleration of 1e-7 m/s² beside 10 m/s²) moves by the noise of its components over its
length (7e-9 measured). A moved vector (≥ 0.001 mm on the sheet, ≥ 1e-5 relative) fails.
"""

from __future__ import annotations

import re
from pathlib import Path

RTOL = 1e-7
ZERO_REL = 1e-12

_NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")


def _last_digit(s: str) -> float:
    """One unit of the last digit written in the decimal number s."""
    mantissa, _, exponent = s.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 10.0 ** ((int(exponent) if exponent else 0) - decimals)


def difference(old: str, new: str) -> str | None:
    """None when ``new`` means what ``old`` means (see the module), else the first difference."""
    old_text, new_text = _NUMBER.split(old), _NUMBER.split(new)
    if old_text != new_text:
        for i, (a, b) in enumerate(zip(old_text, new_text)):
            if a != b:
                return f"text differs: {a[:60]!r} → {b[:60]!r}"
        return f"{abs(len(old_text) - len(new_text))} more or fewer numbers or text runs"
    old_nums, new_nums = _NUMBER.findall(old), _NUMBER.findall(new)
    scale = max((abs(float(x)) for x in old_nums + new_nums), default=0.0)
    for a, b in zip(old_nums, new_nums):
        if a == b:
            continue
        integer = not any(c in a + b for c in ".eE")
        x, y = float(a), float(b)
        d = abs(x - y)
        if integer or not (d <= RTOL * max(abs(x), abs(y)) or d <= 1.000001 * max(_last_digit(a), _last_digit(b))
                           or d <= ZERO_REL * scale):
            return f"number {a} → {b}"
    return None


def stale(gallery: Path, fresh: dict[str, str]) -> list[str]:
    """The files of ``fresh`` (name → text) that output/ lacks or that differ from it in meaning,
    each with its first difference."""
    out = []
    for name, text in sorted(fresh.items()):
        path = gallery / name
        if not path.is_file():
            out.append(f"{name}: not in output/")
            continue
        why = difference(path.read_text(encoding="utf-8"), text)
        if why:
            out.append(f"{name}: {why}")
    return out
