// summary_rows.cpp - Welch's test per pixel from per-pixel summaries (count,
// mean, sum of squared deviations M2), for mcstat.image's .npz input: each
// row's mcstat_moments comes from mcstat_moments_from_summary and is tested
// by libmcstat's mcstat_t_test_2_moments.  (Arrays of serialized accumulators will reach
// the same test through libmcstat's row-wise accumulator API.)
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// An accumulator holding (n, mean, M2): libmcstat builds it (a valid
// accumulator; the t test reads only n, the mean and M2).  The count comes
// as a double from NumPy: it must be a non-negative integer.
int from_summary(double n, double mean, double m2, mcstat_moments *m)
{
    if (!(n >= 0) || n != std::floor(n) || n > 9.0e15)
        return MCSTAT_EINVAL;
    return mcstat_moments_from_summary(static_cast<uint64_t>(n), mean, m2, m);
}

} // namespace

void register_summary_rows(py::module_ &mod)
{
    mod.def(
        "_t_test_2_summary_rows",
        [](carray nx, carray mx, carray m2x, carray ny, carray my, carray m2y, int alternative, double alpha) {
            size_t rows = static_cast<size_t>(nx.size());
            for (const carray *a : {&mx, &m2x, &ny, &my, &m2y})
                if (static_cast<size_t>(a->size()) != rows)
                    throw_invalid("the summary arrays must have the same number of entries");
            py::array_t<double> stat(rows), pval(rows), est(std::vector<py::ssize_t>{static_cast<py::ssize_t>(rows), 2});
            py::array_t<int8_t> decision(rows), status(rows);
            const double *a = nx.data(), *b = mx.data(), *c = m2x.data(), *d = ny.data(), *e = my.data(),
                         *f = m2y.data();
            double *ps = stat.mutable_data(), *pp = pval.mutable_data(), *pe = est.mutable_data();
            int8_t *pd = decision.mutable_data(), *pst = status.mutable_data();
            {
                py::gil_scoped_release nogil;
                for (size_t i = 0; i < rows; i++) {
                    mcstat_moments x, y;
                    mcstat_result r;
                    int st = from_summary(a[i], b[i], c[i], &x);
                    if (!st)
                        st = from_summary(d[i], e[i], f[i], &y);
                    if (!st)
                        st = mcstat_t_test_2_moments(&x, &y, 0.0, alternative, alpha, &r);
                    pst[i] = static_cast<int8_t>(st);
                    ps[i] = st ? NAN : r.statistic;
                    pp[i] = st ? NAN : r.p_value;
                    pe[2 * i] = st ? NAN : r.estimate[0];
                    pe[2 * i + 1] = st ? NAN : r.estimate[1];
                    pd[i] = static_cast<int8_t>(st ? 0 : r.decision);
                }
            }
            py::dict out;
            out["statistic"] = stat;
            out["pvalue"] = pval;
            out["estimate"] = est;
            out["decision_code"] = decision;
            out["status"] = status;
            return out;
        },
        py::arg("nx"), py::arg("mean_x"), py::arg("m2_x"), py::arg("ny"), py::arg("mean_y"), py::arg("m2_y"),
        py::arg("alternative"), py::arg("alpha"),
        "Welch's test per row from (n, mean, M2) summaries (flat arrays); for mcstat.image.");
}

} // namespace mcs
