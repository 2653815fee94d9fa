# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Reference Monte Carlo estimators of the paper's case studies (libmcest).

The estimators that Subr & Arvo test in sections 3.1-3.4, as batch calls
returning NumPy arrays, so that their outputs can be fed to
:func:`mcstat.t_test`, :func:`mcstat.var_test` and :func:`mcstat.ks_test`.

Irradiance from a triangular Lambertian emitter (section 3.1, 3.4)
    :func:`irradiance` (estimators "U", "C", "A", "S" and the three planted
    bugs), :func:`irradiance_exact` (Lambert's formula),
    :class:`IrradiancePlan` (a scene prepared once, with its geometry),
    :func:`paper_scene` (the built-in scene, as keyword arguments).
BRDF sampling (section 3.2)
    :func:`ward`, :func:`ashikhmin_shirley` make a :class:`BRDF`;
    ``brdf.plan(wo)`` a :class:`BRDFPlan` whose ``sample`` draws from the
    model's own sampler (with the true density), ``sample_exact`` from
    f cos / albedo by rejection (with the number of proposals), both with
    Morton keys; :func:`direction_keys`, :func:`direction_square`.
Chi-squared tests of direction samplers
    :func:`direction_cells` cuts the sphere into cells of nearly equal
    probability under a plan's sampler density, with each cell's exact
    probability by cubature; :func:`direction_gof` tests directions against
    them with :func:`mcstat.chisq_gof`; ``plan.sample_bug(n, bug)`` draws
    from the sampler with one of the planted :data:`SAMPLER_BUGS`.
Reflected radiance (section 3.3)
    ``plan.reflected_radiance(method, n)`` under the analytic
    :func:`environment_radiance`; ``plan.reflected_radiance_reference()``.

Randomness is counter-based (Philox4x64-10): estimate (or direction)
number ``first_index + k`` is a pure function of ``(seed, what is drawn,
first_index + k)``.  A run split into calls with consecutive
``first_index`` gives the numbers of one call, and ``threads`` never
changes them.  Different estimators, bugs and samplers draw from
independent streams even with the same seed.  Every batch call releases
the GIL and, above a few thousand values, splits the batch over
``threads`` (default :func:`mcstat.get_num_threads`).

Errors are :class:`EstimatorError` (a :class:`ValueError`) subclasses
carrying libmcest's sentence for the status and its code as ``status``.

Example
-------
>>> import mcstat
>>> from mcstat import estimators as est
>>> scene = est.paper_scene()
>>> a = est.irradiance("A", 20000, **scene, seed=1)
>>> s = est.irradiance("S", 20000, **scene, seed=1)
>>> mcstat.t_test(mcstat.batch_means(a, 100), mcstat.batch_means(s, 100)).decision
'equal'
"""
from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple, Optional

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from ._core import TestResult

__all__ = [
    "irradiance",
    "irradiance_exact",
    "IrradiancePlan",
    "paper_scene",
    "METHODS",
    "BUGS",
    "BRDF",
    "BRDFPlan",
    "ward",
    "ashikhmin_shirley",
    "DirectionSample",
    "direction_keys",
    "direction_square",
    "environment_radiance",
    "RR_METHODS",
    "EstimatorError",
    "InvalidEstimatorArgument",
    "UnsupportedError",
    "TrialLimitError",
    "EstimatorNumericalError",
    "NotReadyError",
    # chi-squared route for direction samplers
    "SAMPLER_BUGS",
    "DirectionCells",
    "direction_cells",
    "direction_gof",
    "default_depth",
]

#: The irradiance estimators of section 3.1.
METHODS = ("U", "C", "A", "S")
#: The planted bugs of section 3.4 (estimator A only).
BUGS = (None, "no_cosine", "barycentric", "no_jacobian")
#: The reflected-radiance estimators of section 3.3.
RR_METHODS = ("sampling", "rejection", "rejection_unbiased")


class DirectionSample(NamedTuple):
    """Directions drawn by :meth:`BRDFPlan.sample` or :meth:`BRDFPlan.sample_exact`.

    Attributes
    ----------
    directions : ndarray of float64, shape (n, 3)
        Unit vectors in the shading frame (normal +z).
    pdf : ndarray of float64, shape (n,), or None
        The density the sampler really draws from, in solid-angle measure
        (``sample``); None for ``sample_exact`` (its density is
        f cos / albedo).
    keys : ndarray of uint64, shape (n,)
        Morton keys (:func:`direction_keys`); ``keys.astype(float)`` is
        ready for :func:`mcstat.ks_test`.
    trials : int
        Proposals drawn: n for ``sample``; for ``sample_exact`` n / trials
        estimates the acceptance rate (:attr:`BRDFPlan.acceptance`).
    """

    directions: np.ndarray
    pdf: Optional[np.ndarray]
    keys: np.ndarray
    trials: int


class EstimatorError(ValueError):
    """Base class of the errors of mcstat.estimators (libmcest's statuses).

    Attributes
    ----------
    status : int
        The libmcest status code (``MCEST_E*``).
    """

    status = -1


class InvalidEstimatorArgument(EstimatorError):
    """An argument outside its domain (MCEST_EINVAL): unknown method, bug or
    model; non-finite or degenerate geometry; a zero normal; negative
    radiance; BRDF parameters out of range; wo.z <= 0; wrong shapes; a
    negative seed."""

    status = 1


class UnsupportedError(EstimatorError):
    """A valid option that does not apply (MCEST_EUNSUPPORTED): a planted
    bug with a method other than "A"."""

    status = 2


class TrialLimitError(EstimatorError):
    """A rejection sampler reached the caller's ``max_trials`` (MCEST_ELIMIT)."""

    status = 3


class EstimatorNumericalError(EstimatorError):
    """A cubature missed its tolerance, or a rejection envelope was exceeded
    (MCEST_ENUMERIC; the latter is never expected)."""

    status = 4


class NotReadyError(EstimatorError):
    """The plan lacks the albedo (MCEST_ENOTREADY): call
    :meth:`BRDFPlan.compute_albedo` or make it with ``albedo=True``."""

    status = 5


_BY_STATUS = {cls.status: cls for cls in (InvalidEstimatorArgument, UnsupportedError, TrialLimitError,
                                          EstimatorNumericalError, NotReadyError)}

from ._estimators import (  # noqa: E402  (the extension looks the errors up here)
    BRDF,
    BRDFPlan,
    IrradiancePlan,
    __libmcest_version__,
    ashikhmin_shirley,
    direction_keys,
    direction_square,
    environment_radiance,
    irradiance,
    irradiance_exact,
    paper_scene,
    ward,
)


# ---- chi-squared route for direction samplers -----------------------------------------

from ._estimators import _brdf_cells, cells_bounds, cells_count, cells_locate  # noqa: E402

#: The planted bugs of the BRDF samplers (``BRDFPlan.sample_bug``); see mcest.h.
SAMPLER_BUGS = ("roughness", "axes_swapped", "phi_half", "jacobian")


class DirectionCells(NamedTuple):
    """Cells of the sphere for chi-squared tests of a direction sampler
    (:func:`direction_cells`).

    Attributes
    ----------
    depth : int
        The k-d tree's depth: ``2**depth`` cells.
    split : ndarray of float64, shape (2**depth - 1,)
        Split values in heap order, alternately across s and t of the
        equal-area square (:func:`direction_square`).
    prob : ndarray of float64, shape (2**depth,)
        Each cell's probability under the plan's sampler density, by
        cubature.
    err : float
        Sum of the cubature's estimated absolute errors.
    """

    depth: int
    split: np.ndarray
    prob: np.ndarray
    err: float

    def counts(self, w) -> np.ndarray:
        """The number of directions w (shape (..., 3)) in each cell."""
        return cells_count(self.split, self.depth, w)

    def locate(self, w) -> np.ndarray:
        """The cell (uint32) of each direction w (shape (..., 3))."""
        return cells_locate(self.split, self.depth, w)

    def bounds(self) -> np.ndarray:
        """Rectangles (s0, s1, t0, t1) of the cells, shape (2**depth, 4)."""
        return cells_bounds(self.split, self.depth)


def default_depth(n: int, min_expected: float = 5.0) -> int:
    """The depth used when none is given: about 2 n^(2/5) cells (Mann and
    Wald's rule of thumb for equiprobable cells), at most n / min_expected
    cells, between 2 and 12 levels."""
    k = 2.0 * max(n, 1) ** 0.4
    k = min(k, max(n, 1) / max(min_expected, 1.0))
    return int(min(12, max(2, round(np.log2(max(k, 1.0))))))


def direction_cells(plan: BRDFPlan, depth: int, *, rel_tol: float = 1e-8, strict: bool = True) -> DirectionCells:
    """Cells of (nearly) equal probability under ``plan``'s sampler density.

    The sphere, mapped to the equal-area square of the Morton keys, is cut
    by a k-d tree of the given depth at medians of a quasi-random pilot of
    the plan's own sampler; each cell's probability under the density
    ``plan.pdf`` (whole sphere, below-horizon directions included) is then
    computed by adaptive cubature to ``rel_tol`` (libmcest's
    ``mcest_brdf_cells``, the GIL released).  Deterministic.

    Raises EstimatorNumericalError when the summed error estimate exceeds
    1e-5 (``strict``); with ``strict=False`` the cells are returned anyway.
    """
    split, prob, err, status = _brdf_cells(plan, depth, rel_tol)
    if status and strict:
        raise EstimatorNumericalError(f"cell probabilities: summed error estimate {err:.3g} exceeds 1e-5")
    return DirectionCells(int(depth), split, prob, float(err))


def direction_gof(directions: npt.ArrayLike, plan: Optional[BRDFPlan] = None, *,
                  cells: Optional[DirectionCells] = None, depth: Optional[int] = None, alpha: float = 0.05,
                  min_expected: float = 5.0) -> TestResult:
    """Chi-squared goodness of fit of directions to a BRDF sampler's density.

    Parameters
    ----------
    directions : array_like, shape (n, 3)
        Directions to test (any non-zero length; below the horizon too).
    plan : BRDFPlan
        Whose sampler density (``plan.pdf``) the directions should follow;
        needed unless ``cells`` is given.
    cells : DirectionCells, optional
        Cells made once by :func:`direction_cells` (reuse them across
        tests: making them costs 0.1-1 s).
    depth : int, optional
        Cells ``2**depth`` when ``cells`` is None; default
        :func:`default_depth` of n.
    alpha, min_expected
        As :func:`mcstat.chisq_gof` (cells are pooled in tree order, so
        neighbours pool).

    Returns
    -------
    mcstat.TestResult
    """
    from . import chisq_gof  # the hypothesis test is libmcstat's

    w = np.asarray(directions, dtype=np.float64)
    if cells is None:
        if plan is None:
            raise InvalidEstimatorArgument("direction_gof needs a plan or cells")
        n = w.size // 3 if w.ndim >= 1 else 0
        cells = direction_cells(plan, default_depth(n, min_expected) if depth is None else depth)
    counts = cells.counts(w)
    return chisq_gof(counts, cells.prob, alpha=alpha, min_expected=min_expected, rescale=True)
