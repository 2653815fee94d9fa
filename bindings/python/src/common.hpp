// common.hpp - shared declarations of the mcstat._core extension.
//
// The binding is thin on purpose: numerics, decisions and the R-style text
// are libmcstat's; this layer converts NumPy arrays and Python arguments,
// maps status codes to exceptions, and runs rows on threads.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#define MCSTAT_EXPERIMENTAL /* the package wraps the experimental families too */
#include "mcstat.h"
#include "real_array.hpp"

namespace py = pybind11;

namespace mcs {

// ---- errors (errors.cpp) ---------------------------------------------------
// The exception classes live in mcstat/_errors.py (documented there); the
// module looks them up once at import.
void init_errors();
// The exception class for a status (McstatError for unknown codes).
py::handle error_class(int status);
// The sentence of a status in Python's words: mcstat_strerror's, but
// "invalid argument" and "too few observations" for MCSTAT_EINVAL and
// MCSTAT_ETOOFEW, whose C sentences speak of NULL pointers and of other
// tests' minimum sizes (mcstat._core._status_text).
const char *status_text(int status);
// Raises the class of `status` with "<status_text(status)> (<detail>)" (the
// sentence alone when detail is empty).
[[noreturn]] void throw_status(int status, const std::string &detail = std::string());
// Invalid argument with a message of its own (InvalidArgumentError): the
// message alone, e.g. "alpha must be in (0, 1), got 5".
[[noreturn]] void throw_invalid(const std::string &message);
// Raises status's exception with C's reason (mcstat_last_error), the
// field's C prefix ("options.", "model.") dropped since Python spells the
// same names as keywords; without a reason, throw_status(status, fallback).
[[noreturn]] void throw_refusal(int status, const std::string &fallback = std::string());

// ---- argument parsing (tests.cpp) -------------------------------------------
// repr() of a Python object, for messages.
std::string repr(PyObject *o);
// A real number (TypeError naming `name` otherwise).
double get_double(PyObject *o, const char *name);
// A str's UTF-8 text (TypeError naming `name` otherwise).
const char *get_str(PyObject *o, const char *name);
// The enum mcstat_alternative named by a str (libmcstat's parser: "two-sided"
// and R's spellings, "less", "greater"): TypeError when not a str,
// InvalidArgumentError naming the value otherwise.  Every alternative the
// extension receives goes through it, and Python code calls it as
// _core._alternative_code.
int parse_alternative(PyObject *o);

// The body of a METH_FASTCALL function: runs f, turning C++ exceptions
// into the Python error they stand for.
template <typename F> PyObject *guarded(F f)
{
    try {
        return f().release().ptr();
    } catch (py::error_already_set &e) {
        e.restore();
    } catch (py::builtin_exception &e) {
        e.set_error();
    } catch (std::bad_alloc &) {
        PyErr_SetString(error_class(MCSTAT_ENOMEM).ptr(), mcstat_strerror(MCSTAT_ENOMEM));
    } catch (std::exception &e) {
        PyErr_SetString(PyExc_RuntimeError, e.what());
    }
    return nullptr;
}

// ---- input arrays (tests.cpp) ---------------------------------------------
// Every array argument goes through these.  obj as a float64 array: the same
// object when it already is one (any layout), else converted once; NumPy's
// own error when it cannot be.  TypeError naming `name` for complex,
// datetime64, timedelta64, object, string and other non-real dtypes (bool
// and integers are accepted).
py::array as_float_array(py::handle obj, const char *name);
// The same, C-contiguous (a copy only when obj is not).
py::array as_contiguous_array(py::handle obj, const char *name);
// Only the dtype check, real_array(obj, name) (real_array.hpp): obj as NumPy
// reads it, not converted to float64.

// ---- accumulators (moments.cpp) ---------------------------------------------
struct Moments {
    mcstat_moments m;
};
void register_moments(py::module_ &mod);
// The accumulator inside a Python Moments, or nullptr if obj is not one.
const mcstat_moments *as_moments(py::handle obj);

// ---- results (result.cpp) -----------------------------------------------------
struct Result {
    mcstat_result r;
    uint64_t seed = 0;     // the simulation's seed (K-S, when has_seed)
    bool has_seed = false; // the p-value was simulated from `seed`
};
void register_result(py::module_ &mod);
void register_result_helpers(py::module_ &mod);
py::object make_result(const mcstat_result &r);
py::object make_result(const Result &r);

// ---- adjusted p-values (p_adjust.cpp) -------------------------------------
void register_p_adjust(py::module_ &mod);
// escalation.cpp: mcstat.Escalation, the two-stage test instead of reruns
void register_escalation(py::module_ &mod);
// Welch's test per row from (n, mean, M2) summaries (summary_rows.cpp).
void register_summary_rows(py::module_ &mod);
// Welch's test per pixel on seeds-major stacks (pixels.cpp).
void register_pixels(py::module_ &mod);

// ---- the K-S test (ks.cpp) ---------------------------------------------------
void register_ks(py::module_ &mod);

// ---- equivalence and power (power.cpp) -------------------------------------------
void register_power(py::module_ &mod);
// ---- binomial test, battery meta-test, diagnostics (diagnostics.cpp) --------
void register_diagnostics(py::module_ &mod);
// ---- chi-squared goodness of fit (chisq.cpp) ------------------------------------
void register_chisq(py::module_ &mod);
// ---- the efficiency-ratio test of two estimators (efficiency.cpp) ----------------
void register_efficiency(py::module_ &mod);
// check.cpp: check_bsdf, check_emitter, check_warp
void register_check(py::module_ &mod);
// ---- t, chi-squared and F distributions over arrays (distributions.cpp) ----
void register_distributions(py::module_ &mod);
// ---- the renderer's buffered accumulator and its checks (stream.cpp) ----
void register_stream(py::module_ &mod);
// The stream inside a Python Stream, or nullptr if obj is not one.
const mcstat_stream *as_stream(py::handle obj);
// mcstat.SequentialTest (sequential.cpp)
void register_sequential(py::module_ &mod);

// ---- the tests (tests.cpp, rows.cpp) ----------------------------------------------
void register_tests(py::module_ &mod);

// T2P: Student's pooled two-sample t; TP: the paired t.
enum class Kind { T1, T2, V1, V2, T2P, TP };

struct TestArgs {
    Kind kind;
    double null_value; // mu, sigma2 or ratio
    int alternative;
    double alpha;
    int axis;
    bool omit_nan;
    bool propagate_nan; // nan_policy="propagate": NaN data give a NaN result, decided here, not in C
    bool intervals;
    bool errors_as_nan;
    int threads = 0; // per-pixel threads= (0: num_threads())
};

// The result a test on data with NaN gets under nan_policy="propagate" (as
// SciPy: statistic, p-value, df and the rest NaN), with the sample sizes.
mcstat_result nan_result(const TestArgs &a, uint64_t nx, uint64_t ny);

// One test per row of N-D arrays (axis moved last); returns the
// BatchResult built by mcstat._result (which also raises for bad rows).
py::object run_rows(const TestArgs &a, py::array x, py::array y, bool two);

// Worker threads for row-wise work (mcstat.set_num_threads: 0 = the
// default, else 1..MAX_THREADS).
constexpr int MAX_THREADS = 1024;
int num_threads();
void set_num_threads(int n);

// Arrays below this many values are processed without releasing the GIL:
// releasing and re-taking it costs more than the loop (measured, see
// bench/RESULTS_python.md); every longer loop over data runs without it.
constexpr size_t GIL_RELEASE_MIN = 4096;

// ---- arrays of accumulators, one per pixel (moments_array.cpp, rows.cpp) ----
struct MomentsArray {
    std::vector<py::ssize_t> shape;
    std::vector<mcstat_moments> m; // C order of shape
};
void register_moments_array(py::module_ &mod);
// The array inside a Python MomentsArray, or nullptr if obj is not one.
const MomentsArray *as_moments_array(py::handle obj);
// One test per pixel of x (and y, same number of pixels); the BatchResult
// of `shape`, as run_rows returns it.
py::object run_moments_rows(const TestArgs &a, const mcstat_moments *x, const mcstat_moments *y, size_t rows,
                            const std::vector<py::ssize_t> &shape);
// t_test / var_test when x or y is a MomentsArray (the other a MomentsArray
// of the same shape or a Moments, compared with every pixel).
py::object test_moments_array(const TestArgs &a, py::handle x, py::handle y);

} // namespace mcs
