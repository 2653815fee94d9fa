"""mcstat through ctypes: the C ABI alone, no compiler, no pybind11.

Proof that any FFI can call libmcstat: the structs are mirrored field by
field from mcstat.h, their sizes checked against the library's
mcstat_sizeof_* functions at load time, and every call goes through the
exported C functions.  Standard library only.

    import mcstat_ctypes as mc
    lib = mc.load()                     # $MCSTAT_LIB, or pkg-config's libdir, or the linker's path
    r = mc.t_test_2(lib, x, y, alpha=0.01)
    print(mc.format_result(lib, r, "new", "trusted"))
"""
import ctypes
import ctypes.util
import os
import subprocess

c_double_p = ctypes.POINTER(ctypes.c_double)


class Moments(ctypes.Structure):
    _fields_ = [("n", ctypes.c_uint64), ("scale", ctypes.c_int32), ("version", ctypes.c_uint32),
                ("mean", ctypes.c_double), ("mean_lo", ctypes.c_double), ("m2", ctypes.c_double),
                ("m3", ctypes.c_double), ("m4", ctypes.c_double), ("min", ctypes.c_double),
                ("max", ctypes.c_double), ("reserved", ctypes.c_double * 7)]


# The per-test outputs: anonymous unions over the reserved storage, as in C.
class _ResultInts(ctypes.Structure):
    _fields_ = [("ks_weight", ctypes.c_int32), ("chisq_cells", ctypes.c_int32),
                ("chisq_n_estimated", ctypes.c_int32)]


class _ResultKs(ctypes.Structure):
    _fields_ = [("ks_critical_se", ctypes.c_double), ("ks_n_sim", ctypes.c_double)]


class _ResultTost(ctypes.Structure):
    _fields_ = [("tost_t_lower", ctypes.c_double), ("tost_t_upper", ctypes.c_double),
                ("tost_p_lower", ctypes.c_double), ("tost_p_upper", ctypes.c_double),
                ("tost_lower", ctypes.c_double), ("tost_upper", ctypes.c_double)]


class _ResultBinom(ctypes.Structure):
    _fields_ = [("binom_unused_", ctypes.c_double * 2), ("binom_log_p_value", ctypes.c_double)]


class _ResultChisq(ctypes.Structure):
    _fields_ = [("chisq_unused_", ctypes.c_double * 2), ("chisq_cells_given", ctypes.c_double),
                ("chisq_min_expected", ctypes.c_double), ("chisq_pool_below", ctypes.c_double)]


class _ResultIntsEff(ctypes.Structure):
    _fields_ = [("eff_batches_x", ctypes.c_int32), ("eff_batches_y", ctypes.c_int32)]


class _ResultEff(ctypes.Structure):
    _fields_ = [("eff_var_ratio", ctypes.c_double), ("eff_time_ratio", ctypes.c_double),
                ("eff_se_log_var_x", ctypes.c_double), ("eff_se_log_var_y", ctypes.c_double),
                ("eff_se_log_time_x", ctypes.c_double), ("eff_se_log_time_y", ctypes.c_double)]


class _ResultIntUnion(ctypes.Union):
    _anonymous_ = ("_s", "_eff_i")
    _fields_ = [("reserved_i", ctypes.c_int32 * 3), ("_s", _ResultInts), ("_eff_i", _ResultIntsEff)]


class _ResultUnion(ctypes.Union):
    _anonymous_ = ("_ks", "_tost", "_binom", "_chisq", "_eff")
    _fields_ = [("reserved", ctypes.c_double * 7), ("_ks", _ResultKs), ("_tost", _ResultTost),
                ("_binom", _ResultBinom), ("_chisq", _ResultChisq), ("_eff", _ResultEff)]


class Result(ctypes.Structure):
    _anonymous_ = ("_ints", "_extras")
    _fields_ = [("test", ctypes.c_int32), ("method", ctypes.c_int32), ("alternative", ctypes.c_int32),
                ("reject", ctypes.c_int32), ("decision", ctypes.c_int32), ("_ints", _ResultIntUnion),
                ("n", ctypes.c_uint64 * 2), ("statistic", ctypes.c_double), ("df", ctypes.c_double * 2),
                ("p_value", ctypes.c_double), ("p_value_se", ctypes.c_double),
                ("conf_int", ctypes.c_double * 2), ("estimate", ctypes.c_double * 2),
                ("null_value", ctypes.c_double), ("alpha", ctypes.c_double), ("critical", ctypes.c_double * 2),
                ("std_error", ctypes.c_double), ("_extras", _ResultUnion)]


class KsOptions(ctypes.Structure):
    _fields_ = [("size", ctypes.c_uint32), ("weight", ctypes.c_int32), ("method", ctypes.c_int32),
                ("threads", ctypes.c_int32), ("n_sim", ctypes.c_int64), ("seed", ctypes.c_uint64),
                ("cache", ctypes.c_void_p), ("critical", ctypes.c_int32), ("reserved", ctypes.c_int32)]


# enum values are part of the ABI (mcstat.h)
TWO_SIDED, LESS, GREATER = 0, 1, 2
ALTERNATIVES = {"two-sided": TWO_SIDED, "less": LESS, "greater": GREATER}
KS_WEIGHT_NONE, KS_WEIGHT_CANNER = 0, 1
METHOD_AUTO, METHOD_EXACT, METHOD_SIMULATE, METHOD_ASYMPTOTIC = 1, 2, 3, 4
DECISION_LESS, DECISION_EQUAL, DECISION_GREATER = -1, 0, 1


class McstatError(ValueError):
    """A non-zero status, with libmcstat's sentence for it."""

    def __init__(self, status, text):
        super().__init__("%s (status %d)" % (text, status))
        self.status = status


def _find_library():
    path = os.environ.get("MCSTAT_LIB")
    if path:
        return path
    try:
        libdir = subprocess.run(["pkg-config", "--variable=libdir", "mcstat"], capture_output=True, text=True,
                                check=True).stdout.strip()
        cand = os.path.join(libdir, "libmcstat.so")
        if os.path.exists(cand):
            return cand
    except (OSError, subprocess.CalledProcessError):
        pass
    found = ctypes.util.find_library("mcstat")
    if not found:
        raise OSError("libmcstat not found: set MCSTAT_LIB or PKG_CONFIG_PATH")
    return found


def load(path=None):
    lib = ctypes.CDLL(path or _find_library())
    D, P, S, I = ctypes.c_double, c_double_p, ctypes.c_size_t, ctypes.c_int
    R = ctypes.POINTER(Result)
    M = ctypes.POINTER(Moments)
    sig = {
        "mcstat_version": (ctypes.c_char_p, []),
        "mcstat_strerror": (ctypes.c_char_p, [I]),
        "mcstat_sizeof_moments": (S, []), "mcstat_sizeof_result": (S, []),
        "mcstat_sizeof_ks_options": (S, []), "mcstat_sizeof_moments_bytes": (S, []),
        "mcstat_moments_init": (I, [M]), "mcstat_moments_add": (I, [M, D]),
        "mcstat_moments_add_array": (I, [M, P, S]), "mcstat_moments_merge": (I, [M, M]),
        "mcstat_moments_mean": (D, [M]), "mcstat_moments_var": (D, [M]),
        "mcstat_moments_to_bytes": (I, [M, ctypes.c_char_p, S]),
        "mcstat_moments_from_bytes": (I, [ctypes.c_char_p, S, M]),
        "mcstat_t_test_1": (I, [P, S, D, I, D, R]),
        "mcstat_t_test_2": (I, [P, S, P, S, D, I, D, R]),
        "mcstat_var_test_1": (I, [P, S, D, I, D, R]),
        "mcstat_var_test_2": (I, [P, S, P, S, D, I, D, R]),
        "mcstat_t_test_1_moments": (I, [M, D, I, D, R]),
        "mcstat_t_test_2_moments": (I, [M, M, D, I, D, R]),
        "mcstat_efficiency_test": (I, [M, M, M, M, D, I, D, R]),
        "mcstat_var_test_1_moments": (I, [M, D, I, D, R]),
        "mcstat_var_test_2_moments": (I, [M, M, D, I, D, R]),
        # FFI callers initialise options for their struct's size (the header's
        # mcstat_ks_options_init is a macro doing that); the plain symbol is
        # 0.1.0's and writes 0.1.0's size.
        "mcstat_ks_options_init_size": (I, [ctypes.POINTER(KsOptions), S]),
        "mcstat_ks_options_init": (I, [ctypes.POINTER(KsOptions)]),
        "mcstat_ks_test_2": (I, [P, S, P, S, I, D, ctypes.POINTER(KsOptions), R]),
        "mcstat_result_format": (I, [R, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, S,
                                     ctypes.POINTER(S)]),
        "mcstat_t_quantile": (I, [D, D, I, P]), "mcstat_chisq_quantile": (I, [D, D, I, P]),
        "mcstat_f_quantile": (I, [D, D, D, I, P]),
        "mcstat_t_logcdf": (I, [D, D, I, P]), "mcstat_chisq_logcdf": (I, [D, D, I, P]),
        "mcstat_f_logcdf": (I, [D, D, D, I, P]),
    }
    for name, (res, args) in sig.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = res, args
    # the mirrored layouts must be the library's
    for name, cls in (("mcstat_sizeof_moments", Moments), ("mcstat_sizeof_result", Result),
                      ("mcstat_sizeof_ks_options", KsOptions)):
        if getattr(lib, name)() != ctypes.sizeof(cls):
            raise OSError("%s: library says %d bytes, this module %d" % (name, getattr(lib, name)(),
                                                                       ctypes.sizeof(cls)))
    return lib


def check(lib, status):
    if status != 0:
        raise McstatError(status, lib.mcstat_strerror(status).decode())


def _array(values):
    values = [float(v) for v in values]
    return (ctypes.c_double * len(values))(*values), len(values)


def t_test_1(lib, x, mu=0.0, alternative="two-sided", alpha=0.05):
    r = Result()
    a, n = _array(x)
    check(lib, lib.mcstat_t_test_1(a, n, mu, ALTERNATIVES[alternative], alpha, ctypes.byref(r)))
    return r


def t_test_2(lib, x, y, mu=0.0, alternative="two-sided", alpha=0.05):
    r = Result()
    a, nx = _array(x)
    b, ny = _array(y)
    check(lib, lib.mcstat_t_test_2(a, nx, b, ny, mu, ALTERNATIVES[alternative], alpha, ctypes.byref(r)))
    return r


def var_test_1(lib, x, sigma2, alternative="two-sided", alpha=0.05):
    r = Result()
    a, n = _array(x)
    check(lib, lib.mcstat_var_test_1(a, n, sigma2, ALTERNATIVES[alternative], alpha, ctypes.byref(r)))
    return r


def var_test_2(lib, x, y, ratio=1.0, alternative="two-sided", alpha=0.05):
    r = Result()
    a, nx = _array(x)
    b, ny = _array(y)
    check(lib, lib.mcstat_var_test_2(a, nx, b, ny, ratio, ALTERNATIVES[alternative], alpha, ctypes.byref(r)))
    return r


def ks_test_2(lib, x, y, alternative="two-sided", alpha=0.05, weight=KS_WEIGHT_CANNER, method=METHOD_AUTO,
              n_sim=None, seed=0):
    o = KsOptions()
    check(lib, lib.mcstat_ks_options_init_size(ctypes.byref(o), ctypes.sizeof(o)))
    o.weight, o.method, o.seed = weight, method, seed
    if n_sim is not None:
        o.n_sim = n_sim
    r = Result()
    a, nx = _array(x)
    b, ny = _array(y)
    check(lib, lib.mcstat_ks_test_2(a, nx, b, ny, ALTERNATIVES[alternative], alpha, ctypes.byref(o),
                                    ctypes.byref(r)))
    return r


def moments(lib, values=()):
    m = Moments()
    check(lib, lib.mcstat_moments_init(ctypes.byref(m)))
    if values:
        a, n = _array(values)
        check(lib, lib.mcstat_moments_add_array(ctypes.byref(m), a, n))
    return m


def format_result(lib, r, x_name="x", y_name="y"):
    """The R-style block, sized by a first call that reports the length."""
    length = ctypes.c_size_t()
    st = lib.mcstat_result_format(ctypes.byref(r), x_name.encode(), y_name.encode(), None, 0,
                                  ctypes.byref(length))
    if st not in (0, 7):  # MCSTAT_EBUFSIZE is expected for the empty buffer
        check(lib, st)
    buf = ctypes.create_string_buffer(length.value + 1)
    check(lib, lib.mcstat_result_format(ctypes.byref(r), x_name.encode(), y_name.encode(), buf,
                                        len(buf), None))
    return buf.value.decode()
