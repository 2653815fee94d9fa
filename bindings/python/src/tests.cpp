// tests.cpp - t_test and var_test: argument parsing and the one-test path.
//
// These two are the calls people make in loops, so they are vectorcall
// (METH_FASTCALL) functions that parse their own arguments: a Welch test on
// 2 x 50 values spends about as long in this file as in libmcstat.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "docs.hpp"
#include "kwargs.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;
using farray = py::array_t<double, py::array::forcecast>;

struct Parsed {
    PyObject *x = nullptr, *y = nullptr;
    PyObject *null_value = nullptr; // mu / sigma2
    PyObject *ratio = nullptr;      // var_test only
    PyObject *alternative = nullptr, *alpha = nullptr, *axis = nullptr, *nan_policy = nullptr;
    PyObject *intervals = nullptr, *on_error = nullptr, *threads = nullptr;
    PyObject *equal_var = nullptr, *paired = nullptr; // t_test only
};

void parse(const char *fname, bool is_var, PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames,
           Parsed &p)
{
    // t_test's null value is mu; var_test's sigma2, and it has ratio too
    mcs_kwargs::parse(fname, args, nargs, kwnames, {{"x", &p.x}, {"y", &p.y}},
                      {{"alternative", &p.alternative}, {"alpha", &p.alpha},
                       {is_var ? "sigma2" : "mu", &p.null_value}, {is_var ? "ratio" : nullptr, &p.ratio},
                       {"axis", &p.axis}, {"nan_policy", &p.nan_policy}, {"intervals", &p.intervals},
                       {"on_error", &p.on_error}, {"threads", &p.threads},
                       {is_var ? nullptr : "equal_var", &p.equal_var},
                       {is_var ? nullptr : "paired", &p.paired}});
    if (!p.x)
        throw py::type_error(std::string(fname) + "() missing required argument 'x'");
    if (p.x == Py_None)
        throw py::type_error(std::string(fname) + "(): x must be array-like or an mcstat.Moments, not None");
    if (p.y == Py_None)
        p.y = nullptr;
}

void common_args(const Parsed &p, TestArgs &a)
{
    a.alternative = p.alternative ? parse_alternative(p.alternative) : MCSTAT_TWO_SIDED;
    a.alpha = p.alpha ? get_double(p.alpha, "alpha") : 0.05;
    if (!(a.alpha > 0.0 && a.alpha < 1.0))
        throw_invalid("alpha must be in (0, 1), got " + repr(p.alpha));
    a.axis = -1;
    if (p.axis) {
        long v = PyLong_AsLong(p.axis);
        if (v == -1 && PyErr_Occurred()) {
            PyErr_Clear();
            throw py::type_error("axis must be an int, got " + repr(p.axis));
        }
        a.axis = static_cast<int>(v);
    }
    a.threads = 0;
    if (p.threads && p.threads != Py_None) {
        long v = PyLong_AsLong(p.threads);
        if (v == -1 && PyErr_Occurred()) {
            PyErr_Clear();
            throw py::type_error("threads must be an int, got " + repr(p.threads));
        }
        if (v < 1 || v > 64)
            throw_invalid("threads must be in 1..64, got " + std::to_string(v));
        a.threads = static_cast<int>(v);
    }
    a.omit_nan = false;
    a.propagate_nan = false;
    if (p.nan_policy) {
        const char *s = get_str(p.nan_policy, "nan_policy");
        if (!std::strcmp(s, "omit"))
            a.omit_nan = true;
        else if (!std::strcmp(s, "propagate"))
            a.propagate_nan = true;
        else if (std::strcmp(s, "raise"))
            throw_invalid(std::string("nan_policy must be 'raise', 'omit' or 'propagate', got '") + s + "'");
    }
    a.intervals = true;
    if (p.intervals) {
        int t = PyObject_IsTrue(p.intervals);
        if (t < 0)
            throw py::error_already_set();
        a.intervals = t != 0;
    }
    a.errors_as_nan = false;
    if (p.on_error) {
        const char *s = get_str(p.on_error, "on_error");
        if (!std::strcmp(s, "nan"))
            a.errors_as_nan = true;
        else if (std::strcmp(s, "raise"))
            throw_invalid(std::string("on_error must be 'raise' or 'nan', got '") + s + "'");
    }
}

// Moments of a 1-D array-like (for a test that mixes an accumulator and an array).
mcstat_moments moments_of(py::handle obj, bool omit, const char *name)
{
    carray a = as_contiguous_array(obj, name);
    if (a.ndim() != 1)
        throw_invalid("an array tested against an mcstat.Moments must be 1-D, got " + std::to_string(a.ndim()) +
                      "-D");
    mcstat_moments m;
    mcstat_moments_init(&m);
    size_t n = static_cast<size_t>(a.size());
    int st;
    if (n >= GIL_RELEASE_MIN) {
        py::gil_scoped_release nogil;
        st = omit ? mcstat_moments_add_array_omit_nan(&m, a.data(), n, nullptr) : mcstat_moments_add_array(&m, a.data(), n);
    } else {
        st = omit ? mcstat_moments_add_array_omit_nan(&m, a.data(), n, nullptr) : mcstat_moments_add_array(&m, a.data(), n);
    }
    if (st)
        throw_status(st);
    return m;
}

bool truthy(PyObject *o)
{
    int t = PyObject_IsTrue(o);
    if (t < 0)
        throw py::error_already_set();
    return t != 0;
}

bool has_nan(const double *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (std::isnan(x[i]))
            return true;
    return false;
}

std::string sizes_detail(const TestArgs &a, size_t nx, size_t ny)
{
    if (a.kind == Kind::TP)
        return std::to_string(nx) + " pairs";
    bool two = a.kind != Kind::T1 && a.kind != Kind::V1;
    return two ? "x has " + std::to_string(nx) + " values, y has " + std::to_string(ny)
               : "x has " + std::to_string(nx) + " values";
}

int call_moments(const TestArgs &a, const mcstat_moments *mx, const mcstat_moments *my, mcstat_result *r)
{
    switch (a.kind) {
    case Kind::T1: return mcstat_t_test_1_moments(mx, a.null_value, a.alternative, a.alpha, r);
    case Kind::T2: return mcstat_t_test_2_moments(mx, my, a.null_value, a.alternative, a.alpha, r);
    case Kind::V1: return mcstat_var_test_1_moments(mx, a.null_value, a.alternative, a.alpha, r);
    case Kind::T2P: return mcstat_t_test_2_pooled_moments(mx, my, a.null_value, a.alternative, a.alpha, r);
    case Kind::V2: return mcstat_var_test_2_moments(mx, my, a.null_value, a.alternative, a.alpha, r);
    default: return MCSTAT_EINVAL; // the paired test needs the pairs (run() refuses accumulators)
    }
}

// The paired test on two 1-D arrays of equal length; nan_policy="omit"
// drops the pairs with NaN on either side (as SciPy's ttest_rel).
int call_paired(const TestArgs &a, const double *x, const double *y, size_t n, mcstat_result *r)
{
    if (!a.omit_nan || (!has_nan(x, n) && !has_nan(y, n)))
        return mcstat_t_test_paired(x, y, n, a.null_value, a.alternative, a.alpha, r);
    std::vector<double> kx, ky;
    kx.reserve(n);
    ky.reserve(n);
    for (size_t i = 0; i < n; i++)
        if (!std::isnan(x[i]) && !std::isnan(y[i])) {
            kx.push_back(x[i]);
            ky.push_back(y[i]);
        }
    return mcstat_t_test_paired(kx.data(), ky.data(), kx.size(), a.null_value, a.alternative, a.alpha, r);
}

int call_arrays(const TestArgs &a, const double *x, size_t nx, const double *y, size_t ny, mcstat_result *r)
{
    unsigned flags = (a.intervals ? 0u : MCSTAT_ROWS_NO_INTERVALS) | (a.omit_nan ? MCSTAT_ROWS_OMIT_NAN : 0u);
    if (!flags) // the plain array functions; a one-row matrix gives the same bits (rows.c)
        switch (a.kind) {
        case Kind::T1: return mcstat_t_test_1(x, nx, a.null_value, a.alternative, a.alpha, r);
        case Kind::T2: return mcstat_t_test_2(x, nx, y, ny, a.null_value, a.alternative, a.alpha, r);
        case Kind::V1: return mcstat_var_test_1(x, nx, a.null_value, a.alternative, a.alpha, r);
        case Kind::V2: return mcstat_var_test_2(x, nx, y, ny, a.null_value, a.alternative, a.alpha, r);
        default: break; // pooled and paired: below
        }
    // skipped intervals or NaN left out: only the matrix functions have the flags
    switch (a.kind) {
    case Kind::T1: return mcstat_t_test_1_matrix(x, nx, 0, 1, a.null_value, a.alternative, a.alpha, flags, r, nullptr);
    case Kind::T2:
        return mcstat_t_test_2_matrix(x, nx, 0, y, ny, 0, 1, a.null_value, a.alternative, a.alpha, flags, r, nullptr);
    case Kind::V1:
        return mcstat_var_test_1_matrix(x, nx, 0, 1, a.null_value, a.alternative, a.alpha, flags, r, nullptr);
    case Kind::V2:
        return mcstat_var_test_2_matrix(x, nx, 0, y, ny, 0, 1, a.null_value, a.alternative, a.alpha, flags, r,
                                      nullptr);
    case Kind::TP:
        return call_paired(a, x, y, nx, r);
    default: { // pooled: no matrix call; the accumulators, NaN omitted if asked
        if (!a.omit_nan)
            return mcstat_t_test_2_pooled(x, nx, y, ny, a.null_value, a.alternative, a.alpha, r);
        mcstat_moments mx, my;
        mcstat_moments_init(&mx);
        mcstat_moments_init(&my);
        int st = mcstat_moments_add_array_omit_nan(&mx, x, nx, nullptr);
        if (!st)
            st = mcstat_moments_add_array_omit_nan(&my, y, ny, nullptr);
        return st ? st : mcstat_t_test_2_pooled_moments(&mx, &my, a.null_value, a.alternative, a.alpha, r);
    }
    }
}


py::object run(const Parsed &p, TestArgs &a)
{
    bool two = p.y != nullptr;
    // Per-pixel accumulators: one test per pixel (moments_array.cpp).
    if (as_moments_array(p.x) || (two && as_moments_array(p.y))) {
        if (a.kind == Kind::TP)
            throw_invalid("paired=True needs the values of x and y (the pairs), not an mcstat.MomentsArray");
        return test_moments_array(a, p.x, two ? py::handle(p.y) : py::handle());
    }
    const mcstat_moments *mx = as_moments(p.x), *my = two ? as_moments(p.y) : nullptr;
    mcstat_result r;
    if (mx || my) { // accumulators (an array beside one is turned into moments)
        if (a.kind == Kind::TP)
            throw_invalid("paired=True needs the values of x and y (the pairs), not mcstat.Moments");
        mcstat_moments bx, by;
        // nan_policy="propagate": an array with NaN beside an accumulator
        // gives the NaN result; accumulators hold no NaN
        if (a.propagate_nan) {
            for (int k = 0; k < (two ? 2 : 1); k++) {
                PyObject *o = k ? p.y : p.x;
                if (as_moments(o))
                    continue;
                py::array v = as_contiguous_array(o, k ? "y" : "x");
                if (has_nan(static_cast<const double *>(v.data()), static_cast<size_t>(v.size())))
                    return make_result(nan_result(a, mx ? mx->n : static_cast<uint64_t>(k ? 0 : v.size()),
                                                  my ? my->n : static_cast<uint64_t>(k ? v.size() : 0)));
            }
        }
        if (!mx) {
            bx = moments_of(p.x, a.omit_nan, "x");
            mx = &bx;
        }
        if (two && !my) {
            by = moments_of(p.y, a.omit_nan, "y");
            my = &by;
        }
        int st = call_moments(a, mx, my, &r);
        if (st)
            throw_status(st, st == MCSTAT_ETOOFEW ? sizes_detail(a, mx->n, my ? my->n : 0) : "");
        return make_result(r);
    }
    // N-D input keeps its dtype (float32 is read as float32: run_rows)
    py::array rx = real_array(p.x, "x"), ry;
    if (two)
        ry = real_array(p.y, "y");
    if (rx.ndim() == 0 || (two && ry.ndim() == 0))
        throw_invalid("x and y must be at least 1-D arrays (got a scalar)");
    if (rx.ndim() > 1 || (two && ry.ndim() > 1))
        return run_rows(a, rx, ry, two);
    py::array xa = as_float_array(rx, "x"), ya;
    if (two)
        ya = as_float_array(ry, "y");
    if (a.axis != 0 && a.axis != -1)
        throw_invalid("axis " + std::to_string(a.axis) + " is out of range for 1-D input");
    // One test: contiguous float64 is read in place, anything else converted once.
    if (!(xa.flags() & py::array::c_style))
        xa = as_contiguous_array(xa, "x");
    if (two && !(ya.flags() & py::array::c_style))
        ya = as_contiguous_array(ya, "y");
    const double *x = static_cast<const double *>(xa.data()), *y = two ? static_cast<const double *>(ya.data()) : nullptr;
    size_t nx = static_cast<size_t>(xa.size()), ny = two ? static_cast<size_t>(ya.size()) : 0;
    if (a.kind == Kind::TP && nx != ny)
        throw_invalid("paired=True needs x and y of the same length (the pairs), got x with " + std::to_string(nx) +
                      " values and y with " + std::to_string(ny));
    // nan_policy="propagate" is decided here: libmcstat never returns NaN
    // with success, so NaN data get the NaN result without a call
    if (a.propagate_nan && (has_nan(x, nx) || (two && has_nan(y, ny))))
        return make_result(nan_result(a, nx, ny));
    int st;
    if (nx + ny >= GIL_RELEASE_MIN) {
        py::gil_scoped_release nogil;
        st = call_arrays(a, x, nx, y, ny, &r);
    } else {
        st = call_arrays(a, x, nx, y, ny, &r);
    }
    if (st)
        throw_status(st, st == MCSTAT_ETOOFEW ? sizes_detail(a, nx, ny) : "");
    return make_result(r);
}

PyObject *t_test(PyObject *, PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames)
{
    return guarded([&]() {
        Parsed p;
        parse("t_test", false, args, nargs, kwnames, p);
        TestArgs a;
        common_args(p, a);
        bool equal_var = p.equal_var && truthy(p.equal_var), paired = p.paired && truthy(p.paired);
        if (paired && equal_var)
            throw_invalid("paired=True and equal_var=True exclude each other: the paired test has one sample "
                          "of differences");
        if ((paired || equal_var) && !p.y)
            throw_invalid(std::string(paired ? "paired=True" : "equal_var=True") + " needs y (a second sample)");
        a.kind = paired ? Kind::TP : equal_var ? Kind::T2P : p.y ? Kind::T2 : Kind::T1;
        a.null_value = p.null_value ? get_double(p.null_value, "mu") : 0.0;
        if (!std::isfinite(a.null_value))
            throw_invalid("mu must be finite, got " + repr(p.null_value));
        return run(p, a);
    });
}

PyObject *var_test(PyObject *, PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames)
{
    return guarded([&]() {
        Parsed p;
        parse("var_test", true, args, nargs, kwnames, p);
        TestArgs a;
        common_args(p, a);
        if (p.y) {
            a.kind = Kind::V2;
            if (p.null_value && p.null_value != Py_None)
                throw_invalid("sigma2 is for the one-sample test; the two-sample F test takes ratio");
            a.null_value = p.ratio ? get_double(p.ratio, "ratio") : 1.0;
            if (!(a.null_value > 0.0 && std::isfinite(a.null_value)))
                throw_invalid("ratio must be positive and finite, got " + repr(p.ratio));
        } else {
            a.kind = Kind::V1;
            if (p.ratio)
                throw_invalid("ratio is for the two-sample F test; the one-sample test takes sigma2");
            if (!p.null_value || p.null_value == Py_None)
                throw_invalid("the one-sample variance test needs sigma2 (the variance under H0)");
            a.null_value = get_double(p.null_value, "sigma2");
            if (!(a.null_value > 0.0 && std::isfinite(a.null_value)))
                throw_invalid("sigma2 must be positive and finite, got " + repr(p.null_value));
        }
        return run(p, a);
    });
}

PyMethodDef methods[] = {
    {"t_test", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)(void)>(t_test)),
     METH_FASTCALL | METH_KEYWORDS, T_TEST_DOC},
    {"var_test", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)(void)>(var_test)),
     METH_FASTCALL | METH_KEYWORDS, VAR_TEST_DOC},
    {nullptr, nullptr, 0, nullptr}};

} // namespace

mcstat_result nan_result(const TestArgs &a, uint64_t nx, uint64_t ny)
{
    mcstat_result r;
    std::memset(&r, 0, sizeof r);
    switch (a.kind) {
    case Kind::T1: r.test = MCSTAT_TEST_T_1; break;
    case Kind::T2: r.test = MCSTAT_TEST_T_2; break;
    case Kind::T2P: r.test = MCSTAT_TEST_T_2_POOLED; break;
    case Kind::TP: r.test = MCSTAT_TEST_T_PAIRED; break;
    case Kind::V1: r.test = MCSTAT_TEST_VAR_1; break;
    case Kind::V2: r.test = MCSTAT_TEST_VAR_2; break;
    }
    r.method = MCSTAT_METHOD_ANALYTIC;
    r.alternative = a.alternative;
    r.alpha = a.alpha;
    r.null_value = a.null_value;
    r.n[0] = nx;
    r.n[1] = ny;
    r.statistic = r.df[0] = r.df[1] = r.p_value = r.p_value_se = NAN;
    r.conf_int[0] = r.conf_int[1] = r.estimate[0] = r.estimate[1] = NAN;
    r.critical[0] = r.critical[1] = r.std_error = NAN;
    return r;
}

std::string repr(PyObject *o)
{
    py::str s = py::repr(o);
    return s;
}

double get_double(PyObject *o, const char *name)
{
    double v = PyFloat_AsDouble(o);
    if (v == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        throw py::type_error(std::string(name) + " must be a real number, got " + repr(o));
    }
    return v;
}

const char *get_str(PyObject *o, const char *name)
{
    if (!PyUnicode_Check(o))
        throw py::type_error(std::string(name) + " must be a str, got " + repr(o));
    const char *s = PyUnicode_AsUTF8(o);
    if (!s)
        throw py::error_already_set();
    return s;
}

int parse_alternative(PyObject *o)
{
    const char *s = get_str(o, "alternative");
    int alternative;
    if (mcstat_alternative_parse(s, &alternative) != MCSTAT_OK)
        throw_invalid(std::string("alternative must be 'two-sided', 'less' or 'greater', got '") + s + "'");
    return alternative;
}

py::array as_float_array(py::handle obj, const char *name)
{
    py::array a = farray::ensure(real_array(obj, name));
    if (!a)
        throw py::type_error(std::string(name) + ": cannot convert " + repr(obj.ptr()) + " to a float64 array");
    return a;
}

py::array as_contiguous_array(py::handle obj, const char *name)
{
    py::array a = carray::ensure(real_array(obj, name));
    if (!a)
        throw py::type_error(std::string(name) + ": cannot convert " + repr(obj.ptr()) + " to a float64 array");
    return a;
}

void register_tests(py::module_ &mod)
{
    mod.def(
        "_alternative_code", [](py::handle name) { return parse_alternative(name.ptr()); }, py::arg("alternative"),
        "The integer of an alternative's name (mcstat_alternative_parse), for the Python modules.");
    for (PyMethodDef *d = methods; d->ml_name; d++) {
        // self = the module, as for any module function (inspect then drops $module)
        PyObject *f = PyCFunction_NewEx(d, mod.ptr(), mod.attr("__name__").ptr());
        if (!f)
            throw py::error_already_set();
        mod.add_object(d->ml_name, py::reinterpret_steal<py::object>(f));
    }
    // The same conversions for the Python layer (mcstat.diagnostics).
    mod.def(
        "_real_array", [](py::handle obj, const std::string &name) { return real_array(obj, name.c_str()); },
        py::arg("obj"), py::arg("name"), "obj as an array, TypeError unless its values are real (float, int, bool).");
    mod.def(
        "_float_array",
        [](py::handle obj, const std::string &name) { return as_contiguous_array(obj, name.c_str()); },
        py::arg("obj"), py::arg("name"), "obj as a C-contiguous float64 array (the checks of _real_array).");
}

} // namespace mcs
