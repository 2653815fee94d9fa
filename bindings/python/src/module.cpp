// module.cpp - mcstat._core: the compiled half of the mcstat package.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

PYBIND11_MODULE(_core, mod)
{
    mod.doc() = "libmcstat bound for Python (use the mcstat package, not this module).";
    mcs::init_errors();
    mcs::register_result(mod);
    mcs::register_result_helpers(mod);
    mcs::register_moments(mod);
    mcs::register_tests(mod);
    mcs::register_ks(mod);
    mcs::register_moments_array(mod); // per-pixel accumulators
    mcs::register_power(mod); // equivalence (TOST), power and sample size
    mcs::register_diagnostics(mod);
    mcs::register_chisq(mod); // chi-squared goodness of fit
    mcs::register_efficiency(mod); // the ratio of two estimators' efficiencies
    mcs::register_p_adjust(mod);
    mcs::register_escalation(mod); // the two-stage test instead of reruns
    mcs::register_summary_rows(mod);
    mcs::register_pixels(mod); // Welch per pixel on seeds-major stacks
    mcs::register_check(mod); // renderer checks: BSDFs, emitters, warps
    mcs::register_distributions(mod); // t, chi-squared and F cdf and quantiles
    mcs::register_stream(mod); // mcstat.Stream, after Moments (it returns one)
    mcs::register_sequential(mod); // mcstat.SequentialTest

    mod.def(
        "set_num_threads",
        [](py::handle n) {
            if (PyBool_Check(n.ptr()) || !PyIndex_Check(n.ptr()))
                throw py::type_error("n must be an int, got " + mcs::repr(n.ptr()));
            py::int_ v = py::reinterpret_steal<py::int_>(PyNumber_Index(n.ptr()));
            int overflow = 0;
            long long t = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
            if (overflow || t < 0 || t > mcs::MAX_THREADS)
                mcs::throw_invalid("n must be 0 (the default) or a number of threads in 1.." +
                                   std::to_string(mcs::MAX_THREADS) + ", got " + mcs::repr(n.ptr()));
            mcs::set_num_threads(static_cast<int>(t));
        },
        py::arg("n"),
        R"doc(Sets the number of threads for row-wise tests: 1 to 1024, or 0 for the default.

The default is the MCSTAT_NUM_THREADS environment variable, else the number
of CPUs.  Results do not depend on it.  Raises `InvalidArgumentError` (a
ValueError) outside 0..1024.)doc");
    mod.def("get_num_threads", &mcs::num_threads, "The number of threads row-wise tests use.");
    mod.def("strerror", &mcstat_strerror, py::arg("status"), "libmcstat's sentence for a status code.");
    mod.def("_status_text", &mcs::status_text, py::arg("status"),
            "The sentence of a status as the exceptions word it (see errors.cpp).");
    mod.attr("__libmcstat_version__") = mcstat_version();
    // MAJOR * 10000 + MINOR * 100 + PATCH of the linked libmcstat
    mod.attr("__libmcstat_version_number__") = mcstat_version_number();

    // GSL's default error handler aborts the process.  libmcstat never
    // reaches it (arguments are validated before GSL is called), but other
    // code in this Python process might call GSL: turn the abort off only if
    // nobody installed a handler of their own (mcstat.h, "GSL's error
    // handler").  gsl_handler_was_default records what happened.
    mod.attr("gsl_handler_was_default") = py::bool_(mcstat_gsl_handler_off_if_default() != 0);
}
