"""Package-level behaviour: zero-copy input, the GIL, GSL's handler, typing."""
import os
import subprocess
import sys
import threading
import tracemalloc

import numpy as np
import pytest

import mcstat


def peak_bytes(f):
    tracemalloc.start()
    try:
        f()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_contiguous_float64_is_not_copied():
    x = np.random.default_rng(1).normal(size=2_000_000)  # 16 MB
    y = x[::-1].copy()
    assert peak_bytes(lambda: mcstat.t_test(x, y)) < 100_000
    assert peak_bytes(lambda: mcstat.Moments(x)) < 100_000
    # other input is converted exactly once (NumPy's allocations are traced)
    x32 = x.astype(np.float32)
    assert 16_000_000 <= peak_bytes(lambda: mcstat.t_test(x32)) < 2 * 16_000_000
    assert 16_000_000 <= peak_bytes(lambda: mcstat.t_test(x[::2].copy()[::1], x[1::2])) < 2 * 16_000_000


def test_rows_read_in_place():
    X = np.random.default_rng(2).normal(size=(20000, 64))  # 10 MB
    out = 20000 * 8 * 16  # the result arrays
    assert peak_bytes(lambda: mcstat.t_test(X)) < out + 1_000_000


def test_gil_is_released_for_long_loops():
    # Another thread, woken just before the call, gets the GIL while
    # libmcstat sums 160 MB only if the extension released it: with a
    # switch interval of 10 s the interpreter itself hands the GIL over
    # only when the holder blocks, so a call that kept it would let the
    # thread run only after it returned, and it would see done set.
    x = np.random.default_rng(3).normal(size=20_000_000)
    state = {"done": False, "seen_inside": None}
    go = threading.Event()

    def other():
        go.wait()
        state["seen_inside"] = not state["done"]

    th = threading.Thread(target=other)
    old = sys.getswitchinterval()
    sys.setswitchinterval(10.0)
    try:
        th.start()
        go.set()
        mcstat.t_test(x)
        state["done"] = True
    finally:
        th.join()
        sys.setswitchinterval(old)
    assert state["seen_inside"] is True


def test_gsl_handler_only_turned_off_when_default():
    code = "import mcstat; print(mcstat.gsl_handler_was_default)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "True"
    # a process that installed its own handler keeps it
    code = """
import ctypes, ctypes.util
gsl = ctypes.CDLL("libgsl.so.27") if ctypes.util.find_library("gsl") is None else ctypes.CDLL(ctypes.util.find_library("gsl"))
HANDLER = ctypes.CFUNCTYPE(None, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int)
h = HANDLER(lambda *a: None)
gsl.gsl_set_error_handler.restype = ctypes.c_void_p
gsl.gsl_set_error_handler(h)
import mcstat
prev = gsl.gsl_set_error_handler(None)
print(mcstat.gsl_handler_was_default, prev == ctypes.cast(h, ctypes.c_void_p).value)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "True"]


def header_version(path, prefix):
    """MAJOR.MINOR.PATCH from a C header's version macros: the one source."""
    import re
    text = open(os.path.join(os.path.dirname(__file__), "..", "..", path)).read()
    parts = [re.search(rf"^#define {prefix}_VERSION_{p} +(\d+)$", text, re.M) for p in ("MAJOR", "MINOR", "PATCH")]
    assert all(parts), path
    return ".".join(m.group(1) for m in parts)


def test_version_single_source():
    """The package's version is the header's (pyproject.toml reads it with a
    regex at build time), as is the linked library's."""
    from importlib.metadata import version
    want = header_version("libmcstat/include/mcstat/version.h", "MCSTAT")
    assert mcstat.__version__ == want
    assert version("mcstat") == want
    assert mcstat.__libmcstat_version__ == want


def test_package_surface():
    for name in ["t_test", "var_test", "Moments", "batch_means", "TestResult", "BatchResult",
                 "DegenerateDataError", "NonFiniteError", "TooFewObservationsError"]:
        assert name in mcstat.__all__ and hasattr(mcstat, name)
    assert mcstat.__libmcstat_version__ == header_version("libmcstat/include/mcstat/version.h", "MCSTAT")
    pkg = os.path.dirname(mcstat.__file__)
    assert os.path.exists(os.path.join(pkg, "py.typed")) and os.path.exists(os.path.join(pkg, "_core.pyi"))
    assert "Welch" in mcstat.t_test.__doc__ and "Parameters" in mcstat.var_test.__doc__
    import inspect
    sig = inspect.signature(mcstat.t_test)
    assert list(sig.parameters)[:3] == ["x", "y", "mu"]
    assert sig.parameters["alternative"].kind is inspect.Parameter.KEYWORD_ONLY


def test_result_pickles():
    import pickle
    r = mcstat.t_test([1.0, 2.0, 4.0], [3.0, 5.0, 4.5, 7.0])
    r2 = pickle.loads(pickle.dumps(r))
    assert r2._raw() == r._raw() and str(r2) == str(r)


def test_ks_and_estimators_surface():
    import inspect
    for name in ["ks_test", "KSCache", "TooBigError"]:
        assert name in mcstat.__all__ and hasattr(mcstat, name)
    sig = inspect.signature(mcstat.ks_test)
    assert list(sig.parameters) == ["x", "y", "weight", "alternative", "alpha", "method", "n_sim", "seed",
                                    "threads", "cache", "critical", "nan_policy"]
    assert sig.parameters["weight"].default == "canner" and sig.parameters["method"].default == "auto"
    assert sig.parameters["weight"].kind is inspect.Parameter.KEYWORD_ONLY
    assert "OPPOSITE of SciPy" in mcstat.ks_test.__doc__
    from mcstat import estimators as est
    pkg = os.path.dirname(mcstat.__file__)
    assert os.path.exists(os.path.join(pkg, "_estimators.pyi"))
    for name in est.__all__:
        assert hasattr(est, name), name
    assert est.__libmcest_version__ == header_version("estimators/include/mcest.h", "MCEST")
    assert "Parameters" in est.irradiance.__doc__ and "first_index" in est.irradiance.__doc__


def test_experimental_families_are_marked():
    """The calls of libmcstat's experimental families (mcstat/power.h,
    mcstat/diagnostics.h, mcstat/gof.h) say so in the Python reference;
    the stable ones (the renderer checks, the sequential tests) do not."""
    for f in (mcstat.power, mcstat.ks_power, mcstat.ks_sample_size, mcstat.diagnose, mcstat.binom_test,
              mcstat.battery_test, mcstat.chisq_gof):
        assert "Experimental (libmcstat's mcstat/" in f.__doc__, f.__name__
    for f in (mcstat.check_bsdf, mcstat.SequentialTest, mcstat.t_test):
        assert "Experimental" not in (f.__doc__ or ""), f.__name__
