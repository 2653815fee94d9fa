"""Bad input that used to crash, allocate gigabytes, or be silently
misread: sizes whose products overflow, complex/date/object/string arrays,
string alphas, counts beyond 2**64 and unreasonable thread counts.  Each
must raise an exception naming the argument, before any large allocation.

The cases that used to crash the interpreter run in a child process, so the
old behaviour is a failed assertion rather than a dead test run."""
import re
import struct
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import mcstat


def run_child(code, as_limit_extra=None):
    """Runs code in a fresh interpreter (optionally with its address space
    limited to its size at the start of `code` plus as_limit_extra bytes);
    returns (returncode, stdout, stderr)."""
    prelude = "import mcstat\n"
    if as_limit_extra is not None:
        prelude += textwrap.dedent(f"""
            import resource
            with open('/proc/self/statm') as f:
                vm = int(f.read().split()[0]) * resource.getpagesize()
            lim = vm + {int(as_limit_extra)}
            resource.setrlimit(resource.RLIMIT_AS, (lim, lim))
            """)
    p = subprocess.run([sys.executable, "-c", prelude + textwrap.dedent(code)], capture_output=True, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


# ---- MomentsArray sizes ----------------------------------------------------------

@pytest.mark.parametrize("expr", [
    "mcstat.MomentsArray((2**32, 2**32))[1, 1]",
    "mcstat.MomentsArray.from_bytes(b'', shape=(2**32, 2**32))[1, 1]",
    "mcstat.MomentsArray((2**62 + 1, 4))[10**6, 0]",
    "mcstat.MomentsArray((2**61, 2**61, 0, 2**61)).size",
])
def test_moments_array_shape_overflow_refused(expr):
    rc, out, err = run_child(f"""
        try:
            r = {expr}
        except (ValueError, OverflowError, MemoryError) as e:
            print(type(e).__name__, e)
        else:
            print("OK", r)
        """)
    assert rc == 0, f"crashed (return code {rc}): {err[-2000:]}"
    if "0, 2**61" in expr:  # a zero dimension: no pixels, nothing overflows
        assert out.startswith("OK 0"), out
    else:
        assert "shape" in out and not out.startswith("OK"), out


def test_moments_array_shape_errors_in_process():
    with pytest.raises(mcstat.InvalidArgumentError, match=r"shape \(4294967296, 4294967296\)"):
        mcstat.MomentsArray((2**32, 2**32))
    with pytest.raises(OverflowError, match="shape"):
        mcstat.MomentsArray((2**70,))
    with pytest.raises(OverflowError, match="shape"):
        mcstat.MomentsArray.from_bytes(b"", (3, 2**64))
    assert mcstat.MomentsArray((3, np.int64(4))).shape == (3, 4)


def test_from_bytes_checks_the_length_before_allocating():
    # 10**7 accumulators are 1.28 GB: with 300 MB of address space to spare
    # the length must be refused first (it used to allocate, then refuse).
    rc, out, err = run_child("""
        try:
            mcstat.MomentsArray.from_bytes(b'abc', shape=(10**7,))
        except Exception as e:
            print(type(e).__name__, e)
        """, as_limit_extra=300 << 20)
    assert rc == 0, err[-2000:]
    assert out.startswith("CorruptDataError") and "3 bytes given" in out, out


def test_from_bytes_length_mismatch_message():
    with pytest.raises(mcstat.CorruptDataError, match=r"3 bytes given.*shape \(10000000,\)"):
        mcstat.MomentsArray.from_bytes(b"abc", shape=(10**7,))
    with pytest.raises(mcstat.CorruptDataError, match="bytes given"):
        mcstat.MomentsArray.from_bytes(b"x" * 95)


# ---- counts past 2**64 - 1 ----------------------------------------------------------

def _record(n):
    """A consistent serialized accumulator (serialize.c's layout) of n values
    spread evenly over {0, 1, 2}: mean 1, M2 = M4 = 2n/3, M3 = 0."""
    body = b"MCSM" + struct.pack("<IQiI", 1, n, 0, 0)
    body += struct.pack("<7d", 1.0, 0.0, 2 * n / 3, 0.0, 2 * n / 3, 0.0, 2.0) + bytes(8)
    h = 0xcbf29ce484222325  # FNV-1a 64 of bytes 0..87
    for c in body:
        h = ((h ^ c) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return body + struct.pack("<Q", h)


def test_count_overflow_refused():
    big = mcstat.Moments.from_bytes(_record(2**64 - 1))
    assert big.n == 2**64 - 1
    small = mcstat.Moments([0.0, 1.0, 2.0])
    before = big.to_bytes()
    with pytest.raises(mcstat.TooBigError):
        big.merge(small)
    with pytest.raises(mcstat.TooBigError):
        big.push(1.0)
    with pytest.raises(mcstat.TooBigError):
        big + small
    assert big.to_bytes() == before and big.n == 2**64 - 1
    half = mcstat.Moments.from_bytes(_record(2**63))
    with pytest.raises(mcstat.TooBigError):
        half.merge(half)
    assert half.n == 2**63

    arr = mcstat.MomentsArray.from_bytes(_record(2**64 - 2) * 2, (2,))
    snap = arr.to_bytes()
    with pytest.raises(mcstat.TooBigError, match="unchanged"):
        arr.push(np.array([[1.0, 2.0], [3.0, 4.0]]))  # 2 more values per pixel
    with pytest.raises(mcstat.TooBigError, match="unchanged"):
        arr.merge(arr)
    assert arr.to_bytes() == snap
    arr.push(np.array([np.nan, 2.0]), nan_policy="omit")  # one value into pixel 1: fits
    assert list(arr.n.astype(np.uint64)) == [2**64 - 2, 2**64 - 1]


# ---- dtypes that are not real numbers ---------------------------------------------------

BAD_DTYPES = {
    "complex": np.array([1 + 2j, 2.0, 3.0, 4.5, 5.0, 6.0, 7.0, 8.0]),
    "datetime64": np.array(["2026-01-01", "2026-01-02", "2026-01-04", "2026-01-08"] * 2, dtype="datetime64[D]"),
    "timedelta64": np.array([1, 2, 4, 8, 3, 5, 7, 9], dtype="timedelta64[s]"),
    "object": np.array([1.0, 2.0, None, 4.0, 5.0, 6.0, 7.0, 8.0], dtype=object),
    "str": np.array(["1", "2", "3", "4", "5", "6", "7", "8"]),
    "bytes": np.array([b"1", b"2", b"3", b"4", b"5", b"6", b"7", b"8"]),
}
GOOD = np.array([0.5, 1.5, 2.0, 3.25, 4.0, 5.5, 6.0, 7.75])
PV = np.array([0.01, 0.2, 0.5, 0.04])


def _calls(bad):
    """(argument name, call) for every path that takes an array."""
    img = np.stack([bad[:4], bad[4:]]).reshape(2, 2, 2)
    return [
        ("x", lambda: mcstat.t_test(bad)),
        ("y", lambda: mcstat.t_test(GOOD, bad)),
        ("x", lambda: mcstat.var_test(bad, sigma2=1.0)),
        ("x", lambda: mcstat.t_test(np.stack([bad, bad]), axis=1)),
        ("y", lambda: mcstat.ks_test(GOOD, bad)),
        ("values", lambda: mcstat.Moments(bad)),
        ("values", lambda: mcstat.Moments().push(bad)),
        ("x", lambda: mcstat.equivalence_test(bad, margin=1.0)),
        ("x", lambda: mcstat.diagnose(np.tile(bad, 10), normality=False)),
        ("x", lambda: mcstat.batch_means(bad, 2)),
        ("images", lambda: mcstat.MomentsArray((2, 2)).push(img)),
        ("observed", lambda: mcstat.chisq_gof(bad, GOOD)),
        ("expected", lambda: mcstat.chisq_gof(GOOD, bad)),
        ("p", lambda: mcstat.p_adjust(bad)),
        ("tests", lambda: mcstat.battery_test(bad)),
    ]


@pytest.mark.parametrize("kind", sorted(BAD_DTYPES))
def test_non_real_dtypes_refused_naming_the_argument(kind):
    bad = BAD_DTYPES[kind]
    for name, call in _calls(bad):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no ComplexWarning-and-carry-on
            with pytest.raises(TypeError, match=rf"^{name} must hold real numbers.*{re.escape(str(bad.dtype))}"):
                call()


def test_complex_scalars_and_lists_refused():
    with pytest.raises(TypeError, match="values must hold real numbers.*complex"):
        mcstat.Moments().push(1 + 2j)
    with pytest.raises(TypeError, match="x must hold real numbers.*complex"):
        mcstat.t_test([1.0, 2.0, 3j])
    with pytest.raises(TypeError, match="tests must hold real numbers.*complex"):
        mcstat.battery_test([0.01 + 0j, 0.5])


def test_bool_and_integer_arrays_still_accepted():
    ints = np.array([1, 2, 4, 8, 3, 5], dtype=np.int32)
    assert mcstat.t_test(ints).pvalue == mcstat.t_test(ints.astype(float)).pvalue
    assert mcstat.Moments(np.array([True, False, True])).mean == pytest.approx(2 / 3)
    assert mcstat.Moments(np.array([1, 2, 3], dtype=np.uint64)).mean == 2.0
    assert mcstat.Moments(np.array([1.0, 2.0], dtype=np.float32)).n == 2
    assert mcstat.batch_means(np.arange(6), 2).tolist() == [0.5, 2.5, 4.5]


# ---- scalar arguments ---------------------------------------------------------------------

def test_string_alpha_refused_like_t_test():
    with pytest.raises(TypeError, match="alpha"):
        mcstat.t_test(GOOD, alpha="0.05")
    with pytest.raises(TypeError, match="alpha must be a real number"):
        mcstat.binom_test(3, 10, alpha="0.05")
    with pytest.raises(TypeError, match="p must be a real number"):
        mcstat.binom_test(3, 10, p="0.5")
    with pytest.raises(TypeError, match="alpha must be a real number"):
        mcstat.battery_test(PV, alpha="0.05")
    with pytest.raises(TypeError, match="alpha must be a real number"):
        mcstat.battery_test(np.array([True, False]), alpha="0.05")
    with pytest.raises(TypeError, match="alpha must be a real number"):
        mcstat.battery_test(3, alpha="0.05", n=10)
    with pytest.raises(TypeError, match="meta_alpha must be a real number"):
        mcstat.battery_test(PV, meta_alpha="0.05")
    assert mcstat.battery_test(PV, alpha=np.float64(0.05)).statistic == 2


def test_binom_huge_n_names_the_argument():
    with pytest.raises(OverflowError, match="n must be below 2\\*\\*64"):
        mcstat.binom_test(3, 2**64)
    with pytest.raises(OverflowError, match="x must be below 2\\*\\*64"):
        mcstat.binom_test(2**70, 2**64)
    with pytest.raises(mcstat.TooBigError):  # representable, but beyond 2**53
        mcstat.binom_test(3, 2**60)


def test_set_num_threads_range():
    try:
        for bad in (-1, 1025, 2**31 - 1, 2**80):
            with pytest.raises(ValueError, match="1..1024"):
                mcstat.set_num_threads(bad)
        with pytest.raises(TypeError):
            mcstat.set_num_threads(2.0)
        with pytest.raises(TypeError):
            mcstat.set_num_threads(True)
        mcstat.set_num_threads(3)
        assert mcstat.get_num_threads() == 3
        mcstat.set_num_threads(1024)
        assert mcstat.get_num_threads() == 1024
    finally:
        mcstat.set_num_threads(0)
    assert mcstat.get_num_threads() >= 1
