"""Fuzzing throughput: reimpl against pydrake, on scenes of 5-30 geometries.

Runs the lockstep machine (``conformance._fuzz.campaign.Campaign``) for a fixed seed and
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
  (operations add geometry to the initial scene);
- each backend's own time per step (its ``execute``, ``observe`` and
  ``reset``), and their ratio reimpl / pydrake, taken in the same run;
- the bound: the steps/s the same run would reach if the backend under test
  took no time at all, ``steps / (wall − its own seconds)``. No work on that
  backend can take the campaign past it; pydrake's calls and Hypothesis's
  engine set it.

``--reimpl-from REV`` also runs the same campaigns with the reimpl of git
revision REV (in a worktree of HEAD whose ``reimpl/`` is REV's, in a
subprocess), and prints the ratio of steps/s, HEAD's over REV's: how much a
change to reimpl alone moved fuzzing throughput, on the same machine, in the
same run. ``--json FILE`` writes the rows.

``--poses`` measures the posed machine (``fuzz --poses``: shapes, poses,
near touches and the queries) instead; both backends need the ``queries``
feature (``--backend`` chooses the one under test, reimpl by default).

Usage: python benchmarks/bench_fuzz.py [--examples N] [--seed S] [--steps K] [--repeat R]
                                       [--operations-per-step P] [--poses] [--backend B]
                                       [--bands 5-10 ...] [--reimpl-from REV] [--json FILE]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any, ClassVar

from hypothesis.stateful import Bundle, RuleBasedStateMachine, rule, run_state_machine_as_test

from conformance._backends.loader import load_backend
from conformance._fuzz.campaign import DEFAULT_STEPS, Campaign, fuzz_settings
from conformance._fuzz.lockstep import LockstepMachine, PosedLockstepMachine
from conformance.protocol import Backend

SIZES = ((5, 10), (10, 20), (20, 30))
ROOT = Path(__file__).resolve().parent.parent

#: Typed alias, as in ``conformance._fuzz.campaign`` (Hypothesis releases differ in its
#: annotations).
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


class _Timed:
    """A backend whose own calls (``execute``, ``observe``, ``reset``) are timed."""

    def __init__(self, backend: Backend) -> None:
        self._backend = backend
        self.seconds = 0.0

    def __getattr__(self, name: str) -> Any:
        return getattr(self._backend, name)

    def _timed(self, method: str, *args: Any) -> Any:
        start = time.perf_counter()
        try:
            return getattr(self._backend, method)(*args)
        finally:
            self.seconds += time.perf_counter() - start

    def execute(self, command: Any) -> Any:
        return self._timed("execute", command)

    def observe(self) -> Any:
        return self._timed("observe")

    def reset(self) -> Any:
        return self._timed("reset")


@dataclass(frozen=True)
class Row:
    band: str
    examples_per_s: float
    steps_per_s: float
    in_backends: float
    overhead_us_per_step: float
    overhead_ratio: float
    final_geometries: float
    divergences: int
    backend_us_per_step: float
    reference_us_per_step: float
    #: Steps/s with the backend under test taking no time: steps / (wall - its seconds).
    bound_steps_per_s: float


def measure(
    reimpl: Backend, pydrake: Backend, sizes: tuple[int, int], args: argparse.Namespace
) -> Row:
    """One campaign of ``args.examples`` examples on initial scenes of ``sizes`` geometries."""
    _Sizing.final_sizes = []
    timed_backend, timed_reference = _Timed(reimpl), _Timed(pydrake)
    campaign = Campaign(
        backend=lambda: timed_backend,
        reference=lambda: timed_reference,
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
        band=f"{sizes[0]}-{sizes[1]}",
        examples_per_s=stats.examples / wall,
        steps_per_s=stats.steps / wall,
        in_backends=inside / wall,
        overhead_us_per_step=1e6 * (wall - inside) / stats.steps,
        overhead_ratio=(wall - inside) / inside,
        final_geometries=statistics.fmean(_Sizing.final_sizes),
        divergences=len(result.divergences),
        backend_us_per_step=1e6 * timed_backend.seconds / stats.steps,
        reference_us_per_step=1e6 * timed_reference.seconds / stats.steps,
        bound_steps_per_s=stats.steps / (wall - timed_backend.seconds),
    )


def _band(text: str) -> tuple[int, int]:
    low, _, high = text.partition("-")
    return int(low), int(high)


def other_reimpl(revision: str, argv: list[str]) -> list[dict[str, Any]]:
    """This script's rows with the reimpl of ``revision`` and HEAD's harness, in a subprocess."""
    with tempfile.TemporaryDirectory(prefix="bench-fuzz-") as scratch:
        tree, rows = Path(scratch) / "tree", Path(scratch) / "rows.json"
        git = ["git", "-C", str(ROOT)]
        subprocess.run([*git, "worktree", "add", "--detach", "-q", str(tree), "HEAD"], check=True)
        try:
            subprocess.run(
                ["git", "-C", str(tree), "checkout", "-q", revision, "--", "reimpl"], check=True
            )
            env = {**os.environ, "PYTHONPATH": str(tree)}
            script = tree / "benchmarks" / "bench_fuzz.py"
            subprocess.run(
                [sys.executable, str(script), *argv, "--json", str(rows)], env=env, check=True
            )
            loaded: list[dict[str, Any]] = json.loads(rows.read_text())["rows"]
            return loaded
        finally:
            subprocess.run([*git, "worktree", "remove", "--force", str(tree)], check=False)


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
    parser.add_argument(
        "--bands",
        nargs="+",
        type=_band,
        default=list(SIZES),
        metavar="LOW-HIGH",
        help="initial scene sizes, one row each (default: 5-10 10-20 20-30)",
    )
    parser.add_argument(
        "--reimpl-from",
        metavar="REV",
        help="also run with the reimpl of git revision REV and print the steps/s ratio",
    )
    parser.add_argument("--json", type=Path, help="write the rows to this file")
    raw = sys.argv[1:] if argv is None else argv
    args = parser.parse_args(raw)
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
        f"{'us/step ' + reimpl.name:>16}  {'us/step pydrake':>15}  {'ratio':>5}  "
        f"{'overhead us/step':>16}  {'overhead ratio':>14}  {'at end':>6}  {'divergences':>11}"
        f"  {'bound':>7}"
    )
    print(header)
    print("-" * len(header))
    rows: list[Row] = []
    for low, high in args.bands:
        runs = [measure(reimpl, pydrake, (low, high), args) for _ in range(args.repeat)]
        row = sorted(runs, key=lambda r: r.steps_per_s)[len(runs) // 2]
        rows.append(row)
        print(
            f"{row.band:>10}  {row.examples_per_s:>10.1f}  {row.steps_per_s:>8.0f}  "
            f"{row.in_backends:>11.0%}  {row.backend_us_per_step:>16.0f}  "
            f"{row.reference_us_per_step:>15.0f}  "
            f"{row.backend_us_per_step / row.reference_us_per_step:>5.2f}  "
            f"{row.overhead_us_per_step:>16.0f}  "
            f"{row.overhead_ratio:>14.2f}  {row.final_geometries:>6.1f}  {row.divergences:>11}"
            f"  {row.bound_steps_per_s:>7.0f}"
        )
        sys.stdout.flush()
    floor = hypothesis_floor(args.examples, args.steps)
    print(
        f"Hypothesis alone (a no-op machine): {floor:.0f} steps/s, "
        f"{1000 / floor:.2f} ms per step before any backend call"
    )
    print(f"bound: steps/s if {reimpl.name} took no time at all (pydrake and Hypothesis only)")
    if args.json is not None:
        args.json.write_text(
            json.dumps(
                {
                    "pydrake": pydrake.version(),
                    "seed": args.seed,
                    "examples": args.examples,
                    "steps": args.steps,
                    "repeat": args.repeat,
                    "hypothesis_steps_per_s": floor,
                    "rows": [asdict(r) for r in rows],
                },
                indent=1,
            )
            + "\n"
        )
    if args.reimpl_from:
        passed = _without_option(_without_option(raw, "--reimpl-from"), "--json")
        print(f"\nThe same campaigns with the reimpl of {args.reimpl_from} (HEAD's harness):")
        sys.stdout.flush()
        theirs = other_reimpl(args.reimpl_from, passed)
        theirs_label = f"steps/s {args.reimpl_from}"
        print(f"\n{'geometries':>10}  {'steps/s HEAD':>12}  {theirs_label:>16}  ratio")
        for ours, other in zip(rows, theirs, strict=True):
            print(
                f"{ours.band:>10}  {ours.steps_per_s:>12.0f}  {other['steps_per_s']:>16.0f}  "
                f"{ours.steps_per_s / other['steps_per_s']:.2f}"
            )
    return 0


def _without_option(argv: list[str], option: str) -> list[str]:
    """``argv`` without ``option`` and its value (either ``--opt V`` or ``--opt=V``)."""
    kept: list[str] = []
    skip = False
    for item in argv:
        if skip:
            skip = False
        elif item == option:
            skip = True
        elif not item.startswith(option + "="):
            kept.append(item)
    return kept


if __name__ == "__main__":
    sys.exit(main())
