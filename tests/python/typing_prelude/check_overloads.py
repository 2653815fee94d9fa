# What the stubs promise, checked by mypy and pyright (test_typing.py):
# the result kind of t_test and var_test follows the input.
from typing import Any, Optional, Tuple, assert_type

import numpy as np

import mcstat
from mcstat import distributions

one: np.ndarray[Tuple[int], np.dtype[np.float64]] = np.zeros(3)
two: np.ndarray[Tuple[int, int], np.dtype[np.float64]] = np.zeros((3, 4))
unknown = np.zeros(3)  # NDArray: the shape is not in the type

assert_type(mcstat.t_test([1.0, 2.0, 3.0], mu=1.0), mcstat.TestResult)
assert_type(mcstat.t_test(one, [1.0, 2.0]), Any)  # an array: its ndim decides at run time
assert_type(mcstat.t_test(mcstat.Moments(one)), mcstat.TestResult)
assert_type(mcstat.t_test(two), Any)  # NDArray: its ndim decides at run time
assert_type(mcstat.t_test(mcstat.MomentsArray(3)), mcstat.BatchResult)
assert_type(mcstat.t_test(mcstat.Moments(one), mcstat.MomentsArray(3)), mcstat.BatchResult)
assert_type(mcstat.t_test(unknown), Any)
assert_type(mcstat.var_test([1.0, 2.0, 4.0], sigma2=1.0), mcstat.TestResult)
assert_type(mcstat.var_test(mcstat.Moments(one), mcstat.Moments(one)), mcstat.TestResult)
assert_type(mcstat.var_test(mcstat.MomentsArray(3), mcstat.Moments(one)), mcstat.BatchResult)
assert_type(mcstat.t_test(mcstat.MomentsArray((2, 3)))[0, 1], Any)  # a TestResult, or a sub-batch for a partial index
assert_type(mcstat.t_test(mcstat.MomentsArray(3)).pvalue, np.ndarray[Tuple[Any, ...], np.dtype[np.float64]])
assert_type(distributions.t_cdf(1.0, 3), float)
assert_type(mcstat.Stream().push(one).check_mean(0.0, tolerance=0.1), mcstat.TestResult)
assert_type(mcstat.power("t", n=20, effect=0.5).power, float)
assert_type(mcstat.equivalence_test(one, margin=0.1).pvalues, Tuple[float, float])
assert_type(mcstat.diagnostics.tail_index(one), Tuple[float, float])


# the renderer checks: every keyword typed (a misspelt one or a wrong type is an error)
def _f(*a: Any) -> Any: ...


assert_type(mcstat.check_bsdf(_f, _f, _f, [0.0, 0.0, 1.0], n=1000, alpha=0.01, seed=1, domain="hemisphere",
                              weight="value", routes=["cells", "weight"], rtol=1e-3, resolution=2.0**-18),
            mcstat.CheckReport)
assert_type(mcstat.check_emitter(_f, _f, _f, n_uniforms=2, cells=64), mcstat.CheckReport)
assert_type(mcstat.check_warp(_f, _f, domain="disk", n_pilot=128), mcstat.CheckReport)
assert_type(mcstat.check_phase(_f, _f, _f, one, reciprocal=True, energy=False), mcstat.CheckReport)
assert_type(mcstat.check_medium(_f, _f, _f, sigma_ref=2.0, escape_transmittance=0.5, batch=4096), mcstat.CheckReport)
assert_type(mcstat.check_bsdf(_f, _f, _f, one).verdict, str)
assert_type(mcstat.check_bsdf(_f, _f, _f, one).route("mass").why, Optional[str])
