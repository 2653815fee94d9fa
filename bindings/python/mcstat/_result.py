# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""BatchResult: the fields of row-wise tests as arrays."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, Iterator, NamedTuple, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._errors import _BY_STATUS, McstatError

class ConfidenceInterval(NamedTuple):
    """A confidence interval, ``(low, high)``, as SciPy's (returned by
    ``TestResult.confidence_interval``)."""

    low: float
    high: float

if TYPE_CHECKING:
    from ._core import TestResult

_METHODS = {
    "t_1": "One Sample t-test",
    "t_2": "Welch Two Sample t-test",
    "t_2_pooled": "Two Sample t-test",
    "t_paired": "Paired t-test",
    "var_1": "One Sample Chi-squared test on variance",
    "var_2": "F test to compare two variances",
}
_ALTERNATIVES = ("two-sided", "less", "greater")
_DECISIONS = np.array(["less", "equal", "greater"])
_SHOW_ROWS = 5  # failed rows named in an error message


class _Lazy:
    """A field computed on first access (see `_Fields`)."""

    __slots__ = ("fn",)

    def __init__(self, fn: Any) -> None:
        self.fn = fn


class _Fields(dict):  # type: ignore[type-arg]
    """The fields of a BatchResult: a value still a `_Lazy` is computed when
    first read (the per-pixel kernel writes flat arrays; the paired fields
    such as ``conf_int`` are stacked only if someone asks)."""

    def __getitem__(self, key: str) -> Any:
        v = dict.__getitem__(self, key)
        if isinstance(v, _Lazy):
            v = v.fn()
            dict.__setitem__(self, key, v)
        return v

    def items(self) -> Any:
        return [(k, self[k]) for k in self.keys()]


class BatchResult:
    """The outcome of one test per row (2-D or N-D input with ``axis``).

    Each field of :class:`TestResult` is an array over the rows: shape
    ``s`` = the input's shape without ``axis``, or ``s + (2,)`` for pairs
    (``conf_int``, ``critical_values``, Welch's ``estimate``, the F test's
    ``df``, two-sample ``nobs``).

    Attributes
    ----------
    statistic, pvalue, std_error : ndarray of float64
    df, conf_int, estimate, critical_values : ndarray of float64
    reject : ndarray of bool
    decision : ndarray of str
        ``"less"``, ``"equal"``, ``"greater"``; ``""`` for failed rows.
    decision_code : ndarray of int8
        -1, 0, +1 (0 for failed rows; see `ok`).
    status : ndarray of int8
        libmcstat's status per row (0 = success); with ``on_error="nan"``
        failed rows have NaN fields and ``reject`` False.
    ok : ndarray of bool
        ``status == 0``.
    nobs : ndarray of int64
        Sizes used per row (after omitted NaNs); 0 for failed rows.
    null_value, alpha : float
    alternative, method : str
    pvalue_se : ndarray of float64
        Zeros (these p-values are exact).

    Notes
    -----
    ``result[i]`` (or ``result[i, j]`` for higher dimensions) is the
    :class:`TestResult` of one row, whose ``str()`` is the R-style block.
    As with NumPy arrays, ``len(result)`` is the length of the first output
    dimension, iterating goes along it, and fewer indices than dimensions
    give a `BatchResult` of the rest: for 1-D output ``list(result)`` is
    the TestResults of the rows; for an image ``(H, W)`` it is H
    BatchResults of shape ``(W,)``, and ``result.ravel()`` iterates over
    every pixel in C order.  A failed row raises its error when indexed
    or reached (with ``on_error="nan"``, select rows with `ok` first).
    """

    def __init__(self, kind: str, fields: Dict[str, np.ndarray], alternative: int, alpha: float,
                 null_value: float, intervals: bool) -> None:
        self._kind = kind
        self._f = fields if isinstance(fields, _Fields) else _Fields(fields)
        self.alternative: str = _ALTERNATIVES[alternative]
        self.alpha: float = alpha
        self.null_value: float = null_value
        self.method: str = _METHODS[kind]
        self.intervals: bool = intervals
        self._decision: Optional[npt.NDArray[np.str_]] = None

    # fields (arrays over the rows; see the class docstring for the shapes)
    @property
    def statistic(self) -> "npt.NDArray[np.float64]":
        return self._f["statistic"]

    @property
    def df(self) -> "npt.NDArray[np.float64]":
        return self._f["df"]

    @property
    def pvalue(self) -> "npt.NDArray[np.float64]":
        return self._f["pvalue"]

    @property
    def conf_int(self) -> "npt.NDArray[np.float64]":
        return self._f["conf_int"]

    @property
    def estimate(self) -> "npt.NDArray[np.float64]":
        return self._f["estimate"]

    @property
    def critical_values(self) -> "npt.NDArray[np.float64]":
        return self._f["critical_values"]

    @property
    def std_error(self) -> "npt.NDArray[np.float64]":
        return self._f["std_error"]

    @property
    def reject(self) -> "npt.NDArray[np.bool_]":
        return self._f["reject"]

    @property
    def decision_code(self) -> "npt.NDArray[np.int8]":
        return self._f["decision_code"]

    @property
    def status(self) -> "npt.NDArray[np.int8]":
        return self._f["status"]

    @property
    def nobs(self) -> "npt.NDArray[np.int64]":
        return self._f["nobs"]

    @property
    def ok(self) -> "npt.NDArray[np.bool_]":
        return self._f["status"] == 0

    @property
    def pvalue_se(self) -> "npt.NDArray[np.float64]":
        return np.zeros(self.shape)

    @property
    def decision(self) -> "npt.NDArray[np.str_]":
        if self._decision is None:
            d = _DECISIONS[self._f["decision_code"].astype(np.intp) + 1]
            d[~self.ok] = ""
            self._decision = d
        return self._decision

    @property
    def shape(self) -> Tuple[int, ...]:
        return self._f["statistic"].shape

    def __len__(self) -> int:
        return self.shape[0] if self.shape else 1

    def _sub(self, fields: Dict[str, np.ndarray]) -> "BatchResult":
        out = BatchResult.__new__(BatchResult)
        out.__dict__.update(self.__dict__)
        out._f = fields
        out._decision = None
        return out

    def ravel(self) -> "BatchResult":
        """The same rows as a 1-D BatchResult (C order): ``for r in
        b.ravel()`` visits every row's TestResult."""
        nd = len(self.shape)
        return self._sub({k: v.reshape((-1,) + v.shape[nd:]) for k, v in self._f.items()})

    def __iter__(self) -> Iterator[Any]:
        if not self.shape:
            yield self[()]
            return
        for i in range(self.shape[0]):
            yield self[i]

    # a TestResult for a full index, a sub-batch for a partial one (as NumPy)
    def __getitem__(self, index: Union[int, Tuple[int, ...]]) -> Any:
        from ._core import _result_from_fields  # the struct is rebuilt in C++

        idx = index if isinstance(index, tuple) else (index,)
        if not all(isinstance(i, (int, np.integer)) for i in idx) or len(idx) > len(self.shape):
            raise IndexError("index rows with at most as many integers as the result has dimensions "
                             f"({len(self.shape)}), got {index!r}")
        if len(idx) < len(self.shape):
            # a sub-batch, as NumPy's a[i] of an N-D array
            for ax, i in enumerate(idx):
                if not -self.shape[ax] <= i < self.shape[ax]:
                    raise IndexError(f"index {i} is out of bounds for axis {ax} with size {self.shape[ax]}")
            return self._sub({k: v[idx] for k, v in self._f.items()})
        for ax, i in enumerate(idx):
            if not -self.shape[ax] <= i < self.shape[ax]:
                raise IndexError(f"index {i} is out of bounds for axis {ax} with size {self.shape[ax]}")
        if not self._f["status"][idx] == 0:
            raise _BY_STATUS.get(int(self._f["status"][idx]), McstatError)(
                f"row {index} failed: status {int(self._f['status'][idx])}")
        return _result_from_fields(self._kind, self.alternative, self.alpha, self.null_value,
                                   {k: v[idx] for k, v in self._f.items()})

    def __repr__(self) -> str:
        return (f"<BatchResult {self.method}: {self.shape} rows, {int(self.reject.sum())} rejected at "
                f"alpha={self.alpha:g} ({self.alternative}), {int((~self.ok).sum())} failed>")

    def __str__(self) -> str:
        n = self.statistic.size
        dc = self._f["decision_code"][self.ok]
        return (f"{self.method}, one test per row: {self.shape} rows\n"
                f"alternative: {self.alternative}, null value {self.null_value:g}, alpha = {self.alpha:g}\n"
                f"decisions: {int((dc < 0).sum())} less, {int((dc == 0).sum())} equal, "
                f"{int((dc > 0).sum())} greater; {n - dc.size} failed\n")


def _describe_rows(bad: np.ndarray, shape: Tuple[int, ...]) -> Tuple[np.ndarray, str]:
    flat = np.flatnonzero(bad)
    if len(shape) == 1:
        rows = flat
        shown = ", ".join(str(int(i)) for i in flat[:_SHOW_ROWS])
    else:
        rows = np.stack(np.unravel_index(flat, shape), axis=-1)
        shown = ", ".join(str(tuple(int(v) for v in r)) for r in rows[:_SHOW_ROWS])
    more = f" and {flat.size - _SHOW_ROWS} more" if flat.size > _SHOW_ROWS else ""
    return rows, shown + more


def _raise_failed(status: np.ndarray, errors_as_nan: bool, nan_rows: Any) -> None:
    # nan_rows (nan_policy="propagate"): rows whose data hold NaN; their NaN
    # fields are the answer, not an error
    bad = status != 0
    if nan_rows is not None:
        bad = bad & ~np.asarray(nan_rows, dtype=bool)
    if not errors_as_nan and status.size and bad.any():
        first = int(status.flat[np.argmax(bad)])
        cls = _BY_STATUS.get(first, McstatError)
        from ._core import _status_text

        rows, shown = _describe_rows(bad, status.shape)
        nbad = int(bad.sum())
        others = int((bad & (status != first)).sum())
        extra = f"; {others} of them failed for another reason" if others else ""
        raise cls(f"{_status_text(first)}: {nbad} of {status.size} rows failed (rows {shown}){extra}; "
                  "pass on_error='nan' to get NaN for failed rows instead", rows=rows)


def _make_batch(kind: str, fields: Dict[str, np.ndarray], alternative: int, alpha: float, null_value: float,
                axis: int, errors_as_nan: bool, intervals: bool, nan_rows: Any = None) -> BatchResult:
    _raise_failed(fields["status"], errors_as_nan, nan_rows)
    return BatchResult(kind, fields, alternative, alpha, null_value, intervals)


def _make_pixel_batch(kind: str, raw: Dict[str, Any], alternative: int, alpha: float, null_value: float,
                      errors_as_nan: bool, intervals: bool, nan_rows: Any = None,
                      all_ok: bool = False) -> BatchResult:
    """The BatchResult of mcstat_pixels_test's flat arrays (rows.cpp): the
    fields of pairs (df of F, Welch's estimates, intervals, critical values,
    two-sample sizes), reject and the int8 status are formed on first read.
    raw["n_x"] / raw["n_y"] are arrays with NaN left out, else the common
    size (n_y None for one-sample tests).  raw["df"] None: every pixel that
    succeeded has the df of raw["df_const"]; raw["std_error"] None: NaN
    (the variance tests).  all_ok: the call returned
    MCSTAT_OK, so no pixel failed and the status need not be read."""
    status = raw["status"]
    if not all_ok:
        _raise_failed(status, errors_as_nan, nan_rows)
    shape = status.shape

    def pair(a: str, b: str) -> _Lazy:
        return _Lazy(lambda: np.stack([raw[a], raw[b]], axis=-1))

    def nans() -> _Lazy:
        return _Lazy(lambda: np.full(shape + (2,), np.nan))

    def sizes(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            return v.astype(np.int64)
        return np.where(status == 0, np.int64(v), np.int64(0))

    def constant(v: float) -> Any:  # v where the pixel succeeded, else NaN
        return np.where(status == 0, v, np.nan)

    f = _Fields()
    f["statistic"] = raw["statistic"]
    f["pvalue"] = raw["pvalue"]
    f["std_error"] = raw["std_error"] if raw["std_error"] is not None else _Lazy(lambda: np.full(shape, np.nan))
    if raw["df"] is None:  # the same df for every pixel (raw["df_const"]): formed when read
        d = raw["df_const"]
        f["df"] = _Lazy(lambda: constant(d[0]) if len(d) == 1
                        else np.stack([constant(d[0]), constant(d[1])], axis=-1))
    else:
        f["df"] = pair("df", "df2") if raw["df2"] is not None else raw["df"]
    f["estimate"] = pair("estimate", "estimate2") if raw["estimate2"] is not None else raw["estimate"]
    f["conf_int"] = pair("conf_lo", "conf_hi") if intervals else nans()
    f["critical_values"] = pair("critical_lo", "critical_hi") if intervals else nans()
    f["reject"] = _Lazy(lambda: raw["decision"] != 0)
    f["decision_code"] = raw["decision"]
    f["status"] = _Lazy(lambda: status.astype(np.int8))
    if raw["n_y"] is None:
        f["nobs"] = _Lazy(lambda: sizes(raw["n_x"]))
    else:
        f["nobs"] = _Lazy(lambda: np.stack([sizes(raw["n_x"]), sizes(raw["n_y"])], axis=-1))
    return BatchResult(kind, f, alternative, alpha, null_value, intervals)
