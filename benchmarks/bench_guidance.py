"""What coverage guidance buys a campaign: reimpl's branches and the sequence pairs reached.

Runs the default lockstep campaign (reimpl against pydrake in this process) for
each seed and number of examples in four arms, each measured by the same
``BranchCoverage`` (coverage.py, branch mode, over ``reimpl/geometry`` and
``reimpl/multibody``):

- ``plain``: ``fuzz`` without ``--coverage`` (measured, no feedback);
- ``target``: ``hypothesis.target`` on each example's new reimpl branches;
- ``tour``: the ``sequence_tour`` operation added (``sequence_tour.guided``);
- ``both``: what ``fuzz --coverage`` runs.

For each it prints the branches and lines of reimpl run, the reachable
sequence pairs reached, the steps and the seconds; ``--json FILE`` writes the
rows. The gain of an arm is its count minus ``plain``'s at the same seed and
examples: deterministic for a seed, so a difference is the guidance's, not
noise (the seconds are not).

Usage: python benchmarks/bench_guidance.py [--seeds 1 2] [--examples 300] [--poses] [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

from conformance._backends.loader import load_backend
from conformance._fuzz.branch_coverage import BranchCoverage
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.lockstep import LockstepMachine, PosedLockstepMachine
from conformance._fuzz.operations import issued_ops
from conformance._fuzz.sequence_coverage import expected_pairs
from conformance._fuzz.sequence_tour import guided
from conformance._grammar import GRAMMAR

ARMS = ("plain", "target", "tour", "both")


@dataclass(frozen=True)
class Row:
    arm: str
    seed: int
    examples: int
    steps: int
    branches: int
    covered_branches: int
    covered_lines: int
    pairs: int
    pairs_reached: int
    seconds: float


def run_arm(arm: str, seed: int, examples: int, *, posed: bool) -> Row:
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    base: type[LockstepMachine] = PosedLockstepMachine if posed else LockstepMachine
    shared = reimpl.features() & pydrake.features()
    optional = {"activation", "queries"} - shared
    pairs = expected_pairs(
        op for op in issued_ops(base.OPERATIONS) if GRAMMAR[op].feature not in optional
    )
    campaign = Campaign(
        backend=lambda: reimpl,
        reference=lambda: pydrake,
        seed=seed,
        max_examples=examples,
        machine_base=guided(base) if arm in ("tour", "both") else base,
    )
    coverage = BranchCoverage(feedback=arm in ("target", "both"))
    start = time.perf_counter()
    with coverage.measuring():
        result = campaign.run()
    seconds = time.perf_counter() - start
    report = coverage.report()
    return Row(
        arm,
        seed,
        examples,
        result.stats.steps,
        report.branches,
        report.covered_branches,
        report.covered_lines,
        len(pairs),
        len(pairs) - len(result.stats.sequences.gaps(pairs)),
        round(seconds, 1),
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seeds", type=int, nargs="+", default=[1])
    parser.add_argument("--examples", type=int, default=300)
    parser.add_argument("--poses", action="store_true", help="the posed campaign")
    parser.add_argument("--json", type=Path, help="write the rows")
    args = parser.parse_args()
    rows = []
    print(
        f"{'arm':>7} {'seed':>4} {'examples':>8} {'steps':>6} {'branches':>13} "
        f"{'lines':>6} {'pairs':>9} {'s':>6}"
    )
    for seed in args.seeds:
        for arm in ARMS:
            row = run_arm(arm, seed, args.examples, posed=args.poses)
            rows.append(row)
            print(
                f"{row.arm:>7} {row.seed:>4} {row.examples:>8} {row.steps:>6} "
                f"{row.covered_branches:>6}/{row.branches:<6} {row.covered_lines:>6} "
                f"{row.pairs_reached:>4}/{row.pairs:<4} {row.seconds:>6}",
                flush=True,
            )
    if args.json:
        mode = "poses" if args.poses else "sequences"
        document = {"mode": mode, "rows": [asdict(r) for r in rows]}
        args.json.write_text(json.dumps(document, indent=2) + "\n")


if __name__ == "__main__":
    main()
