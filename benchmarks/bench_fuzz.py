"""Fuzzing throughput: reimpl against pydrake, on scenes of 5-30 geometries.

Runs the lockstep machine (``conformance.fuzz.Campaign``) for a fixed seed and
number of examples per scene size, and prints:

- examples/s and steps/s;
- the share of wall time spent inside the two backends' own calls
  (``Backend.execute`` and ``Backend.observe``);
- the overhead ratio: time outside those calls (Hypothesis's generation and
  shrinking engine plus the harness's own bookkeeping) divided by the time
  inside them. The target is below 0.5.

Usage: python benchmarks/bench_fuzz.py [--examples N] [--seed S] [--steps K]
"""

from __future__ import annotations

import argparse
import sys
import time

from hypothesis.stateful import Bundle, RuleBasedStateMachine, rule, run_state_machine_as_test

from conformance.backends import load_backend
from conformance.fuzz import DEFAULT_STEPS, Campaign, fuzz_settings

SIZES = ((5, 10), (10, 20), (20, 30))


class _NoOpMachine(RuleBasedStateMachine):
    """Two trivial rules and a bundle: what a Hypothesis step costs with no backend."""

    things = Bundle("things")
    steps = 0

    @rule(target=things)
    def make(self) -> str:
        type(self).steps += 1
        return "x"

    @rule(thing=things)
    def use(self, thing: str) -> None:
        type(self).steps += 1


def hypothesis_floor(examples: int, steps: int) -> float:
    """Steps/s of ``_NoOpMachine`` under the campaign's settings."""
    _NoOpMachine.steps = 0
    start = time.perf_counter()
    run_state_machine_as_test(
        _NoOpMachine, settings=fuzz_settings(max_examples=examples, steps=steps)
    )
    return _NoOpMachine.steps / (time.perf_counter() - start)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--examples", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--steps", type=int, default=DEFAULT_STEPS)
    args = parser.parse_args(argv)
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    print(
        f"reimpl against pydrake {pydrake.version()}, seed {args.seed}, "
        f"{args.examples} examples of up to {args.steps} steps per row"
    )
    header = (
        f"{'geometries':>10}  {'examples/s':>10}  {'steps/s':>8}  {'in backends':>11}  "
        f"{'overhead ratio':>14}  {'divergences':>11}"
    )
    print(header)
    print("-" * len(header))
    for low, high in SIZES:
        campaign = Campaign(
            backend=lambda: reimpl,
            reference=lambda: pydrake,
            seed=args.seed,
            max_examples=args.examples,
            steps=args.steps,
            scene_frames=(2, 5),
            scene_geometries=(low, high),
        )
        start = time.perf_counter()
        result = campaign.run()
        wall = time.perf_counter() - start
        stats = result.stats
        inside = stats.backend_seconds
        print(
            f"{f'{low}-{high}':>10}  {stats.examples / wall:>10.1f}  {stats.steps / wall:>8.0f}  "
            f"{inside / wall:>11.0%}  {(wall - inside) / inside:>14.2f}  "
            f"{len(result.divergences):>11}"
        )
        sys.stdout.flush()
    floor = hypothesis_floor(args.examples, args.steps)
    print(
        f"Hypothesis alone (a no-op machine): {floor:.0f} steps/s, "
        f"{1000 / floor:.2f} ms per step before any backend call"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
