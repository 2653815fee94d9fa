# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Exceptions of mcstat: one per libmcstat status code.

Every one is a :class:`ValueError` (bad data and bad arguments are value
problems) and has the C status code as ``status``.  The message says what
was wrong in Python's terms, naming the argument (``"alpha must be in (0,
1), got 5"``); for bad data it starts with the C library's sentence for the
status (``"the data contain NaN or infinite values"``).  Errors of row-wise tests also
carry ``rows``: the indices (into the output's shape) of the rows that
failed.  Arguments of the wrong type (``None`` for ``x``, a number for
``alternative``) raise :class:`TypeError`, as elsewhere in Python.
"""
from __future__ import annotations

from typing import Optional

import numpy as np

__all__ = [
    "McstatError",
    "InvalidArgumentError",
    "TooFewObservationsError",
    "NonFiniteError",
    "DegenerateDataError",
    "OutOfMemoryError",
    "NumericalError",
    "BufferSizeError",
    "CorruptDataError",
    "TooBigError",
    "CallbackError",
    "HeavyTailError",
]


class McstatError(ValueError):
    """Base class of mcstat's errors.

    Attributes
    ----------
    status : int
        The libmcstat status code (``MCSTAT_E*``).
    rows : numpy.ndarray or None
        For row-wise tests: indices of the failed rows, shape ``(k, ndim)``
        for k failed rows of an output with ``ndim`` dimensions (``(k,)``
        when the output is 1-D).  None otherwise.
    status_text : str
        libmcstat's sentence for `status` (``mcstat_strerror``); the message
        itself says what was wrong in Python's words.
    """

    status = -1

    def __init__(self, *args: object, rows: Optional[np.ndarray] = None) -> None:
        super().__init__(*args)
        self.rows = rows

    @property
    def status_text(self) -> str:
        from ._core import strerror

        return strerror(self.status)


class InvalidArgumentError(McstatError):
    """An argument outside its domain (MCSTAT_EINVAL): alpha outside (0, 1),
    an unknown alternative or nan_policy, a non-positive sigma2 or ratio,
    an axis out of range, mismatched shapes, scalar input."""

    status = 1


class TooFewObservationsError(McstatError):
    """Fewer than 2 observations in a sample (MCSTAT_ETOOFEW), after NaNs
    were omitted with ``nan_policy="omit"``; empty input."""

    status = 2


class NonFiniteError(McstatError):
    """NaN or infinite values in the data (MCSTAT_ENONFINITE).  With
    ``nan_policy="omit"`` only infinities raise it."""

    status = 3


class DegenerateDataError(McstatError):
    """A sample is constant to within rounding (MCSTAT_EDEGENERATE): its
    standard deviation is zero or below 10 eps ``|mean|``.  Welch's test needs
    spread in only one of its samples."""

    status = 4


class OutOfMemoryError(McstatError, MemoryError):
    """Out of memory (MCSTAT_ENOMEM); also a :class:`MemoryError`."""

    status = 5


class NumericalError(McstatError):
    """A numerical method failed to converge (MCSTAT_ENUMERIC; not expected)."""

    status = 6


class BufferSizeError(McstatError):
    """An output buffer was too small (MCSTAT_EBUFSIZE; internal, not expected)."""

    status = 7


class CorruptDataError(McstatError):
    """Serialized bytes are truncated, corrupt or of an unknown format
    version (MCSTAT_ECORRUPT), from :meth:`Moments.from_bytes`."""

    status = 8


class TooBigError(McstatError):
    """The sizes are too large for the requested method (MCSTAT_ETOOBIG):
    an exact K-S p-value whose lattice would take too long (more than
    ``(min(nx, ny) + 1) * (nx + ny + 1) = 2e11`` cells), or ``nx * ny``
    beyond 2**62.  Choose another method (``"simulate"`` or, unweighted,
    ``"asymptotic"``).  Also raised when adding or merging would take an
    accumulator's count past 2**64 - 1 (the accumulator is unchanged)."""

    status = 9


class CallbackError(McstatError):
    """A callable handed to a renderer check (:func:`check_bsdf`,
    :func:`check_emitter`, :func:`check_warp`) returned something the check
    cannot use (MCSTAT_ECALLBACK): the wrong shape or type, NaN, an
    infinity, a negative density or weight, or a point off the domain (a
    direction not of unit length within 1e-4).  The message names the
    callable, the point and the value.  An exception the callable raises
    itself propagates unchanged instead."""

    status = 10


class HeavyTailError(McstatError):
    """The data's tails were too heavy for a decision within the samples
    seen (MCSTAT_EHEAVYTAIL): :meth:`SequentialTest.finish` when the
    kurtosis gate never opened (infinite variance, or far more samples
    needed).  The message gives the n the kurtosis asks for."""

    status = 11


_BY_STATUS = {
    cls.status: cls
    for cls in (
        InvalidArgumentError,
        TooFewObservationsError,
        NonFiniteError,
        DegenerateDataError,
        OutOfMemoryError,
        NumericalError,
        BufferSizeError,
        CorruptDataError,
        TooBigError,
        CallbackError,
        HeavyTailError,
    )
}
