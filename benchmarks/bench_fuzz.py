"""Fuzzing throughput: reimpl against pydrake, on scenes of 5-30 geometries.

Runs the lockstep machine (``conformance.fuzz.campaign.Campaign``) for a fixed seed and
number of examples per initial scene size, ``--repeat`` times, and prints the
median run's:

- examples/s and steps/s (a step is one command sent to both backends);
- the share of wall time spent inside the two backends' own calls
  (``Backend.execute``, ``observe`` and ``reset``);
- the time outside those calls per step, in microseconds;
- the overhead ratio: time outside those calls (Hypothesis's generation and
  shrinking engine plus the harness's own bookkeeping) divided by the time
  inside them. The target is below 0.5;
- how many geometries an example has registered by its end, on average
  (operations add geometry to the initial scene).

``--poses`` measures the posed machine (``fuzz --poses``: shapes, poses,
near touches and the queries) instead; both backends need the ``queries``
feature (``--backend`` chooses the one under test, reimpl by default).

Usage: python benchmarks/bench_fuzz.py [--examples N] [--seed S] [--steps K] [--repeat R]
                                       [--operations-per-step P] [--poses] [--backend B]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar

from hypothesis.stateful import Bundle, RuleBasedStateMachine, rule, run_state_machine_as_test

from conformance.backends.loader import load_backend
from conformance.fuzz.campaign import DEFAULT_STEPS, Campaign, fuzz_settings
from conformance.fuzz.lockstep import LockstepMachine, PosedLockstepMachine
from conformance.protocol import Backend

SIZES = ((5, 10), (10, 20), (20, 30))

#: Typed alias, as in ``conformance.fuzz.campaign`` (Hypothesis releases differ in its annotations).
_run_machine: Callable[..., None] = run_state_machine_as_test


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
    _run_machine(_NoOpMachine, settings=fuzz_settings(max_examples=examples, steps=steps))
    return _NoOpMachine.steps / (time.perf_counter() - start)


class _Sizing(LockstepMachine):
    """Records how many geometries each example registered by its end."""

    final_sizes: ClassVar[list[int]] = []

    def teardown(self) -> None:
        type(self).final_sizes.append(len(self.names["geometries"]))


class _PosedSizing(_Sizing):
    """``_Sizing`` on posed scenes, with ``PosedLockstepMachine``'s operations."""

    OPERATIONS = PosedLockstepMachine.OPERATIONS
    posed = True


@dataclass(frozen=True)
class Row:
    examples_per_s: float
    steps_per_s: float
    in_backends: float
    overhead_us_per_step: float
    overhead_ratio: float
    final_geometries: float
    divergences: int


def measure(
    reimpl: Backend, pydrake: Backend, sizes: tuple[int, int], args: argparse.Namespace
) -> Row:
    """One campaign of ``args.examples`` examples on initial scenes of ``sizes`` geometries."""
    _Sizing.final_sizes = []
    campaign = Campaign(
        backend=lambda: reimpl,
        reference=lambda: pydrake,
        seed=args.seed,
        max_examples=args.examples,
        steps=args.steps,
        machine_base=_PosedSizing if args.poses else _Sizing,
        scene_frames=(2, 5),
        scene_geometries=sizes,
    )
    start = time.perf_counter()
    result = campaign.run()
    wall = time.perf_counter() - start
    stats = result.stats
    inside = stats.backend_seconds
    return Row(
        examples_per_s=stats.examples / wall,
        steps_per_s=stats.steps / wall,
        in_backends=inside / wall,
        overhead_us_per_step=1e6 * (wall - inside) / stats.steps,
        overhead_ratio=(wall - inside) / inside,
        final_geometries=statistics.fmean(_Sizing.final_sizes),
        divergences=len(result.divergences),
    )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--examples", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--steps", type=int, default=DEFAULT_STEPS)
    parser.add_argument("--repeat", type=int, default=3, help="runs per row; the median is shown")
    parser.add_argument(
        "--operations-per-step",
        type=int,
        default=LockstepMachine.operations_per_step,
        help="operations per Hypothesis step (default: the machine's)",
    )
    parser.add_argument("--poses", action="store_true", help="the posed machine (fuzz --poses)")
    parser.add_argument("--backend", default="reimpl", help="the backend under test (reimpl)")
    args = parser.parse_args(argv)
    _Sizing.operations_per_step = args.operations_per_step
    reimpl, pydrake = load_backend(args.backend), load_backend("pydrake")
    print(
        f"{reimpl.name} against pydrake {pydrake.version()}{' (posed)' if args.poses else ''}, "
        f"seed {args.seed}, {args.examples} "
        f"examples of up to {args.steps} Hypothesis steps of {args.operations_per_step} "
        f"operations per run, median of {args.repeat}"
    )
    header = (
        f"{'geometries':>10}  {'examples/s':>10}  {'steps/s':>8}  {'in backends':>11}  "
        f"{'overhead us/step':>16}  {'overhead ratio':>14}  {'at end':>6}  {'divergences':>11}"
    )
    print(header)
    print("-" * len(header))
    for low, high in SIZES:
        runs = [measure(reimpl, pydrake, (low, high), args) for _ in range(args.repeat)]
        row = sorted(runs, key=lambda r: r.overhead_ratio)[len(runs) // 2]
        print(
            f"{f'{low}-{high}':>10}  {row.examples_per_s:>10.1f}  {row.steps_per_s:>8.0f}  "
            f"{row.in_backends:>11.0%}  {row.overhead_us_per_step:>16.0f}  "
            f"{row.overhead_ratio:>14.2f}  {row.final_geometries:>6.1f}  {row.divergences:>11}"
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
