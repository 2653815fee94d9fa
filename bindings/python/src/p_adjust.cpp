// p_adjust.cpp - mcstat.p_adjust: libmcstat's mcstat_p_adjust on arrays of
// any shape (all entries form one family of tests).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "output_array.hpp"

#include <cmath>
#include <vector>

namespace mcs {

namespace {

// statsmodels' multipletests methods libmcstat does not implement: said so,
// rather than only "unknown".
std::string unsupported_note(const std::string &method)
{
    std::string l;
    for (char c : method)
        l += (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
    static const char *const names[] = {"s",        "sidak",     "hs",        "holm-sidak",   "fdr_tsbh",
                                        "fdr_2sbh", "fdr_tsbky", "fdr_2sbky", "fdr_twostage", "fdr_gbs"};
    for (const char *n : names)
        if (l == n)
            return " (a statsmodels method mcstat does not implement)";
    return "";
}

// The caller's scratch for mcstat_p_adjust: a writable C-contiguous buffer
// of at least `need` bytes, aligned for double; None: the call allocates.
void *scratch(py::handle work, size_t need, size_t *bytes)
{
    *bytes = 0;
    if (work.is_none())
        return nullptr;
    py::buffer_info bi;
    try {
        bi = py::reinterpret_borrow<py::buffer>(work).request(true);
    } catch (const std::exception &) {
        throw_invalid("work must be a writable buffer (e.g. a NumPy array) or None");
    }
    py::ssize_t step = bi.itemsize;
    for (py::ssize_t d = bi.ndim; d-- > 0;) {
        if (bi.shape[d] > 1 && bi.strides[d] != step)
            throw_invalid("work must be C-contiguous");
        step *= bi.shape[d];
    }
    size_t have = static_cast<size_t>(bi.size) * static_cast<size_t>(bi.itemsize);
    if (reinterpret_cast<uintptr_t>(bi.ptr) % sizeof(double) != 0)
        throw_invalid("work must be aligned for float64");
    if (have < need)
        throw_invalid("work holds " + std::to_string(have) + " bytes; this call needs " + std::to_string(need));
    *bytes = have;
    return bi.ptr;
}

} // namespace

void register_p_adjust(py::module_ &mod)
{
    mod.def(
        "_p_adjust_method_name",
        [](const std::string &method) {
            int m = 0;
            if (method.find('\0') != std::string::npos || mcstat_p_adjust_method_parse(method.c_str(), &m))
                throw_invalid("unknown p_adjust method " + repr(py::str(method).ptr()));
            return std::string(mcstat_p_adjust_method_name(m));
        },
        py::arg("method"), "R's name of a p_adjust method given by any of its accepted names.");
    mod.def(
        "p_adjust_work_size",
        [](py::ssize_t n, const std::string &method) {
            int m = 0;
            if (n < 0)
                throw_invalid("n must be >= 0, got " + std::to_string(n));
            if (method.find('\0') != std::string::npos || mcstat_p_adjust_method_parse(method.c_str(), &m))
                throw_invalid("unknown p_adjust method " + repr(py::str(method).ptr()));
            size_t bytes = 0;
            int st = mcstat_p_adjust_work_size(static_cast<size_t>(n), m, &bytes);
            if (st)
                throw_status(st);
            return bytes;
        },
        py::arg("n"), py::arg("method") = "holm",
        "Bytes of scratch ``p_adjust(p, method=method, work=...)`` needs for n p-values (0 for "
        "'none' and 'bonferroni').");
    mod.def(
        "p_adjust",
        [](py::handle p, const std::string &method, py::handle work) {
            if (p.is_none())
                throw py::type_error("p_adjust() needs an array of p-values, not None");
            int m = 0;
            if (method.find('\0') != std::string::npos || mcstat_p_adjust_method_parse(method.c_str(), &m))
                throw_invalid("method must be one of 'holm', 'hochberg', 'hommel', 'bonferroni', 'BH' "
                              "('fdr'), 'BY' or 'none' (R's names), 'e-BH' ('ebh', 'e_bh'), or statsmodels' "
                              "names for these: "
                              "'h', 'sh' ('simes-hochberg'), 'ho', 'b' ('bonf'), 'fdr_bh' ('fdr_i', 'fdr_p'), "
                              "'fdr_by' ('fdr_n', 'fdr_c', 'fdrcorr'); case is ignored; got " +
                              repr(py::str(method).ptr()) + unsupported_note(method));
            py::array a = as_float_array(p, "p");
            // The output, C-ordered, is also the input: adjusted in place.
            auto out = output_array<double>(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
            py::module_::import("numpy").attr("copyto")(out, a);
            size_t n = static_cast<size_t>(out.size());
            double *d = out.mutable_data();
            size_t need = 0, bytes = 0;
            int st = mcstat_p_adjust_work_size(n, m, &need);
            if (st)
                throw_status(st);
            // Without the caller's scratch the call allocates its own: at
            // image scale it asks the system for huge pages, whose first
            // touch costs a fraction of 4 KiB pages'.
            void *w = scratch(work, need, &bytes);
            {
                py::gil_scoped_release nogil;
                st = mcstat_p_adjust(d, n, m, w, bytes, d);
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
        py::arg("p"), py::kw_only(), py::arg("method") = "holm", py::arg("work") = py::none(),
        R"doc(Adjusted p-values for multiple testing, as R's ``p.adjust``.

Parameters
----------
p : array_like
    p-values in [0, 1], any shape; all of them form one family.  NaN marks
    a missing value (R's NA): it stays NaN and is not counted.
method : str, optional
    ``"holm"`` (default), ``"hochberg"``, ``"hommel"``, ``"bonferroni"``
    (family-wise error rate), ``"BH"`` (also ``"fdr"``:
    Benjamini-Hochberg false discovery rate, for independent or positively
    dependent tests), ``"BY"`` (Benjamini-Yekutieli, FDR under any
    dependence) or ``"none"``: R's names; ``"e-BH"`` (also ``"ebh"``,
    ``"e_bh"``): `e_bh` on the e-values ``p ** -0.9 / 10`` (a calibrator:
    FDR under any dependence, like BY, and less powerful than BY on the
    same p-values; one p-value comes back unchanged, as in every method).  statsmodels'
    ``multipletests`` names for the same methods are accepted too:
    ``"h"`` (Holm), ``"sh"``/``"simes-hochberg"``, ``"ho"`` (Hommel),
    ``"b"``/``"bonf"``, ``"fdr_bh"`` (``"fdr_i"``, ``"fdr_p"``, ``"fdri"``,
    ``"fdrp"``), ``"fdr_by"`` (``"fdr_n"``, ``"fdr_c"``, ``"fdrn"``,
    ``"fdrcorr"``).  Case is ignored.  statsmodels' Sidak and two-stage
    methods (``"sidak"``, ``"holm-sidak"``, ``"fdr_tsbh"``, ...) are not
    implemented and raise.
work : writable array, optional
    Scratch the call may overwrite: C-contiguous, aligned for float64, of
    at least ``p_adjust_work_size(p.size, method)`` bytes (32 a p-value,
    40 for Hommel), e.g. an input no longer needed.  None (default): the
    call allocates it and frees it before returning.

Returns
-------
ndarray
    float64, the shape of `p`: reject where it is <= alpha.

Raises
------
InvalidArgumentError
    An unknown method, a p-value outside [0, 1] (infinities included), or
    a `work` that is not writable, contiguous, aligned or large enough.
OutOfMemoryError
    No memory for the workspace (32 bytes per p-value; 40 for Hommel).)doc");
    mod.def(
        "e_bh",
        [](py::handle e) {
            if (e.is_none())
                throw py::type_error("e_bh() needs an array of e-values, not None");
            py::array a = as_float_array(e, "e");
            auto out = output_array<double>(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()));
            py::module_::import("numpy").attr("copyto")(out, a);
            size_t n = static_cast<size_t>(out.size());
            double *d = out.mutable_data();
            int st; // the workspace from the call, as p_adjust's
            {
                py::gil_scoped_release nogil;
                st = mcstat_e_bh(d, n, nullptr, 0, d);
            }
            if (st == MCSTAT_EINVAL) {
                size_t k = 0;
                while (k < n && (std::isnan(d[k]) || d[k] >= 0.0))
                    k++;
                throw_invalid("e-values must be >= 0 (inf allowed; NaN marks a missing one), got " +
                              (k < n ? repr(py::float_(d[k]).ptr()) : std::string("?")) + " at flat index " +
                              std::to_string(k));
            }
            if (st)
                throw_status(st);
            return out;
        },
        py::arg("e"),
        R"doc(e-BH (Wang & Ramdas 2022): false discovery rate control from e-values,
valid under any dependence among them.

With the e-values sorted, e_(1) >= ... >= e_(m), e-BH at level alpha
rejects the k* largest, k* = max{k : k e_(k) / m >= 1 / alpha}.  The
values returned make that one comparison at every alpha: reject where
the result is <= alpha (min over k >= the rank of m / (k e_(k)), capped
at 1).

Parameters
----------
e : array_like
    e-values in [0, inf] (non-negative, expectation <= 1 under their
    null), any shape; all of them form one family.  NaN marks a missing
    one: it stays NaN and is not counted.

Returns
-------
ndarray
    float64, the shape of `e`.  A single e-value gives min(1, 1/e).

Raises
------
InvalidArgumentError
    A negative e-value.

See also ``p_adjust(p, method="e-BH")``, which calibrates p-values into
e-values first.)doc");
}

} // namespace mcs
