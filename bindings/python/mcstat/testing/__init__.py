# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat in a test suite: statistical assertions under one error budget.

A renderer's CI runs hundreds of statistical tests; at 0.01 each, 200
correct tests fail some run in most runs, and the usual cures (reruns,
wider tolerances, disabled tests) quietly remove the power to find bugs.
Here:

- **assertions** that raise `StatisticalAssertionError` (an
  AssertionError) with mcstat's report, the alpha spent, the seed and how
  to reproduce: `assert_bsdf_consistent`, `assert_emitter_consistent`,
  `assert_warp_consistent`, `assert_phase_consistent`,
  `assert_medium_consistent` (the renderer kit), `assert_unbiased`,
  `assert_same_distribution`, `assert_images_equivalent`;
- **one budget for the suite** (`Suite`, `scope`): the run's
  false-failure probability is the budget, each test's share fixed before
  any test runs;
- **escalation instead of reruns** (`mcstat.Escalation`): a check whose
  first p-value is suspicious but not decisive continues on more, fresh
  samples and decides on both, at the same level;
- **seeds** that are a pure function of the master seed, the test's name
  and the check's index (`check_seed`), so a failure reruns exactly.

Under pytest the plugin (``mcstat.testing.pytest_plugin``, installed with
the package) does the bookkeeping once a run opts in::

    # test_bsdf.py                       # run: pytest --mcstat-alpha 1e-3
    import pytest
    from mcstat.testing import assert_bsdf_consistent

    @pytest.mark.mcstat
    @pytest.mark.parametrize("theta", [10, 45, 80])
    def test_ggx(theta):
        wi = direction(theta)
        assert_bsdf_consistent(bsdf.sample, bsdf.eval, bsdf.pdf, wi, n=100_000)

Elsewhere, ``with mcstat.testing.scope("name", alpha=1e-3): ...`` or
``alpha=`` on the call.  This package never imports the application.
"""
from ._assertions import (
    StatisticalAssertionError,
    assert_bsdf_consistent,
    assert_emitter_consistent,
    assert_images_equivalent,
    assert_medium_consistent,
    assert_phase_consistent,
    assert_same_distribution,
    assert_unbiased,
    assert_warp_consistent,
)
from ._budget import BudgetError, CheckRecord, Scope, Suite, current_scope, scope
from ._seeds import check_seed, stage2_seed

__all__ = [
    "StatisticalAssertionError",
    "BudgetError",
    "assert_bsdf_consistent",
    "assert_emitter_consistent",
    "assert_warp_consistent",
    "assert_phase_consistent",
    "assert_medium_consistent",
    "assert_unbiased",
    "assert_same_distribution",
    "assert_images_equivalent",
    "Suite",
    "Scope",
    "CheckRecord",
    "scope",
    "current_scope",
    "check_seed",
    "stage2_seed",
]
