// stream.cpp - mcstat.Stream: libmcstat's mcstat_stream, the buffered
// accumulator a renderer keeps per thread, with its two checks.
//
// What it adds over Moments: NaN and infinities are counted instead of
// refused (a check on a stream that saw one fails with NonFiniteError, so a
// renderer can keep going and report at the end of the frame), and the
// checks check_mean (with a tolerance: two one-sided t tests) and check_var
// (variance below a bound) are one call each.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <memory>
#include <string>

namespace mcs {

namespace {

struct Stream {
    mcstat_stream s;
    Stream()
    {
        if (mcstat_stream_init(&s))
            throw_status(MCSTAT_EINVAL, "stream");
    }
};

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

void push_values(Stream &st, py::handle values)
{
    carray a = as_contiguous_array(values, "values");
    const double *x = a.data();
    size_t n = static_cast<size_t>(a.size());
    auto loop = [&]() {
        for (size_t i = 0; i < n; i++)
            mcstat_stream_add(&st.s, x[i]);
    };
    if (n >= GIL_RELEASE_MIN) {
        py::gil_scoped_release nogil;
        loop();
    } else {
        loop();
    }
    // mcstat_stream_add drops the flush's status: a count past 2^64 - 1 is
    // recorded in n_overflow and every check reports it
}

// The number of finite values (buffered ones may include non-finite ones).
uint64_t finite_n(const Stream &st)
{
    mcstat_moments m;
    int rc = mcstat_stream_moments(&st.s, &m);
    if (rc)
        throw_status(rc, "stream moments");
    return m.n;
}

py::object moments_of(const Stream &st)
{
    mcstat_moments m;
    int rc = mcstat_stream_moments(&st.s, &m);
    if (rc)
        throw_status(rc, "stream moments");
    return py::cast(Moments{m});
}

} // namespace

const mcstat_stream *as_stream(py::handle obj)
{
    static py::handle type = py::type::of<Stream>();
    if (!PyObject_TypeCheck(obj.ptr(), reinterpret_cast<PyTypeObject *>(type.ptr())))
        return nullptr;
    return &obj.cast<const Stream &>().s;
}

void register_stream(py::module_ &mod)
{
    py::class_<Stream>(mod, "Stream", R"doc(
A renderer's per-thread accumulator with its checks (libmcstat's
``mcstat_stream``; mcstat.h, "Buffered per-thread accumulator").

Values are buffered and added to a `Moments` 492 at a time, giving exactly
the moments ``Moments().push(values)`` gives.  Unlike `Moments`, NaN and
infinities are not refused but counted (`n_nonfinite`) and left out; a
check on a stream that has seen one raises `NonFiniteError`.  Merge the
threads' streams at the end of a frame, then check:

>>> s = mcstat.Stream().push(radiance_samples)
>>> s.check_mean(reference, tolerance=1e-3).reject   # the check failed
>>> s.check_var(bound).reject

Not picklable; ship ``s.moments().to_bytes()`` instead.)doc")
        .def(py::init<>())
        .def(
            "push",
            [](Stream &st, py::handle values) -> Stream & {
                push_values(st, values);
                return st;
            },
            py::arg("values"), py::return_value_policy::reference_internal,
            "Adds a value or an array of values (any shape, read in C order); returns self.")
        .def(
            "flush",
            [](Stream &st) -> Stream & {
                int rc = mcstat_stream_flush(&st.s);
                if (rc)
                    throw_status(rc, "the count would pass 2**64 - 1 (values left out, counted in n_overflow)");
                return st;
            },
            py::return_value_policy::reference_internal,
            "Adds the buffered values to the moments now (a check does not need it); returns self.")
        .def(
            "merge",
            [](Stream &st, const Stream &other) -> Stream & {
                int rc = mcstat_stream_merge(&st.s, &other.s);
                if (rc)
                    throw_status(rc, "merging streams");
                return st;
            },
            py::arg("other"), py::return_value_policy::reference_internal,
            "Adds another stream's values (moments, buffer and non-finite count) to this one; returns self.")
        .def("moments", &moments_of, "The `Moments` of every value seen so far (buffered ones included).")
        .def_property_readonly("n", &finite_n, "Number of finite values added.")
        .def_property_readonly(
            "n_nonfinite",
            [](const Stream &st) {
                uint64_t k = st.s.n_nonfinite; // counted at each flush; the buffer's not yet
                for (uint32_t i = 0; i < st.s.count; i++)
                    k += !std::isfinite(st.s.buf[i]);
                return k;
            },
            "NaN and infinite values seen (and left out).")
        .def_property_readonly("n_overflow", [](const Stream &st) { return st.s.n_overflow; },
                               "Values left out because the count would pass 2**64 - 1.")
        .def(
            "check_mean",
            [](const Stream &st, double reference, double tolerance, double alpha) {
                mcstat_result r;
                int rc = mcstat_stream_check_mean(&st.s, reference, tolerance, alpha, &r);
                if (rc)
                    throw_status(rc, rc == MCSTAT_ENONFINITE
                                         ? "the stream has seen NaN or infinite values"
                                         : "check_mean(reference=" + repr(py::float_(reference).ptr()) + ", tolerance=" +
                                               repr(py::float_(tolerance).ptr()) + ", alpha=" +
                                               repr(py::float_(alpha).ptr()) + ") on " +
                                               std::to_string(finite_n(st)) + " values");
                return make_result(r);
            },
            py::arg("reference"), py::kw_only(), py::arg("tolerance") = 0.0, py::arg("alpha") = 0.05,
            R"doc(Is the mean of the values `reference` (to within `tolerance`)?

tolerance 0: the two-sided one-sample t test of mean == reference.
tolerance > 0: H0 ``|mean - reference| <= tolerance``, as two one-sided t tests
at alpha/2 each; the result is the one with the smaller p-value (its
``alpha`` is alpha/2).  ``reject`` True means the check failed.  Raises
`NonFiniteError` if the stream has seen NaN or infinity,
`TooFewObservationsError` below 2 values, `InvalidArgumentError` for a
negative or non-finite tolerance or alpha outside (0, 1).)doc")
        .def(
            "check_var",
            [](const Stream &st, double bound, double alpha) {
                mcstat_result r;
                int rc = mcstat_stream_check_var(&st.s, bound, alpha, &r);
                if (rc)
                    throw_status(rc, rc == MCSTAT_ENONFINITE
                                         ? "the stream has seen NaN or infinite values"
                                         : "check_var(bound=" + repr(py::float_(bound).ptr()) + ", alpha=" +
                                               repr(py::float_(alpha).ptr()) + ") on " +
                                               std::to_string(finite_n(st)) + " values");
                return make_result(r);
            },
            py::arg("bound"), py::kw_only(), py::arg("alpha") = 0.05,
            R"doc(Is the variance of the values below `bound` (> 0)?

The one-sample chi-squared test of var == bound against var > bound;
``reject`` True (the variance is significantly above the bound) means the
check failed.  Errors as `check_mean`.)doc")
        .def("__repr__", [](const Stream &st) {
            return "Stream(n=" + std::to_string(finite_n(st)) +
                   ", n_nonfinite=" + std::to_string(st.s.n_nonfinite) + ")";
        });
}

} // namespace mcs
