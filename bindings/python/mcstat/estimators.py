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

from typing import NamedTuple, Optional

import numpy as np

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
