// p_adjust.cpp - mcstat.p_adjust: libmcstat's mcstat_p_adjust on arrays of
// any shape (all entries form one family of tests).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <memory>
#include <vector>

namespace mcs {

void register_p_adjust(py::module_ &mod)
{
    mod.def(
        "p_adjust",
        [](py::handle p, const std::string &method) {
            if (p.is_none())
                throw py::type_error("p_adjust() needs an array of p-values, not None");
            int m = 0;
            if (mcstat_p_adjust_method_parse(method.c_str(), &m)) {
                std::string names; // R's names, as libmcstat has them
                for (int i = 0; const char *name = mcstat_p_adjust_method_name(i); i++)
                    names += (i ? ", '" : "'") + std::string(name) + "'";
                throw_invalid("method must be one of " + names + " (also 'bh', 'fdr' for 'BH' and 'by' for 'BY'), "
                              "got '" + method + "'");
            }
            py::array a = as_float_array(p, "p");
            // The output, C-ordered, is also the input: adjusted in place.
            py::array_t<double> out(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
            py::module_::import("numpy").attr("copyto")(out, a);
            size_t n = static_cast<size_t>(out.size());
            double *d = out.mutable_data();
            size_t bytes = 0;
            int st = mcstat_p_adjust_work_size(n, m, &bytes);
            if (st)
                throw_status(st);
            // Uninitialised scratch (a zero-filled vector would cost a pass
            // over 32 bytes per p-value).
            std::unique_ptr<double[]> work(new double[bytes / sizeof(double) + 1]);
            {
                py::gil_scoped_release nogil;
                st = mcstat_p_adjust(d, n, m, work.get(), bytes, d);
            }
            if (st == MCSTAT_EINVAL) {
                size_t k = 0;
                while (k < n && (std::isnan(d[k]) || (d[k] >= 0.0 && d[k] <= 1.0)))
                    k++;
                throw_invalid("p-values must lie in [0, 1] (NaN marks a missing one), got " +
                              (k < n ? repr(py::float_(d[k]).ptr()) : std::string("?")) + " at flat index " +
                              std::to_string(k));
            }
            if (st)
                throw_status(st);
            return out;
        },
        py::arg("p"), py::kw_only(), py::arg("method") = "holm",
        R"doc(Adjusted p-values for multiple testing, as R's ``p.adjust``.

Parameters
----------
p : array_like
    p-values in [0, 1], any shape; all of them form one family.  NaN marks
    a missing value (R's NA): it stays NaN and is not counted.
method : str, optional
    ``"holm"`` (default), ``"hochberg"``, ``"hommel"``, ``"bonferroni"``
    (family-wise error rate), ``"BH"`` (also ``"bh"``, ``"fdr"``:
    Benjamini-Hochberg false discovery rate), ``"BY"`` (also ``"by"``:
    Benjamini-Yekutieli, FDR under any dependence) or ``"none"``.

Returns
-------
ndarray
    float64, the shape of `p`: reject where it is <= alpha.

Raises
------
InvalidArgumentError
    An unknown method, or a p-value outside [0, 1] (infinities included).
OutOfMemoryError
    No memory for the workspace (32 bytes per p-value; 40 for Hommel).)doc");
}

} // namespace mcs
