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
    mcs::register_diagnostics(mod); // issue 9
    mcs::register_chisq(mod); // chi-squared goodness of fit (issue 9)

    mod.def("set_num_threads", &mcs::set_num_threads, py::arg("n"),
            R"doc(Sets the number of threads for row-wise tests (0 = the default).

The default is the MCSTAT_NUM_THREADS environment variable, else the number
of CPUs.  Results do not depend on it.)doc");
    mod.def("get_num_threads", &mcs::num_threads, "The number of threads row-wise tests use.");
    mod.def("strerror", &mcstat_strerror, py::arg("status"), "libmcstat's sentence for a status code.");
    mod.attr("__libmcstat_version__") = mcstat_version();

    // GSL's default error handler aborts the process.  libmcstat never
    // reaches it (arguments are validated before GSL is called), but other
    // code in this Python process might call GSL: turn the abort off only if
    // nobody installed a handler of their own (mcstat.h, "GSL's error
    // handler").  gsl_handler_was_default records what happened.
    mod.attr("gsl_handler_was_default") = py::bool_(mcstat_gsl_handler_off_if_default() != 0);
}
