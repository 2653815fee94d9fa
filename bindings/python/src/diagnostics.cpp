// diagnostics.cpp - the exact binomial test, the battery meta-test and the
// estimator diagnostics: argument conversion only; the numbers
// are libmcstat's (binom_test.c, diagnose.c).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <string>

namespace mcs {

namespace {

uint64_t count(py::handle o, const char *name)
{
    if (PyBool_Check(o.ptr()) || !PyIndex_Check(o.ptr()))
        throw py::type_error(std::string(name) + " must be an integer, not " + repr(o.ptr()));
    py::int_ v = py::reinterpret_steal<py::int_>(PyNumber_Index(o.ptr()));
    if (!v)
        throw py::error_already_set();
    if (PyObject_RichCompareBool(v.ptr(), py::int_(0).ptr(), Py_LT) == 1)
        throw_invalid(std::string(name) + " must be >= 0, got " + repr(o.ptr()));
    unsigned long long u = PyLong_AsUnsignedLongLong(v.ptr());
    if (u == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
        PyErr_Clear();
        PyErr_SetString(PyExc_OverflowError,
                        (std::string(name) + " must be below 2**64, got " + repr(o.ptr())).c_str());
        throw py::error_already_set();
    }
    return static_cast<uint64_t>(u);
}

} // namespace

void register_diagnostics(py::module_ &mod)
{
    mod.def(
        "_binom_test",
        [](py::object x, py::object n, double p, py::handle alternative, double alpha) {
            uint64_t xx = count(x, "x"), nn = count(n, "n");
            mcstat_result r;
            int st = mcstat_binom_test(xx, nn, p, parse_alternative(alternative.ptr()), alpha, &r);
            if (st == MCSTAT_EINVAL) {
                // in the order of mcstat_binom_test's checks
                if (!(alpha > 0.0 && alpha < 1.0))
                    throw_invalid("alpha must be in (0, 1), got " + repr(py::float_(alpha).ptr()));
                if (!(p >= 0.0 && p <= 1.0))
                    throw_invalid("p must be in [0, 1], got " + repr(py::float_(p).ptr()));
                throw_invalid("x (successes) must be at most n (trials), got x=" + std::to_string(xx) +
                              ", n=" + std::to_string(nn));
            }
            if (st == MCSTAT_ETOOFEW)
                throw_status(st, "binom_test needs n >= 1 trials, got n=0");
            if (st == MCSTAT_ETOOBIG)
                throw_status(st, "n=" + std::to_string(nn) + " trials is beyond the exact test's range (2**53)");
            if (st)
                throw_status(st);
            return make_result(r);
        },
        py::arg("x"), py::arg("n"), py::arg("p"), py::arg("alternative"), py::arg("alpha"));

    mod.def(
        "_battery_test",
        [](py::object rejections, py::object k, double level, py::handle alternative, double alpha) {
            uint64_t r = count(rejections, "rejections"), kk = count(k, "n");
            mcstat_result res;
            int st = mcstat_battery_test(r, kk, level, parse_alternative(alternative.ptr()), alpha, &res);
            if (st)
                throw_status(st, "battery_test(" + std::to_string(r) + " rejections, n=" + std::to_string(kk) + ")");
            return make_result(res);
        },
        py::arg("rejections"), py::arg("k"), py::arg("level"), py::arg("alternative"), py::arg("alpha"));

    mod.def(
        "_tail_index",
        [](py::object x, py::object tail_k) {
            py::array_t<double, py::array::c_style | py::array::forcecast> a = as_contiguous_array(x, "x");
            if (a.ndim() != 1)
                throw_invalid("tail_index: x must be one-dimensional, got " + std::to_string(a.ndim()) + " dimensions");
            uint64_t tk = count(tail_k, "tail_k");
            double index[2];
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcstat_diag_tail_index(a.data(), static_cast<size_t>(a.size()), static_cast<size_t>(tk), index);
            }
            if (st)
                throw_status(st, "tail_index of " + std::to_string(a.size()) + " values" +
                                     (tk ? " with tail_k=" + std::to_string(tk) : std::string()));
            return py::make_tuple(index[0], index[1]);
        },
        py::arg("x"), py::arg("tail_k"));

    mod.def(
        "_battery_test_pvalues",
        [](py::object pv, double level, py::handle alternative, double alpha) {
            py::array a = as_contiguous_array(pv, "tests");
            mcstat_result r;
            int st = mcstat_battery_test_pvalues(static_cast<const double *>(a.data()), static_cast<size_t>(a.size()),
                                                 level, parse_alternative(alternative.ptr()), alpha, &r);
            if (st == MCSTAT_EINVAL && !(level > 0.0 && level < 1.0))
                throw_invalid("battery_test: the tests' level must be in (0, 1), got " +
                              repr(py::float_(level).ptr()));
            if (st)
                throw_status(st);
            return make_result(r);
        },
        py::arg("pvalues"), py::arg("level"), py::arg("alternative"), py::arg("alpha"));

    mod.def(
        "_diagnose",
        [](py::object x, uint64_t k, uint64_t m, double alpha, double tolerance, uint64_t tail_k,
           double tail_threshold) {
            py::array a = as_contiguous_array(x, "x");
            if (a.ndim() != 1)
                throw_invalid("diagnose: x must be one-dimensional, got " + std::to_string(a.ndim()) + " dimensions");
            mcstat_diag_options o;
            mcstat_diag_options_init(&o);
            o.k = k;
            o.m = m;
            o.alpha = alpha;
            o.tolerance = tolerance;
            o.tail_k = tail_k;
            o.tail_threshold = tail_threshold;
            mcstat_diagnostics d;
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcstat_diag_compute(static_cast<const double *>(a.data()), static_cast<size_t>(a.size()), &o, &d);
            }
            if (st == MCSTAT_EINVAL) {
                // in the order of mcstat_diag_compute's checks
                if (!(alpha > 0.0 && alpha < 1.0))
                    throw_invalid("diagnose: alpha must be in (0, 1), got " + repr(py::float_(alpha).ptr()));
                if (!(tolerance > 0.0 && tolerance < 1.0))
                    throw_invalid("diagnose: tolerance must be in (0, 1), got " + repr(py::float_(tolerance).ptr()));
                if (!(tail_threshold > 0.0))
                    throw_invalid("diagnose: tail_threshold must be > 0, got " +
                                  repr(py::float_(tail_threshold).ptr()));
                if (k > static_cast<uint64_t>(a.size()))
                    throw_invalid("diagnose: k (the batch size) must be at most the " + std::to_string(a.size()) +
                                  " values of x, got " + std::to_string(k));
                throw_status(st);
            }
            if (st == MCSTAT_ETOOFEW)
                throw_status(st, "diagnose needs at least 2 tail_k + 2 values of x (22 with the default tail_k, "
                                 "Hill's order statistics per tail) and m >= 2 batch means; x has " +
                                     std::to_string(a.size()) + " values" +
                                     (k ? ", k = " + std::to_string(k) : std::string()) +
                                     (m ? ", m = " + std::to_string(m) : std::string()) +
                                     (tail_k ? ", tail_k = " + std::to_string(tail_k) : std::string()));
            if (st == MCSTAT_EDEGENERATE)
                throw_status(st, "x is constant");
            if (st)
                throw_status(st);
            py::dict out;
            out["n"] = d.n;
            out["mean"] = d.mean;
            out["sd"] = d.sd;
            out["skewness"] = d.skewness;
            out["skewness_se"] = d.skewness_se;
            out["kurtosis"] = d.kurtosis;
            out["kurtosis_se"] = d.kurtosis_se;
            out["tail_k"] = d.tail_k;
            out["tail_index"] = py::make_tuple(d.tail_index[0], d.tail_index[1]);
            out["tail_index_se"] = py::make_tuple(d.tail_index_se[0], d.tail_index_se[1]);
            out["max_share"] = d.max_share;
            out["heavy_tail"] = d.heavy_tail != 0;
            out["k"] = d.k;
            out["m"] = d.m;
            out["t_size"] = py::make_tuple(d.t_size[0], d.t_size[1]);
            out["recommended_k"] = d.recommended_k;
            out["alpha"] = d.alpha;
            out["tolerance"] = d.tolerance;
            return out;
        },
        py::arg("x"), py::arg("k"), py::arg("m"), py::arg("alpha"), py::arg("tolerance"), py::arg("tail_k"),
        py::arg("tail_threshold"));

    mod.def(
        "_t_size_edgeworth",
        [](double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha) {
            double s[2];
            int st = mcstat_diag_t_size(skewness, kurtosis, k, m, alpha, s);
            if (st == MCSTAT_ETOOFEW)
                throw_status(st, "t_size_edgeworth needs m >= 2 batch means, got m = " + std::to_string(m));
            if (st == MCSTAT_EINVAL)
                throw_invalid("t_size_edgeworth: skewness and kurtosis must be finite, kurtosis >= -2, "
                              "alpha in (0, 1) and k >= 1");
            if (st)
                throw_status(st);
            return py::make_tuple(s[0], s[1]);
        },
        py::arg("skewness"), py::arg("kurtosis"), py::arg("k"), py::arg("m"), py::arg("alpha"));

    mod.def(
        "_batch_size_recommend",
        [](double skewness, double kurtosis, uint64_t m, double alpha, double tolerance) {
            uint64_t k;
            int st = mcstat_diag_batch_size(skewness, kurtosis, m, alpha, tolerance, &k);
            if (st == MCSTAT_ETOOFEW)
                throw_status(st, "batch_size_recommend needs m >= 2 batch means, got m = " + std::to_string(m));
            if (st == MCSTAT_EINVAL)
                throw_invalid("batch_size_recommend: skewness and kurtosis must be finite, kurtosis >= -2, "
                              "alpha and tolerance in (0, 1)");
            if (st)
                throw_status(st);
            return k;
        },
        py::arg("skewness"), py::arg("kurtosis"), py::arg("m"), py::arg("alpha"), py::arg("tolerance"));
}

} // namespace mcs
