"""Fuzz shards: a long campaign split into seed ranges, run by pytest-xdist.

Run with ``pytest -m fuzz -n auto``. The environment picks the shard:

- ``CONFORMANCE_FUZZ_SEEDS``: seeds as ``first-last`` (default ``0-3``);
- ``CONFORMANCE_FUZZ_EXAMPLES``: examples per seed (default 50);
- ``CONFORMANCE_FUZZ_DB``: a Hypothesis example database directory to share
  (failures found by one job are replayed first by the others);
- ``CONFORMANCE_FUZZ_OUT``: where findings are written (default: a temporary
  directory; set it to ``scenarios/regressions`` to keep them);
- ``CONFORMANCE_FUZZ_COVERAGE=1``: run guided, as ``fuzz --coverage`` does
  (``sequence_tour.guided``, and ``hypothesis.target`` on new reimpl branches,
  ``branch_coverage``); the database then also keeps each job's best targeted
  examples (Hypothesis's pareto front), which the other jobs replay first.

Each seed is one test, so xdist spreads seeds over workers and a CI matrix
spreads seed ranges over jobs (see docs/fuzzing.md).
"""

from __future__ import annotations

import os
from contextlib import nullcontext
from pathlib import Path

import pytest

from conformance._backends.loader import load_backend
from conformance._fuzz.branch_coverage import BranchCoverage
from conformance._fuzz.campaign import Campaign
from conformance._fuzz.lockstep import LockstepMachine
from conformance._fuzz.regression import write_regression
from conformance._fuzz.sequence_tour import guided


def _seeds() -> range:
    first, _, last = os.environ.get("CONFORMANCE_FUZZ_SEEDS", "0-3").partition("-")
    return range(int(first), int(last or first) + 1)


@pytest.mark.fuzz
@pytest.mark.parametrize("seed", _seeds())
def test_reimpl_matches_pydrake_on_a_fuzz_shard(seed: int, tmp_path: Path) -> None:
    database = os.environ.get("CONFORMANCE_FUZZ_DB")
    reimpl, pydrake = load_backend("reimpl"), load_backend("pydrake")
    steer = os.environ.get("CONFORMANCE_FUZZ_COVERAGE") == "1"
    campaign = Campaign(
        backend=lambda: reimpl,
        reference=lambda: pydrake,
        seed=seed,
        max_examples=int(os.environ.get("CONFORMANCE_FUZZ_EXAMPLES", "50")),
        database=Path(database) if database else None,
        machine_base=guided(LockstepMachine) if steer else LockstepMachine,
    )
    with BranchCoverage().measuring() if steer else nullcontext():
        result = campaign.run()
    assert result.stats.steps > 0
    for divergence in result.divergences:
        out = Path(os.environ.get("CONFORMANCE_FUZZ_OUT", str(tmp_path)))
        path = write_regression(
            divergence,
            out,
            backend="reimpl",
            reference="pydrake",
            reference_version=pydrake.version(),
            seed=seed,
        )
        pytest.fail(f"seed {seed}: {divergence}\nwritten: {path}")
