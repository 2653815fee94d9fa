// escalation.cpp - mcstat.Escalation: libmcstat's two-stage test
// (mcstat_escalation_design, mcstat_escalation_decide), which a test suite
// runs instead of rerunning a suspicious statistical test.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>

namespace mcs {

namespace {

const char *decision_name(int d)
{
    return d == MCSTAT_ESCALATION_REJECT ? "reject" : d == MCSTAT_ESCALATION_CONTINUE ? "continue" : "pass";
}

std::string num(double v)
{
    return repr(py::float_(v).ptr());
}

mcstat_escalation design(double alpha, double share1, double alpha0)
{
    // the C call says only EINVAL: name the argument that made it
    if (!(alpha > 0.0 && alpha < 1.0))
        throw_invalid("alpha must be in (0, 1), got " + num(alpha));
    if (!(share1 > 0.0 && share1 < 1.0))
        throw_invalid("share1 must be in (0, 1), got " + num(share1));
    if (!(alpha0 > share1 * alpha && alpha0 <= 1.0))
        throw_invalid("alpha0 must be in (alpha1, 1] = (" + num(share1 * alpha) + ", 1], got " + num(alpha0));
    mcstat_escalation d;
    int st = mcstat_escalation_design(alpha, share1, alpha0, &d);
    if (st == MCSTAT_EINVAL)
        throw_invalid("alpha0 " + num(alpha0) + " leaves stage 2 too narrow a band to spend the rest of alpha " +
                      "(it needs alpha0 >= alpha1 e^((1 - share1) / share1) = " +
                      num(share1 * alpha * std::exp((1.0 - share1) / share1)) + ")");
    if (st != MCSTAT_OK)
        throw_status(st, "Escalation");
    return d;
}

const char *DOC = R"doc(Escalation(alpha, share1=0.5, alpha0=0.05)

A two-stage test (Bauer & Koehne 1994) to run instead of rerunning a
suspicious statistical test: stage 1's p-value p1 rejects when
p1 <= alpha1 = share1 * alpha, passes when p1 > alpha0, and in between the
test continues on fresh, independent samples (stage 2, of any size chosen
after stage 1) whose p-value p2 rejects when p1 * p2 <= c, with
c = (alpha - alpha1) / ln(alpha0 / alpha1).  The whole test has level alpha
for valid p-values (uniform or super-uniform under H0); a correct test
escalates with probability alpha0 - alpha1.  mcstat.h, "Escalation instead
of reruns".

Raises InvalidArgumentError naming the argument outside its range, or
when alpha0 leaves stage 2 too narrow a band (c would exceed alpha1).
)doc";

} // namespace

void register_escalation(py::module_ &mod)
{
    py::class_<mcstat_escalation>(mod, "Escalation", DOC)
        .def(py::init(&design), py::arg("alpha"), py::arg("share1") = 0.5, py::arg("alpha0") = 0.05)
        .def_property_readonly("alpha", [](const mcstat_escalation &d) { return d.alpha; },
                               "The level of the whole two-stage test.")
        .def_property_readonly("alpha1", [](const mcstat_escalation &d) { return d.alpha1; },
                               "Stage 1 rejects when p1 <= alpha1.")
        .def_property_readonly("alpha0", [](const mcstat_escalation &d) { return d.alpha0; },
                               "Stage 1 passes when p1 > alpha0 (escalates in between).")
        .def_property_readonly("c", [](const mcstat_escalation &d) { return d.c; },
                               "Stage 2 rejects when p1 * p2 <= c.")
        .def(
            "decide",
            [](const mcstat_escalation &d, double p1, py::object p2) {
                double q = p2.is_none() ? NAN : get_double(p2.ptr(), "p2");
                if (!(p1 >= 0.0 && p1 <= 1.0))
                    throw_invalid("p1 must be in [0, 1], got " + num(p1));
                if (!p2.is_none() && !(q >= 0.0 && q <= 1.0))
                    throw_invalid("p2 must be in [0, 1] or None, got " + num(q));
                int dec;
                int st = mcstat_escalation_decide(&d, p1, q, &dec);
                if (st == MCSTAT_EINVAL && !std::isnan(q))
                    throw_invalid("p2 given, but stage 1's p1 = " + num(p1) + " already decided (" +
                                  decision_name(p1 <= d.alpha1 ? MCSTAT_ESCALATION_REJECT
                                                               : MCSTAT_ESCALATION_PASS) +
                                  ")");
                if (st != MCSTAT_OK)
                    throw_status(st, "Escalation.decide");
                return std::string(decision_name(dec));
            },
            py::arg("p1"), py::arg("p2") = py::none(),
            "'reject', 'pass' or 'continue' (stage 1 inconclusive: run stage 2 and call again with p2).")
        .def("__repr__", [](const mcstat_escalation &d) {
            return "Escalation(alpha=" + num(d.alpha) + ", alpha1=" + num(d.alpha1) + ", alpha0=" + num(d.alpha0) +
                   ", c=" + num(d.c) + ")";
        });
}

} // namespace mcs
