// distributions.cpp - the t, chi-squared and F distributions of libmcstat
// (mcstat.h, "Distributions") over NumPy arrays: the arguments broadcast
// against each other as NumPy's ufuncs do, every element is one call of
// libmcstat's function, and the first bad element raises an error naming
// the argument, its value and where it is.  mcstat.distributions wraps
// this one entry point in named functions.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "threads.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace mcs {

namespace {

using fn2 = int (*)(double, double, int, double *);
using fn3 = int (*)(double, double, double, int, double *);

struct Op {
    const char *name;
    fn2 f2; // t and chi-squared: (x or p, df)
    fn3 f3; // F: (x or p, df1, df2)
    bool quantile;
};

const Op OPS[] = {
    {"t_cdf", mcstat_t_cdf, nullptr, false},
    {"t_logcdf", mcstat_t_logcdf, nullptr, false},
    {"t_quantile", mcstat_t_quantile, nullptr, true},
    {"chisq_cdf", mcstat_chisq_cdf, nullptr, false},
    {"chisq_logcdf", mcstat_chisq_logcdf, nullptr, false},
    {"chisq_quantile", mcstat_chisq_quantile, nullptr, true},
    {"f_cdf", nullptr, mcstat_f_cdf, false},
    {"f_logcdf", nullptr, mcstat_f_logcdf, false},
    {"f_quantile", nullptr, mcstat_f_quantile, true},
};

std::string shape_str(const std::vector<py::ssize_t> &s)
{
    std::string out = "(";
    for (size_t i = 0; i < s.size(); i++)
        out += (i ? ", " : "") + std::to_string(s[i]);
    return out + (s.size() == 1 ? ",)" : ")");
}

// Why libmcstat refused the element (a, b, c): the argument at fault, as
// libmcstat's own checks (dist.c) decide; empty when the arguments are
// valid and the computation itself failed.
std::string fault(const Op &op, const char *const names[3], int nargs, const double v[3])
{
    auto val = [](double d) { return repr(py::float_(d).ptr()); };
    if (op.quantile ? !(v[0] >= 0.0 && v[0] <= 1.0) : std::isnan(v[0]))
        return op.quantile ? std::string("p must be a probability in [0, 1], got ") + val(v[0])
                           : std::string("x must not be NaN");
    for (int k = 1; k < nargs; k++)
        if (!(v[k] > 0.0 && std::isfinite(v[k])))
            return std::string(names[k]) + " must be positive and finite, got " + val(v[k]);
    return std::string();
}

// mcstat_t_quantiles over mcstat.set_num_threads' threads (without the
// GIL): x[i] for df[i] at one level, NaN where an element fails; the first
// failing element's status.
int t_quantiles(double p, const double *df, size_t n, bool upper, double *x)
{
    py::gil_scoped_release nogil;
    return mcs_threads::split_ranges(n, static_cast<size_t>(num_threads()), size_t{1} << 16,
                                     [&](size_t b, size_t e) {
                                         return mcstat_t_quantiles(p, df + b, e - b, upper ? 1 : 0, x + b);
                                     });
}

py::object distribution(const std::string &name, py::handle a0, py::handle a1, py::handle a2, bool upper)
{
    const Op *op = nullptr;
    for (const Op &o : OPS)
        if (name == o.name)
            op = &o;
    if (!op)
        throw_invalid("unknown distribution function '" + name + "'");
    const int nargs = op->f3 ? 3 : 2;
    const char *names[3] = {op->quantile ? "p" : "x", op->f3 ? "df1" : "df", "df2"};
    py::handle in[3] = {a0, a1, a2};
    py::array arr[3];
    for (int k = 0; k < nargs; k++) {
        if (in[k].is_none())
            throw py::type_error(std::string(op->name) + "(): " + names[k] + " must be a real number or an array " +
                                 "of them, not None");
        arr[k] = as_float_array(in[k], names[k]);
    }
    // The broadcast shape, as NumPy's ufuncs have it.
    py::ssize_t nd = 0;
    for (int k = 0; k < nargs; k++)
        nd = std::max<py::ssize_t>(nd, arr[k].ndim());
    std::vector<py::ssize_t> shape(static_cast<size_t>(nd), 1);
    // strides[k][d]: the byte step of argument k along output dimension d (0 where it is broadcast)
    std::vector<py::ssize_t> strides[3];
    for (int k = 0; k < nargs; k++) {
        strides[k].assign(static_cast<size_t>(nd), 0);
        py::ssize_t off = nd - arr[k].ndim();
        for (py::ssize_t d = 0; d < arr[k].ndim(); d++) {
            py::ssize_t len = arr[k].shape(d), &out = shape[static_cast<size_t>(off + d)];
            if (len != 1 && out != 1 && len != out) {
                std::string msg = std::string(op->name) + ": the arguments do not broadcast together:";
                for (int j = 0; j < nargs; j++)
                    msg += std::string(j ? "," : "") + " " + names[j] + " has shape " +
                           shape_str(std::vector<py::ssize_t>(arr[j].shape(), arr[j].shape() + arr[j].ndim()));
                throw_invalid(msg);
            }
            if (len != 1) {
                out = len;
                strides[k][static_cast<size_t>(off + d)] = arr[k].strides(d);
            }
        }
    }
    size_t total = 1;
    for (py::ssize_t s : shape)
        total *= static_cast<size_t>(s);
    py::array_t<double> result(shape);
    double *out = result.mutable_data();
    const char *base[3] = {nullptr, nullptr, nullptr};
    for (int k = 0; k < nargs; k++)
        base[k] = static_cast<const char *>(arr[k].data());

    int status = MCSTAT_OK;
    size_t bad = 0;
    double bad_v[3] = {0, 0, 0};
    auto loop = [&]() {
        std::vector<py::ssize_t> idx(static_cast<size_t>(nd), 0);
        const char *ptr[3] = {base[0], base[1], base[2]};
        const int up = upper ? 1 : 0;
        for (size_t i = 0; i < total; i++) {
            double v[3] = {0, 0, 0};
            for (int k = 0; k < nargs; k++)
                std::memcpy(&v[k], ptr[k], sizeof(double)); // views may be unaligned
            int st = op->f3 ? op->f3(v[0], v[1], v[2], up, &out[i]) : op->f2(v[0], v[1], up, &out[i]);
            if (st) {
                status = st;
                bad = i;
                std::memcpy(bad_v, v, sizeof v);
                return;
            }
            for (py::ssize_t d = nd - 1; d >= 0; d--) { // next element in C order
                size_t du = static_cast<size_t>(d);
                for (int k = 0; k < nargs; k++)
                    ptr[k] += strides[k][du];
                if (++idx[du] < shape[du])
                    break;
                for (int k = 0; k < nargs; k++)
                    ptr[k] -= strides[k][du] * shape[du];
                idx[du] = 0;
            }
        }
    };
    double p0 = 0.0; // the level, where one level meets many df
    if (arr[0].size() == 1)
        std::memcpy(&p0, base[0], sizeof p0);
    if (op->f2 == mcstat_t_quantile && arr[0].size() == 1 && static_cast<size_t>(arr[1].size()) == total &&
        total > 64 && p0 >= 0.0 && p0 <= 1.0) {
        // one level, many df: mcstat_t_quantiles' table, not one solve each
        // (an invalid level takes the loop, which names it at index 0)
        const double p = p0;
        py::array_t<double, py::array::c_style | py::array::forcecast> dfc(arr[1]);
        status = t_quantiles(p, dfc.data(), total, upper, out);
        if (status) {
            for (bad = 0; bad < total && !std::isnan(out[bad]); bad++)
                ;
            bad_v[0] = p;
            bad_v[1] = bad < total ? dfc.data()[bad] : NAN;
        }
    } else if (total >= GIL_RELEASE_MIN) {
        py::gil_scoped_release nogil;
        loop();
    } else {
        loop();
    }
    if (status) {
        std::string where;
        if (nd > 0) {
            std::vector<py::ssize_t> ix(static_cast<size_t>(nd));
            size_t r = bad;
            for (py::ssize_t d = nd - 1; d >= 0; d--) {
                ix[static_cast<size_t>(d)] = static_cast<py::ssize_t>(r % static_cast<size_t>(shape[static_cast<size_t>(d)]));
                r /= static_cast<size_t>(shape[static_cast<size_t>(d)]);
            }
            where = " at index " + shape_str(ix) + " of the broadcast shape " + shape_str(shape);
        }
        std::string why = status == MCSTAT_EINVAL ? fault(*op, names, nargs, bad_v) : std::string();
        if (!why.empty())
            throw_invalid(std::string(op->name) + ": " + why + where);
        std::string args;
        for (int k = 0; k < nargs; k++)
            args += std::string(k ? ", " : "") + names[k] + "=" + repr(py::float_(bad_v[k]).ptr());
        throw_status(status, std::string(op->name) + "(" + args + (upper ? ", upper=True" : "") + ")" + where);
    }
    if (nd == 0)
        return py::float_(out[0]);
    return std::move(result);
}

} // namespace

void register_distributions(py::module_ &mod)
{
    mod.def("_distribution", &distribution, py::arg("name"), py::arg("a"), py::arg("b"), py::arg("c"),
            py::arg("upper"), "libmcstat's t, chi-squared and F functions over arrays (use mcstat.distributions).");
    mod.def(
        "_t_quantiles",
        [](double p, py::array_t<double, py::array::c_style | py::array::forcecast> df, bool upper) {
            py::array_t<double> x(std::vector<py::ssize_t>(df.shape(), df.shape() + df.ndim()));
            if (!(p >= 0.0 && p <= 1.0))
                throw_invalid("p must be a probability in [0, 1], got " + repr(py::float_(p).ptr()));
            t_quantiles(p, df.data(), static_cast<size_t>(df.size()), upper, x.mutable_data());
            return x;
        },
        py::arg("p"), py::arg("df"), py::arg("upper") = true,
        "t quantiles at one level for an array of df (mcstat_t_quantiles over the threads), NaN where df is not "
        "a valid degree of freedom.");
}

} // namespace mcs
