// power.cpp - equivalence (TOST) and power / sample size: libmcstat's
// mcstat_equivalence_test_* and mcstat_power_* for mcstat._power, which
// wraps the dictionaries returned here in result objects.  Numerics,
// decisions and the R-style text are libmcstat's.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A 1-D array-like as a contiguous float64 array.
carray array_1d(py::handle obj, const char *name)
{
    if (obj.is_none())
        throw py::type_error(std::string(name) + " must be array-like or an mcstat.Moments, not None");
    carray a = as_contiguous_array(obj, name);
    if (a.ndim() != 1)
        throw_invalid(std::string("equivalence_test: ") + name + " must be 1-D, got " + std::to_string(a.ndim()) +
                      "-D");
    return a;
}

// An mcstat.Moments as it is, or the moments of a 1-D array-like.
mcstat_moments to_moments(py::handle obj, bool omit, const char *name)
{
    if (const mcstat_moments *m = as_moments(obj))
        return *m;
    carray a = array_1d(obj, name);
    mcstat_moments m;
    mcstat_moments_init(&m);
    size_t n = static_cast<size_t>(a.size());
    int st;
    {
        py::gil_scoped_release nogil;
        st = omit ? mcstat_moments_add_array_omit_nan(&m, a.data(), n, nullptr)
                  : mcstat_moments_add_array(&m, a.data(), n);
    }
    if (st)
        throw_status(st, std::string(name) + " has " + std::to_string(n) + " values");
    return m;
}

template <typename F> std::string format_with(F f)
{
    std::vector<char> buf(2048);
    size_t len = 0;
    int st = f(buf.data(), buf.size(), &len);
    if (st == MCSTAT_EBUFSIZE) {
        buf.resize(len + 1);
        st = f(buf.data(), buf.size(), &len);
    }
    if (st)
        throw_status(st, "formatting");
    return std::string(buf.data(), len);
}

py::dict equivalence(py::object x, py::object y, double mu0, double lower, double upper, double alpha, bool omit)
{
    if (!(alpha > 0.0 && alpha < 0.5))
        throw_invalid("alpha must be in (0, 0.5) for an equivalence test (its interval has level 1 - 2 alpha), got " +
                      std::to_string(alpha));
    if (!(std::isfinite(lower) && std::isfinite(upper) && lower < upper))
        throw_invalid("the margin's bounds must be finite with lower < upper, got (" + std::to_string(lower) + ", " +
                      std::to_string(upper) + ")");
    bool two = !y.is_none();
    mcstat_result r;
    int st;
    uint64_t nx, ny = 0;
    if (!omit && !as_moments(x) && !(two && as_moments(y))) {
        // arrays: libmcstat's array functions (the same moments as to_moments)
        carray ax = array_1d(x, "x"), ay;
        if (two)
            ay = array_1d(y, "y");
        nx = static_cast<uint64_t>(ax.size());
        ny = two ? static_cast<uint64_t>(ay.size()) : 0;
        py::gil_scoped_release nogil;
        st = two ? mcstat_equivalence_test_2(ax.data(), ax.size(), ay.data(), ay.size(), lower, upper, alpha, &r)
                 : mcstat_equivalence_test_1(ax.data(), ax.size(), mu0, lower, upper, alpha, &r);
    } else {
        mcstat_moments mx = to_moments(x, omit, "x"), my;
        if (two)
            my = to_moments(y, omit, "y");
        nx = mx.n;
        ny = two ? my.n : 0;
        st = two ? mcstat_equivalence_test_2_moments(&mx, &my, lower, upper, alpha, &r)
                 : mcstat_equivalence_test_1_moments(&mx, mu0, lower, upper, alpha, &r);
    }
    if (st)
        throw_status(st, two ? "x has " + std::to_string(nx) + " values, y has " + std::to_string(ny)
                             : "x has " + std::to_string(nx) + " values");
    py::dict d;
    d["two_sample"] = two;
    d["statistic"] = r.statistic;
    d["df"] = r.df[0];
    d["pvalue"] = r.p_value;
    d["statistics"] = py::make_tuple(r.tost_t_lower, r.tost_t_upper);
    d["pvalues"] = py::make_tuple(r.tost_p_lower, r.tost_p_upper);
    d["bounds"] = py::make_tuple(r.tost_lower, r.tost_upper);
    d["conf_int"] = py::make_tuple(r.conf_int[0], r.conf_int[1]);
    d["estimate"] = two ? py::object(py::make_tuple(r.estimate[0], r.estimate[1])) : py::object(py::float_(r.estimate[0]));
    d["null_value"] = r.null_value;
    d["alpha"] = r.alpha;
    d["reject"] = r.reject != 0;
    d["decision_code"] = r.decision;
    d["critical_values"] = py::make_tuple(r.critical[0], r.critical[1]);
    d["std_error"] = r.std_error;
    d["nobs"] = two ? py::object(py::make_tuple(r.n[0], r.n[1])) : py::object(py::int_(r.n[0]));
    d["text"] = format_with([&](char *b, size_t s, size_t *l) { return mcstat_result_format(&r, "x", "y", b, s, l); });
    return d;
}

py::dict power(int test, int alternative, bool strict, double n, double n_ratio, double sd_ratio, double effect,
               double alpha, double power, int unknown)
{
    mcstat_power_options o;
    mcstat_power_options_init(&o);
    o.test = test;
    o.alternative = alternative;
    o.strict = strict ? 1 : 0;
    o.n = n;
    o.n_ratio = n_ratio;
    o.sd_ratio = sd_ratio;
    o.effect = effect;
    o.alpha = alpha;
    o.power = power;
    mcstat_power_options r = o;
    int st;
    if (unknown == MCSTAT_POWER_SOLVE_POWER) { // nothing to solve: the power at n, effect, alpha
        st = mcstat_power_compute(&o, &r.power);
    } else {
        py::gil_scoped_release nogil;
        st = mcstat_power_solve(&o, unknown, &r);
    }
    if (st == MCSTAT_EINVAL)
        throw_invalid("no solution with these arguments: n must be >= 2 in each group, alpha and power in "
                      "(0, 1), an effect of the alternative's sign (a variance ratio > 0), and the power above "
                      "what alpha alone gives");
    if (st)
        throw_status(st);
    py::dict d;
    d["n"] = r.n;
    d["n_ratio"] = r.n_ratio;
    d["sd_ratio"] = r.sd_ratio;
    d["effect"] = r.effect;
    d["alpha"] = r.alpha;
    d["power"] = r.power;
    d["text"] = format_with([&](char *b, size_t s, size_t *l) { return mcstat_power_format(&r, b, s, l); });
    return d;
}

} // namespace

void register_power(py::module_ &mod)
{
    mod.def("_equivalence", &equivalence, py::arg("x"), py::arg("y"), py::arg("mu0"), py::arg("lower"),
            py::arg("upper"), py::arg("alpha"), py::arg("omit_nan"),
            "libmcstat's TOST (use mcstat.equivalence_test).");
    mod.def("_power", &power, py::arg("test"), py::arg("alternative"), py::arg("strict"), py::arg("n"),
            py::arg("n_ratio"), py::arg("sd_ratio"), py::arg("effect"), py::arg("alpha"), py::arg("power"),
            py::arg("unknown"), "libmcstat's power solver (use mcstat.power).");
}

} // namespace mcs
