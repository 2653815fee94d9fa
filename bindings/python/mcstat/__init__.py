# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat: statistical hypothesis tests for Monte Carlo estimators.

The tests of Subr & Arvo, "Statistical Hypothesis Testing for Assessing
Monte Carlo Estimators", over libmcstat (C):

=================  ==========================================  ==================================
question           test                                        call
=================  ==========================================  ==================================
unbiased?          one-sample t, mean vs mu                    ``t_test(x, mu=...)``
variance below?    one-sample chi-squared on the variance      ``var_test(x, sigma2=...)``
two agree?         Welch two-sample t                          ``t_test(x, y)``
agree, equal var?  Student's pooled two-sample t               ``t_test(x, y, equal_var=True)``
agree, paired?     paired t                                    ``t_test(x, y, paired=True)``
which varies less  two-sample F                                ``var_test(x, y)``
same distribution  two-sample Kolmogorov-Smirnov (Canner)      ``ks_test(x, y)``
counts fit?        Pearson's chi-squared goodness of fit       ``chisq_gof(x, p)``
more efficient?    ratio of efficiencies, 1/(variance x time)  ``efficiency_test(x, y, tx, ty)``
=================  ==========================================  ==================================

Each returns a `TestResult` (``str()`` prints R's layout plus the paper's
less / equal / greater decision), or a `BatchResult` of arrays for N-D
input (one test per row, e.g. per pixel).  `Moments` accumulates samples
in streams and merges across threads and machines; `batch_means` makes
secondary estimates; `KSCache` shares simulated K-S null distributions
across a battery of tests.  `MomentsArray` keeps one accumulator per
pixel (render farms: push images, ship bytes, merge, test per pixel).
Errors are `ValueError` subclasses (see
`mcstat._errors`).  The reference estimators of the paper's case studies
are in the subpackage `mcstat.estimators`; the ``mcstat`` command and
its case studies are the separate package ``mcstat_app``, which this
package never imports.

Beyond the paper: `binom_test` (R's exact binomial test),
`battery_test` (is a battery's rejection count consistent with its level?)
and `diagnose` (skewness, kurtosis, heavy tails, the batch size the t test
needs) in `mcstat.diagnostics`; the t, chi-squared and F distributions the
tests use (cdf, log cdf, quantile, over arrays) in `mcstat.distributions`.
`compare_efficiency` times two estimators itself (interleaved batches)
and runs `efficiency_test` on their samples and times.

Gradients: `check_gradient` tests a gradient estimator (a differentiable
renderer's) against central finite differences of the same loss with common
random numbers, or against a reference estimator of the same derivative.

Mitsuba 3: `mcstat.mitsuba` checks a Mitsuba BSDF, phase function,
emitter or medium in one line, from its plugin dict or the loaded object
(the extra ``mcstat[mitsuba]``; importing mcstat never imports Mitsuba).

In a test suite: `mcstat.testing` (assertions, one error budget for the
whole suite, escalation instead of reruns, and its pytest plugin, enabled
by ``pytest --mcstat-alpha A``); `Escalation` is its two-stage test.

One-sided alternatives are claims about the first sample in every test:
``ks_test(x, y, alternative="less")`` means x tends to be smaller, which
SciPy's ``ks_2samp`` and R's ``ks.test`` call "greater".

Importing mcstat turns GSL's abort-on-error handler off if, and only if,
no other handler was installed in the process (``gsl_handler_was_default``
says whether it did); libmcstat itself never reaches GSL's handler.
"""
from . import _errors
from ._errors import (
    BufferSizeError,
    CallbackError,
    CorruptDataError,
    HeavyTailError,
    DegenerateDataError,
    InvalidArgumentError,
    McstatError,
    NonFiniteError,
    NumericalError,
    OutOfMemoryError,
    TooBigError,
    TooFewObservationsError,
)
from ._core import (  # noqa: E402  (the extension looks the errors up at import)
    KSCache,
    Moments,
    TestResult,
    __libmcstat_version__,
    __libmcstat_version_number__,
    batch_means,
    Escalation,
    e_bh,
    get_num_threads,
    gsl_handler_was_default,
    ks_test,
    p_adjust,
    p_adjust_work_size,
    set_num_threads,
    t_test,
    var_test,
)
from ._core import chisq_gof  # noqa: E402  (chi-squared goodness of fit)
# is one estimator more efficient (1 / (variance x time)) than another?
from ._core import efficiency_test  # noqa: E402
from ._efficiency import compare_efficiency  # noqa: E402
from ._result import BatchResult

# Per-pixel accumulators (render farms): one Moments per pixel, mergeable and picklable.
from ._core import MomentsArray  # noqa: E402
# A renderer thread's buffered accumulator with its mean and variance checks.
from ._core import Stream  # noqa: E402
# Anytime-valid sequential tests and their driver: render until decided.
from ._core import SequentialTest  # noqa: E402
from ._sequential import run_until_decided  # noqa: E402
# Equivalence (TOST), power and sample size (mcstat._power).
from ._power import (  # noqa: E402
    EquivalenceResult,
    KSPowerResult,
    PowerResult,
    equivalence_test,
    ks_power,
    ks_sample_size,
    power,
)
# Renderer checks: do a BSDF's, an emitter's or a warp's sample, pdf and eval agree?
from ._core import CheckReport, CheckRoute, check_bsdf, check_emitter, check_medium, check_phase, check_warp  # noqa: E402
# Gradient checks: does an AD gradient agree with finite differences (or a reference)?
from ._gradient import GradientParameter, GradientReport, check_gradient  # noqa: E402
# the binomial meta-test and estimator diagnostics
from .diagnostics import Diagnostics, battery_test, binom_test, diagnose  # noqa: E402
# the t, chi-squared and F distributions (cdf, log cdf, quantile)
from . import distributions  # noqa: E402

# The distribution's version, which the build reads from mcstat.h (the same
# header the linked libmcstat reports as __libmcstat_version__).
try:
    from importlib.metadata import PackageNotFoundError as _NotFound, version as _dist_version

    __version__ = _dist_version("mcstat")
except _NotFound:  # imported from a source tree without being installed
    __version__ = __libmcstat_version__

__all__ = [
    "t_test",
    "var_test",
    "ks_test",
    "chisq_gof",
    "efficiency_test",
    "compare_efficiency",
    "KSCache",
    "Moments",
    "batch_means",
    "p_adjust",
    "p_adjust_work_size",
    "e_bh",
    "Escalation",
    "TestResult",
    "BatchResult",
    "MomentsArray",
    "Stream",
    "SequentialTest",
    "run_until_decided",
    "set_num_threads",
    "get_num_threads",
    "binom_test",
    "battery_test",
    "diagnose",
    "Diagnostics",
    "check_bsdf",
    "check_emitter",
    "check_medium",
    "check_phase",
    "check_warp",
    "CheckReport",
    "CheckRoute",
    "check_gradient",
    "GradientReport",
    "GradientParameter",
    "distributions",
    *_errors.__all__,
    # equivalence, power and sample size
    "equivalence_test",
    "EquivalenceResult",
    "power",
    "PowerResult",
    "ks_power",
    "ks_sample_size",
    "KSPowerResult",
]
