from pathlib import Path

import pytest

EXAMPLES = sorted((Path(__file__).resolve().parent.parent / "plans" / "examples").glob("*.toml"))
#: The example the bad-input and contract tests edit: the central crank-slider.
CRANK_SLIDER = next(p for p in EXAMPLES if p.stem == "crank_slider_central")


@pytest.fixture(scope="session")
def rendered(tmp_path_factory):
    """Every example rendered once into a temporary folder."""
    from plans.cli import main

    out = tmp_path_factory.mktemp("render")
    assert main(["render", *map(str, EXAMPLES), "-o", str(out), "-q"]) == 0
    return out
