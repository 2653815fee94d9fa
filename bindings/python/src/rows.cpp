// rows.cpp - one test per row of N-D input (the per-pixel case).
//
// The test axis is moved last (a view, no copy).  When every row is then a
// contiguous run of float64 at a constant stride (C-contiguous input with
// axis=-1), libmcstat reads the rows in place; otherwise each chunk of rows
// is gathered into a small per-thread buffer.  Rows are split into one
// contiguous range per thread, each row computed by libmcstat's
// mcstat_*_rows exactly as by the one-test call, so the results do not
// depend on the number of threads.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "threads.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

namespace mcs {

namespace {

std::atomic<int> g_threads{0};

int default_threads()
{
    if (const char *e = std::getenv("MCSTAT_NUM_THREADS")) {
        int v = std::atoi(e);
        if (v > 0)
            return v < MAX_THREADS ? v : MAX_THREADS;
    }
    unsigned h = std::thread::hardware_concurrency();
    return h ? static_cast<int>(h) : 1;
}

// Where the rows of one operand are: base pointer, byte offset of each row
// (or a constant stride), the byte stride between a row's values.
struct Layout {
    const char *base = nullptr;
    size_t n = 0;
    ptrdiff_t inner = 0;          // bytes between consecutive values of a row
    bool uniform = false;         // rows at base + i * row_stride, values contiguous
    ptrdiff_t row_stride = 0;     // bytes (uniform only)
    std::vector<ptrdiff_t> offs;  // bytes, one per row (otherwise)
};

Layout layout_of(const py::array &a, size_t rows)
{
    Layout L;
    int nd = static_cast<int>(a.ndim());
    L.base = static_cast<const char *>(a.data());
    L.n = static_cast<size_t>(a.shape(nd - 1));
    L.inner = a.strides(nd - 1);
    // Offsets of the rows over the outer dimensions, in C order.
    L.offs.assign(rows, 0);
    std::vector<py::ssize_t> idx(static_cast<size_t>(std::max(nd - 1, 0)), 0);
    ptrdiff_t off = 0;
    for (size_t r = 0; r < rows; r++) {
        L.offs[r] = off;
        for (int d = nd - 2; d >= 0; d--) {
            if (++idx[static_cast<size_t>(d)] < a.shape(d)) {
                off += a.strides(d);
                break;
            }
            off -= a.strides(d) * (a.shape(d) - 1);
            idx[static_cast<size_t>(d)] = 0;
        }
    }
    bool aligned = reinterpret_cast<uintptr_t>(L.base) % sizeof(double) == 0;
    bool contiguous_rows = (L.inner == static_cast<ptrdiff_t>(sizeof(double)) || L.n <= 1) && aligned;
    ptrdiff_t s = rows > 1 ? L.offs[1] - L.offs[0] : 0;
    bool progression = s >= 0 && s % static_cast<ptrdiff_t>(sizeof(double)) == 0;
    for (size_t r = 0; progression && r < rows; r++)
        progression = L.offs[r] == static_cast<ptrdiff_t>(r) * s;
    if (contiguous_rows && progression) {
        L.uniform = true;
        L.row_stride = s;
        L.offs.clear();
        L.offs.shrink_to_fit();
    }
    return L;
}

// Rows [r0, r0 + k) of an operand as (pointer, stride in elements): in
// place when uniform, else gathered into buf (k * n doubles).
const double *rows_at(const Layout &L, size_t r0, size_t k, std::vector<double> &buf, size_t *stride)
{
    if (L.uniform) {
        *stride = static_cast<size_t>(L.row_stride) / sizeof(double);
        return reinterpret_cast<const double *>(L.base + static_cast<ptrdiff_t>(r0) * L.row_stride);
    }
    buf.resize(k * L.n);
    for (size_t i = 0; i < k; i++) {
        const char *p = L.base + L.offs[r0 + i];
        for (size_t j = 0; j < L.n; j++)
            std::memcpy(&buf[i * L.n + j], p + static_cast<ptrdiff_t>(j) * L.inner, sizeof(double));
    }
    *stride = L.n;
    return buf.data();
}

struct Outputs {
    double *statistic, *df, *pvalue, *conf_int, *estimate, *critical, *std_error;
    bool *reject;
    int8_t *decision, *status;
    int64_t *nobs;
    int ndf, nest, nobs_per_row;
};

void scatter(const mcstat_result *res, const int32_t *st, size_t r0, size_t k, const Outputs &o)
{
    for (size_t i = 0; i < k; i++) {
        const mcstat_result &r = res[i];
        size_t j = r0 + i;
        o.statistic[j] = r.statistic;
        for (int d = 0; d < o.ndf; d++)
            o.df[j * o.ndf + d] = r.df[d];
        o.pvalue[j] = r.p_value;
        o.conf_int[2 * j] = r.conf_int[0];
        o.conf_int[2 * j + 1] = r.conf_int[1];
        for (int e = 0; e < o.nest; e++)
            o.estimate[j * o.nest + e] = r.estimate[e];
        o.critical[2 * j] = r.critical[0];
        o.critical[2 * j + 1] = r.critical[1];
        o.std_error[j] = r.std_error;
        o.reject[j] = st[i] == 0 && r.reject;
        o.decision[j] = static_cast<int8_t>(st[i] == 0 ? r.decision : 0);
        o.status[j] = static_cast<int8_t>(st[i]);
        for (int s = 0; s < o.nobs_per_row; s++)
            o.nobs[j * o.nobs_per_row + s] = st[i] == 0 ? static_cast<int64_t>(r.n[s]) : 0;
    }
}

// Rows of the pooled and the paired test, which have no libmcstat matrix
// call: each row through the single call (bit for bit that call), a failed
// row cleared to NaN as the matrix calls clear theirs.
void extra_rows(const TestArgs &a, const double *px, size_t nx, size_t sx, const double *py_, size_t ny, size_t sy,
                size_t k, mcstat_result *res, int32_t *st)
{
    std::vector<double> kx, ky;
    for (size_t i = 0; i < k; i++) {
        const double *x = px + i * sx, *y = py_ + i * sy;
        int s;
        if (a.kind == Kind::T2P) {
            mcstat_moments mx, my;
            mcstat_moments_init(&mx);
            mcstat_moments_init(&my);
            s = a.omit_nan ? mcstat_moments_add_array_omit_nan(&mx, x, nx, nullptr) : mcstat_moments_add_array(&mx, x, nx);
            if (!s)
                s = a.omit_nan ? mcstat_moments_add_array_omit_nan(&my, y, ny, nullptr)
                               : mcstat_moments_add_array(&my, y, ny);
            if (!s)
                s = mcstat_t_test_2_pooled_moments(&mx, &my, a.null_value, a.alternative, a.alpha, &res[i]);
        } else if (a.omit_nan) { // paired: the pairs without NaN
            kx.clear();
            ky.clear();
            for (size_t j = 0; j < nx; j++)
                if (!std::isnan(x[j]) && !std::isnan(y[j])) {
                    kx.push_back(x[j]);
                    ky.push_back(y[j]);
                }
            s = mcstat_t_test_paired(kx.data(), ky.data(), kx.size(), a.null_value, a.alternative, a.alpha, &res[i]);
        } else {
            s = mcstat_t_test_paired(x, y, nx, a.null_value, a.alternative, a.alpha, &res[i]);
        }
        if (s)
            res[i] = nan_result(a, 0, 0);
        st[i] = s;
    }
}

void run_range(const TestArgs &a, const Layout &X, const Layout &Y, bool two, size_t begin, size_t end,
               const Outputs &o)
{
    unsigned flags = (a.intervals ? 0u : MCSTAT_ROWS_NO_INTERVALS) | (a.omit_nan ? MCSTAT_ROWS_OMIT_NAN : 0u);
    // Chunks bound the result buffer and, when gathering, the copy (~1 MiB).
    size_t per_row = X.n + (two ? Y.n : 0);
    size_t chunk = std::max<size_t>(1, std::min<size_t>(256, (size_t(1) << 17) / std::max<size_t>(per_row, 1)));
    std::vector<mcstat_result> res(chunk);
    std::vector<int32_t> st(chunk);
    std::vector<double> bx, by;
    for (size_t r0 = begin; r0 < end; r0 += chunk) {
        size_t k = std::min(chunk, end - r0), sx = 0, sy = 0;
        const double *px = rows_at(X, r0, k, bx, &sx);
        const double *py_ = two ? rows_at(Y, r0, k, by, &sy) : nullptr;
        switch (a.kind) {
        case Kind::T1:
            mcstat_t_test_1_matrix(px, X.n, sx, k, a.null_value, a.alternative, a.alpha, flags, res.data(), st.data());
            break;
        case Kind::T2:
            mcstat_t_test_2_matrix(px, X.n, sx, py_, Y.n, sy, k, a.null_value, a.alternative, a.alpha, flags,
                                 res.data(), st.data());
            break;
        case Kind::V1:
            mcstat_var_test_1_matrix(px, X.n, sx, k, a.null_value, a.alternative, a.alpha, flags, res.data(),
                                   st.data());
            break;
        case Kind::V2:
            mcstat_var_test_2_matrix(px, X.n, sx, py_, Y.n, sy, k, a.null_value, a.alternative, a.alpha, flags,
                                   res.data(), st.data());
            break;
        case Kind::T2P:
        case Kind::TP:
            extra_rows(a, px, X.n, sx, py_, Y.n, sy, k, res.data(), st.data());
            break;
        }
        scatter(res.data(), st.data(), r0, k, o);
    }
}

const char *kind_name(Kind k)
{
    switch (k) {
    case Kind::T1: return "t_1";
    case Kind::T2: return "t_2";
    case Kind::V1: return "var_1";
    case Kind::T2P: return "t_2_pooled";
    case Kind::TP: return "t_paired";
    default: return "var_2";
    }
}


// The result arrays of a batch (the image's shape, a trailing axis where a
// field has several values) and the pointers scatter() writes through.
struct BatchOutputs {
    py::array_t<double> statistic, df, pvalue, conf_int, estimate, critical, std_error;
    py::array_t<bool> reject;
    py::array_t<int8_t> decision, status;
    py::array_t<int64_t> nobs;
    Outputs o;

    BatchOutputs(const std::vector<py::ssize_t> &shape, Kind kind)
    {
        bool two = kind == Kind::T2 || kind == Kind::V2 || kind == Kind::T2P; // (paired: the number of pairs)
        o.ndf = kind == Kind::V2 ? 2 : 1;
        o.nest = kind == Kind::T2 || kind == Kind::T2P ? 2 : 1;
        o.nobs_per_row = two ? 2 : 1;
        auto with = [&](int k) {
            std::vector<py::ssize_t> s = shape;
            if (k > 1)
                s.push_back(k);
            return s;
        };
        statistic = py::array_t<double>(with(1));
        df = py::array_t<double>(with(o.ndf));
        pvalue = py::array_t<double>(with(1));
        conf_int = py::array_t<double>(with(2));
        estimate = py::array_t<double>(with(o.nest));
        critical = py::array_t<double>(with(2));
        std_error = py::array_t<double>(with(1));
        reject = py::array_t<bool>(with(1));
        decision = py::array_t<int8_t>(with(1));
        status = py::array_t<int8_t>(with(1));
        nobs = py::array_t<int64_t>(with(o.nobs_per_row));
        o.statistic = statistic.mutable_data();
        o.df = df.mutable_data();
        o.pvalue = pvalue.mutable_data();
        o.conf_int = conf_int.mutable_data();
        o.estimate = estimate.mutable_data();
        o.critical = critical.mutable_data();
        o.std_error = std_error.mutable_data();
        o.reject = reject.mutable_data();
        o.decision = decision.mutable_data();
        o.status = status.mutable_data();
        o.nobs = nobs.mutable_data();
    }

    // Under nan_policy="propagate", the rows whose data hold NaN: NaN fields
    // (libmcstat refused them) that are not errors.
    py::object nan_rows = py::none();

    // The Python BatchResult (mcstat._result._make_batch) of these arrays.
    py::object result(const TestArgs &a) const
    {
        py::dict fields;
        fields["statistic"] = statistic;
        fields["df"] = df;
        fields["pvalue"] = pvalue;
        fields["conf_int"] = conf_int;
        fields["estimate"] = estimate;
        fields["critical_values"] = critical;
        fields["std_error"] = std_error;
        fields["reject"] = reject;
        fields["decision_code"] = decision;
        fields["status"] = status;
        fields["nobs"] = nobs;
        static py::object make = py::module_::import("mcstat._result").attr("_make_batch");
        return make(kind_name(a.kind), fields, a.alternative, a.alpha, a.null_value, a.axis, a.errors_as_nan,
                    a.intervals, py::arg("nan_rows") = nan_rows);
    }
};

// Runs range(begin, end) over [0, rows) split into one range per thread, the
// GIL released.  At least 1024 rows per thread: below that a thread costs
// more than it saves.
template <class F> void for_row_ranges(size_t rows, F range)
{
    py::gil_scoped_release nogil;
    mcs_threads::split_ranges(rows, static_cast<size_t>(num_threads()), 1024, [&range](size_t b, size_t e) {
        range(b, e);
        return 0;
    });
}

} // namespace

int num_threads()
{
    int t = g_threads.load();
    return t > 0 ? t : default_threads();
}

void set_num_threads(int n)
{
    g_threads.store(n > 0 ? n : 0);
}

py::object run_rows(const TestArgs &a, py::array x, py::array y, bool two)
{
    int nd = static_cast<int>(x.ndim());
    if (two && y.ndim() != nd)
        throw_invalid("x and y must have the same number of dimensions for row-wise tests, got " +
                      std::to_string(nd) + "-D and " + std::to_string(y.ndim()) + "-D");
    int axis = a.axis;
    if (axis < -nd || axis >= nd)
        throw_invalid("axis " + std::to_string(axis) + " is out of range for " + std::to_string(nd) + "-D input");
    if (axis < 0)
        axis += nd;
    if (a.kind == Kind::TP && x.shape(axis) != y.shape(axis))
        throw_invalid("paired=True needs x and y of the same length along axis " + std::to_string(axis) +
                      " (the pairs), got " + std::to_string(x.shape(axis)) + " and " + std::to_string(y.shape(axis)));
    if (two) {
        for (int d = 0; d < nd; d++) {
            if (d != axis && x.shape(d) != y.shape(d)) {
                auto shape_str = [nd](const py::array &v) {
                    std::string out = "(";
                    for (int k = 0; k < nd; k++)
                        out += std::to_string(v.shape(k)) + (k + 1 < nd || nd == 1 ? "," : "") + (k + 1 < nd ? " " : "");
                    return out + ")";
                };
                std::string sx = shape_str(x), sy = shape_str(y);
                throw_invalid("x and y must have the same shape except along axis " + std::to_string(axis) +
                              ", got " + sx + " and " + sy);
            }
        }
    }
    py::module_ np = py::module_::import("numpy");
    py::array xv = np.attr("moveaxis")(x, axis, -1);
    py::array yv = two ? py::array(np.attr("moveaxis")(y, axis, -1)) : py::array();
    std::vector<py::ssize_t> outer(xv.shape(), xv.shape() + nd - 1);
    size_t rows = 1;
    for (auto s : outer)
        rows *= static_cast<size_t>(s);

    Layout X = layout_of(xv, rows), Y;
    if (two)
        Y = layout_of(yv, rows);

    BatchOutputs out(outer, a.kind);
    if (a.propagate_nan) {
        py::object isnan = np.attr("isnan");
        py::object m = isnan(xv).attr("any")(-1);
        if (two)
            m = m.attr("__or__")(isnan(yv).attr("any")(-1));
        out.nan_rows = m;
    }
    for_row_ranges(rows, [&](size_t b, size_t e) { run_range(a, X, Y, two, b, e, out.o); });
    return out.result(a);
}

} // namespace mcs

// ---- one test per accumulator (MomentsArray) ---------------------------------
// The accumulators are already reduced, so there is no layout to read: rows
// are split into one range per thread and libmcstat's *_moments_rows fills
// each range, bit for bit the single *_moments call per pixel.
namespace mcs {

py::object run_moments_rows(const TestArgs &a, const mcstat_moments *x, const mcstat_moments *y, size_t rows,
                            const std::vector<py::ssize_t> &shape)
{
    bool two = a.kind == Kind::T2 || a.kind == Kind::V2 || a.kind == Kind::T2P;
    BatchOutputs out(shape, a.kind);
    const Outputs &o = out.o;
    unsigned flags = a.intervals ? 0u : MCSTAT_ROWS_NO_INTERVALS;
    auto range = [&](size_t begin, size_t end) {
        const size_t chunk = 256;
        std::vector<mcstat_result> res(chunk);
        std::vector<int32_t> st(chunk);
        for (size_t r0 = begin; r0 < end; r0 += chunk) {
            size_t k = std::min(chunk, end - r0);
            const mcstat_moments *px = x + r0, *py_ = two ? y + r0 : nullptr;
            switch (a.kind) {
            case Kind::T1:
                mcstat_t_test_1_moments_rows(px, k, a.null_value, a.alternative, a.alpha, flags, res.data(), st.data());
                break;
            case Kind::T2:
                mcstat_t_test_2_moments_rows(px, py_, k, a.null_value, a.alternative, a.alpha, flags, res.data(),
                                             st.data());
                break;
            case Kind::V1:
                mcstat_var_test_1_moments_rows(px, k, a.null_value, a.alternative, a.alpha, flags, res.data(),
                                               st.data());
                break;
            case Kind::V2:
                mcstat_var_test_2_moments_rows(px, py_, k, a.null_value, a.alternative, a.alpha, flags, res.data(),
                                               st.data());
                break;
            case Kind::T2P: // no rows call: one per pixel, failed pixels cleared to NaN
                for (size_t i = 0; i < k; i++) {
                    st[i] = mcstat_t_test_2_pooled_moments(&px[i], &py_[i], a.null_value, a.alternative, a.alpha,
                                                           &res[i]);
                    if (st[i])
                        res[i] = nan_result(a, 0, 0);
                }
                break;
            case Kind::TP: // refused by tests.cpp: accumulators hold no pairs
                std::fill(st.begin(), st.begin() + static_cast<ptrdiff_t>(k), MCSTAT_EINVAL);
                break;
            }
            scatter(res.data(), st.data(), r0, k, o);
        }
    };
    for_row_ranges(rows, range);
    return out.result(a);
}

} // namespace mcs
