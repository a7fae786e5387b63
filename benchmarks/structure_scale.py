"""Timing of the structural search on long chains of four-bars (prints a table).

    python benchmarks/structure_scale.py                     # 50, 100, 200 links
    python benchmarks/structure_scale.py --links 40 60 84 --timeout 120
    python benchmarks/structure_scale.py --baseline old_structure.py   # time another structure.py

Each case runs in a child process with a time limit (the old exhaustive search takes minutes
to refuse a long chain); a case over the limit prints as "> limit". The scenes come from
``tests/test_structure_scale.py``: a crank and parallelogram RRR dyads, listed in order or
reversed, valid or with one pin moved so the chain does not split into Assur groups (at the
crank: "refused", or halfway along: "refused/2"); "triads" is a crank and a chain of class III
groups. "model" is parse_scene + build_mechanism,
"structure" analyse_structure alone.
"""

from __future__ import annotations

import argparse
import importlib.util
import multiprocessing as mp
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))

#: (label, defect, where the chain breaks: 0 at the crank, 1 halfway; order of [links])
CASES = [("valid", None, 0, "forward"), ("valid", None, 0, "reverse"),
         ("refused", "moved", 0, "forward"), ("refused", "moved", 0, "reverse"),
         ("refused/2", "moved", 1, "forward"), ("refused/2", "moved", 1, "reverse"),
         ("triads", "triad", 0, "forward"), ("triads", "triad", 0, "reverse")]


def _analyse(baseline: str | None):
    if baseline is None:
        from plans.structure import analyse_structure
        return analyse_structure
    spec = importlib.util.spec_from_file_location("plans._structure_baseline", baseline)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module.analyse_structure


def _run(queue, links: int, defect: str | None, half: int, order: str, baseline: str | None) -> None:
    from test_structure_scale import chain_scene, group_chain_scene
    from plans.errors import StructureError
    from plans.model import build_mechanism
    from plans.scene import parse_scene

    analyse_structure = _analyse(baseline)
    stages = (links - 1) // 2
    start = time.perf_counter()
    if defect == "triad":       # class III groups: a crank and (links - 1) / 4 triads
        data = group_chain_scene((links - 1) // 4, "triad", order=order)
    else:
        data = chain_scene(stages, order=order, defect=defect, at=max(1, stages // 2) if half else 1)
    mech = build_mechanism(parse_scene(data))
    built = time.perf_counter() - start
    start = time.perf_counter()
    try:
        st = analyse_structure(mech)
        outcome = f"{len(st.groups)} groups"
    except StructureError:
        outcome = "StructureError"
    queue.put((built, time.perf_counter() - start, outcome))


def measure(links: int, defect: str | None, half: int, order: str, baseline: str | None, timeout: float):
    queue = mp.get_context("fork").Queue()
    proc = mp.get_context("fork").Process(target=_run, args=(queue, links, defect, half, order, baseline))
    proc.start()
    proc.join(timeout)
    if proc.is_alive():
        proc.terminate()
        proc.join()
        return None, None, "over the limit"
    return queue.get() if not queue.empty() else (None, None, f"exit {proc.exitcode}")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--links", type=int, nargs="+", default=[51, 101, 199],
                        help="moving links (odd: a crank and dyads); default 51 101 199")
    parser.add_argument("--timeout", type=float, default=60.0, help="limit per case, s (default 60)")
    parser.add_argument("--baseline", help="time this structure.py instead of plans/structure.py")
    args = parser.parse_args(argv)
    print(f"structural search: {args.baseline or 'plans/structure.py'}")
    print(f"{'moving links':>12} {'chain':>10} {'order':>8} {'model, s':>9} {'structure, s':>13}  outcome")
    for links in args.links:
        for kind, defect, half, order in CASES:
            built, seconds, outcome = measure(links, defect, half, order, args.baseline, args.timeout)
            model = "" if built is None else f"{built:.3f}"
            shown = f"> {args.timeout:g}" if seconds is None else f"{seconds:.3f}"
            print(f"{links:>12} {kind:>10} {order:>8} {model:>9} {shown:>13}  {outcome}", flush=True)


if __name__ == "__main__":
    main()
