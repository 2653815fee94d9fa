// moments.cpp - mcstat.Moments (the streaming accumulator) and batch_means.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

bool parse_omit(const std::string &nan_policy)
{
    if (nan_policy == "raise")
        return false;
    if (nan_policy == "omit")
        return true;
    throw_invalid("nan_policy must be 'raise' or 'omit', got '" + nan_policy + "'");
}

// Adds values to m: exactly mcstat_moments_add_array on a fresh accumulator,
// merged into m on success (m is untouched on error).  The loop runs
// without the GIL, on a local accumulator, so no other thread sees m half
// updated.
void push_values(mcstat_moments &m, py::handle values, bool omit)
{
    if (values.is_none())
        throw py::type_error("Moments.push() needs numbers, not None");
    carray a = as_contiguous_array(values, "values");
    const double *p = a.data();
    size_t n = static_cast<size_t>(a.size());
    mcstat_moments local;
    mcstat_moments_init(&local);
    int st;
    if (n >= GIL_RELEASE_MIN) {
        py::gil_scoped_release nogil;
        st = omit ? mcstat_moments_add_array_omit_nan(&local, p, n, nullptr) : mcstat_moments_add_array(&local, p, n);
    } else {
        st = omit ? mcstat_moments_add_array_omit_nan(&local, p, n, nullptr) : mcstat_moments_add_array(&local, p, n);
    }
    if (st)
        throw_status(st);
    st = mcstat_moments_merge(&m, &local);
    if (st)
        throw_status(st);
}

double nan_if_empty(const mcstat_moments &m, double v) { return m.n == 0 ? NAN : v; }

py::bytes to_bytes(const Moments &s)
{
    unsigned char buf[MCSTAT_MOMENTS_BYTES];
    int st = mcstat_moments_to_bytes(&s.m, buf, sizeof buf);
    if (st)
        throw_status(st);
    return py::bytes(reinterpret_cast<const char *>(buf), sizeof buf);
}

Moments from_bytes(py::handle data)
{
    Py_buffer view;
    if (PyObject_GetBuffer(data.ptr(), &view, PyBUF_SIMPLE) != 0)
        throw py::error_already_set();
    Moments out;
    int st = mcstat_moments_from_bytes(static_cast<const unsigned char *>(view.buf), static_cast<size_t>(view.len),
                                       &out.m);
    size_t len = static_cast<size_t>(view.len);
    PyBuffer_Release(&view);
    if (st) {
        char detail[96];
        std::snprintf(detail, sizeof detail, "%zu bytes given; an mcstat.Moments is %u bytes", len,
                      MCSTAT_MOMENTS_BYTES);
        throw_status(st, st == MCSTAT_ECORRUPT && len != MCSTAT_MOMENTS_BYTES ? detail : "");
    }
    return out;
}

// Means of consecutive batches of k values along the last axis of a
// C-contiguous array (rows of n values): out has n / k per row.
void batch_means_rows(const double *x, size_t rows, size_t n, size_t k, double *out, int *status)
{
    size_t nb = n / k;
    *status = MCSTAT_OK;
    for (size_t r = 0; r < rows; r++) {
        for (size_t b = 0; b < nb; b++) {
            mcstat_moments m;
            mcstat_moments_init(&m);
            int st = mcstat_moments_add_array(&m, x + r * n + b * k, k);
            if (st) {
                *status = st;
                return;
            }
            out[r * nb + b] = mcstat_moments_mean(&m);
        }
    }
}

} // namespace

const mcstat_moments *as_moments(py::handle obj)
{
    static py::handle type = py::type::of<Moments>();
    if (Py_TYPE(obj.ptr()) != reinterpret_cast<PyTypeObject *>(type.ptr()) &&
        !PyObject_TypeCheck(obj.ptr(), reinterpret_cast<PyTypeObject *>(type.ptr())))
        return nullptr;
    return &obj.cast<const Moments &>().m;
}

void register_moments(py::module_ &mod)
{
    py::class_<Moments>(mod, "Moments", R"doc(
Streaming, mergeable moments of a sample (libmcstat's ``mcstat_moments``).

Push values as they come, merge accumulators from threads, processes or
machines, and pass the accumulator to `t_test` or `var_test` in place of
an array.  Means are kept to about 32 digits and sums are scaled, so data
such as 1e9 + 1e-3 noise or values near 1e300 keep their digits.

Parameters
----------
values : array_like, optional
    Initial values (any shape; all values are used).
nan_policy : {"raise", "omit"}, optional
    What `push` does with NaN: raise `NonFiniteError`, or skip it.
    Infinite values always raise.

Examples
--------
>>> m = mcstat.Moments()
>>> m.push([1.0, 2.0, 4.0])
Moments(n=3, mean=2.33333, sd=1.52753)
>>> m2 = mcstat.Moments.from_bytes(m.to_bytes())   # 96 bytes, versioned
)doc")
        .def(py::init([](py::handle values, const std::string &nan_policy) {
                 Moments s;
                 mcstat_moments_init(&s.m);
                 if (!values.is_none())
                     push_values(s.m, values, parse_omit(nan_policy));
                 return s;
             }),
             py::arg("values") = py::none(), py::kw_only(), py::arg("nan_policy") = "raise")
        .def(
            "push",
            [](py::object self, py::handle values, const std::string &nan_policy) {
                Moments &s = self.cast<Moments &>();
                bool omit = parse_omit(nan_policy);
                if (PyFloat_Check(values.ptr()) || PyLong_Check(values.ptr())) {
                    double v = values.cast<double>();
                    if (std::isnan(v) && omit)
                        return self;
                    int st = mcstat_moments_add(&s.m, v);
                    if (st)
                        throw_status(st);
                } else {
                    push_values(s.m, values, omit);
                }
                return self;
            },
            py::arg("values"), py::kw_only(), py::arg("nan_policy") = "raise",
            R"doc(Adds a value or an array of values (any shape); returns self.

Raises `NonFiniteError` (the accumulator unchanged) for infinite values and,
unless ``nan_policy="omit"``, for NaN.)doc")
        .def(
            "merge",
            [](py::object self, const Moments &other) {
                Moments &s = self.cast<Moments &>();
                int st = mcstat_moments_merge(&s.m, &other.m);
                if (st)
                    throw_status(st);
                return self;
            },
            py::arg("other"), "Merges `other` into this accumulator (exactly, Chan/Pebay); returns self.")
        .def("__iadd__", [](py::object self, const Moments &other) {
            Moments &s = self.cast<Moments &>();
            int st = mcstat_moments_merge(&s.m, &other.m);
            if (st)
                throw_status(st);
            return self;
        })
        .def("__add__", [](const Moments &a, const Moments &b) {
            Moments out = a;
            int st = mcstat_moments_merge(&out.m, &b.m);
            if (st)
                throw_status(st);
            return out;
        })
        .def_property_readonly("n", [](const Moments &s) { return s.m.n; }, "Number of values.")
        .def_property_readonly("mean", [](const Moments &s) { return mcstat_moments_mean(&s.m); },
                               "Mean (NaN when empty).")
        .def_property_readonly("var", [](const Moments &s) { return mcstat_moments_var(&s.m); },
                               "Sample variance with n - 1 (NaN when n < 2).")
        .def_property_readonly("sd", [](const Moments &s) { return mcstat_moments_sd(&s.m); },
                               "Sample standard deviation (NaN when n < 2).")
        .def_property_readonly("std", [](const Moments &s) { return mcstat_moments_sd(&s.m); },
                               "Alias of `sd`.")
        .def_property_readonly("skewness", [](const Moments &s) { return mcstat_moments_skewness(&s.m); },
                               "g1 = sqrt(n) M3 / M2^1.5 (NaN when undefined).")
        .def_property_readonly("kurtosis", [](const Moments &s) { return mcstat_moments_kurtosis(&s.m); },
                               "Excess kurtosis g2 = n M4 / M2^2 - 3 (NaN when undefined).")
        .def_property_readonly("min", [](const Moments &s) { return nan_if_empty(s.m, s.m.min); },
                               "Smallest value (NaN when empty).")
        .def_property_readonly("max", [](const Moments &s) { return nan_if_empty(s.m, s.m.max); },
                               "Largest value (NaN when empty).")
        .def("copy", [](const Moments &s) { return s; }, "An independent copy.")
        .def("__copy__", [](const Moments &s) { return s; })
        .def("__deepcopy__", [](const Moments &s, py::handle) { return s; })
        .def("to_bytes", &to_bytes, R"doc(The accumulator as 96 bytes.

libmcstat's versioned, little-endian format with a checksum: the same on
every machine and in every language binding.)doc")
        .def_static("from_bytes", &from_bytes, py::arg("data"), R"doc(An accumulator from `to_bytes` output.

Raises `CorruptDataError` for bytes that are truncated, corrupt, of another
format version or internally inconsistent.)doc")
        .def("__reduce__", [](py::object self) {
            return py::make_tuple(py::module_::import("mcstat._core").attr("_moments_from_bytes"),
                                  py::make_tuple(to_bytes(self.cast<const Moments &>())));
        })
        .def("__eq__", [](const Moments &a, py::handle b) -> py::object {
            const mcstat_moments *mb = as_moments(b);
            if (!mb)
                return py::reinterpret_borrow<py::object>(Py_NotImplemented);
            Moments bb{*mb};
            return py::bool_(static_cast<std::string>(to_bytes(a)) == static_cast<std::string>(to_bytes(bb)));
        })
        .def("__repr__", [](const Moments &s) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "Moments(n=%llu, mean=%.6g, sd=%.6g)", (unsigned long long)s.m.n,
                          mcstat_moments_mean(&s.m), mcstat_moments_sd(&s.m));
            return std::string(buf);
        });
    py::setattr(mod.attr("Moments"), "__hash__", py::none());
    mod.def("_moments_from_bytes", &from_bytes, py::arg("data"), "Moments.from_bytes (for pickle).");

    mod.def(
        "batch_means",
        [](py::handle x, long long k, int axis, const std::string &remainder) {
            if (x.is_none())
                throw py::type_error("batch_means() needs an array, not None");
            if (k < 1)
                throw_invalid("k must be a positive integer, got " + std::to_string(k));
            if (remainder != "drop" && remainder != "raise")
                throw_invalid("remainder must be 'drop' or 'raise', got '" + remainder + "'");
            py::array a = as_float_array(x, "x");
            int nd = static_cast<int>(a.ndim());
            if (nd < 1)
                throw_invalid("x must be at least 1-D");
            if (axis < -nd || axis >= nd)
                throw_invalid("axis " + std::to_string(axis) + " is out of range for " + std::to_string(nd) +
                              "-D input");
            if (axis < 0)
                axis += nd;
            py::module_ np = py::module_::import("numpy");
            carray c = as_contiguous_array(np.attr("moveaxis")(a, axis, -1), "x");
            size_t n = static_cast<size_t>(c.shape(nd - 1));
            size_t rows = n ? static_cast<size_t>(c.size()) / n : 0;
            if (remainder == "raise" && n % static_cast<size_t>(k) != 0)
                throw_invalid(std::to_string(n) + " values do not split into batches of " + std::to_string(k));
            std::vector<py::ssize_t> shape(c.shape(), c.shape() + nd);
            shape[nd - 1] = static_cast<py::ssize_t>(n / static_cast<size_t>(k));
            py::array_t<double> out(shape);
            int st;
            {
                py::gil_scoped_release nogil;
                batch_means_rows(c.data(), rows, n, static_cast<size_t>(k), out.mutable_data(), &st);
            }
            if (st)
                throw_status(st);
            return py::object(np.attr("moveaxis")(out, -1, axis));
        },
        py::arg("x"), py::arg("k"), py::kw_only(), py::arg("axis") = -1, py::arg("remainder") = "drop",
        R"doc(Secondary estimates: the means of consecutive batches of `k` primary estimates.

The tests assume normal samples; means of k primary estimates are close to
normal even when the primary estimates are not (ERRATA 7).

Parameters
----------
x : array_like
    Primary estimates; batches are taken along `axis`.
k : int
    Batch size (>= 1).
axis : int, optional
    The axis holding the estimates (default: the last).
remainder : {"drop", "raise"}, optional
    With n values along `axis`, the result has n // k batch means and the
    last n % k values are dropped ("drop", the default), or
    `InvalidArgumentError` is raised unless k divides n ("raise").

Returns
-------
ndarray
    float64, the shape of `x` with n // k along `axis`.

Raises
------
NonFiniteError
    NaN or infinite values in `x`.)doc");
}

} // namespace mcs
