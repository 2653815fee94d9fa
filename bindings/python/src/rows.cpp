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
#include "output_array.hpp"
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

namespace {

int test_code(Kind k)
{
    switch (k) {
    case Kind::T1: return MCSTAT_TEST_T_1;
    case Kind::T2: return MCSTAT_TEST_T_2;
    case Kind::V1: return MCSTAT_TEST_VAR_1;
    case Kind::V2: return MCSTAT_TEST_VAR_2;
    case Kind::T2P: return MCSTAT_TEST_T_2_POOLED;
    default: return MCSTAT_TEST_T_PAIRED;
    }
}

bool native_float(const py::array &a, char bytes)
{
    py::dtype d = a.dtype();
    return d.kind() == 'f' && d.itemsize() == bytes && d.attr("isnative").cast<bool>();
}

// v (the test axis last) as an mcstat_pixels_in read in place: the outer
// axes must collapse into one pixel stride (C order over them, as any
// view of a C-contiguous stack with the test axis moved does), the strides
// whole non-negative multiples of the item size, the data aligned.
bool pixels_view(const py::array &v, size_t itemsize, mcstat_pixels_in *in)
{
    int nd = static_cast<int>(v.ndim());
    auto ok_stride = [&](py::ssize_t s) { return s >= 0 && static_cast<size_t>(s) % itemsize == 0; };
    if (reinterpret_cast<uintptr_t>(v.data()) % itemsize != 0)
        return false;
    py::ssize_t vs = v.shape(nd - 1) > 1 ? v.strides(nd - 1) : 0;
    if (!ok_stride(vs))
        return false;
    py::ssize_t ps = 0; // the stride of the innermost outer axis of size > 1
    py::ssize_t expect = -1;
    for (int d = nd - 2; d >= 0; d--) {
        if (v.shape(d) == 1)
            continue;
        if (expect < 0) {
            ps = v.strides(d);
            if (!ok_stride(ps))
                return false;
        } else if (v.strides(d) != expect) {
            return false;
        }
        expect = v.strides(d) * v.shape(d);
    }
    in->data = v.data();
    in->n = static_cast<size_t>(v.shape(nd - 1));
    in->value_stride = static_cast<size_t>(vs) / itemsize;
    in->pixel_stride = static_cast<size_t>(ps) / itemsize;
    return true;
}

py::array as_pixels(py::array v, bool f32, mcstat_pixels_in *in)
{
    py::module_ np = py::module_::import("numpy");
    size_t itemsize = f32 ? sizeof(float) : sizeof(double);
    bool native = native_float(v, static_cast<char>(itemsize));
    if (!native || !pixels_view(v, itemsize, in)) {
        // a copy: C order, the test axis last (the rows layout)
        v = np.attr("ascontiguousarray")(v, py::arg("dtype") = f32 ? "float32" : "float64");
        pixels_view(v, itemsize, in);
    }
    in->type = f32 ? MCSTAT_VALUE_FLOAT32 : MCSTAT_VALUE_FLOAT64;
    return v;
}

} // namespace

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

    // float32 stays float32 when both sides are; anything else is read as float64
    bool f32 = native_float(xv, 4) && (!two || native_float(yv, 4));
    mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py_ = MCSTAT_PIXELS_IN_INIT;
    xv = as_pixels(xv, f32, &px);
    if (two)
        yv = as_pixels(yv, f32, &py_);

    const bool two_out = a.kind == Kind::T2 || a.kind == Kind::V2 || a.kind == Kind::T2P;
    auto arr = [&](auto tag) { return output_array<decltype(tag)>(outer); };
    // what is the same for every pixel that succeeded is not written by the
    // kernel but formed on first read (_make_pixel_batch): the degrees of
    // freedom of all tests but Welch's (without NaN left out), the variance
    // tests' standard error (NaN)
    const bool var = a.kind == Kind::V1 || a.kind == Kind::V2;
    const bool const_df = a.kind != Kind::T2 && !a.omit_nan;
    py::array_t<double> pv = arr(0.0), stat = arr(0.0), est = arr(0.0);
    py::array_t<double> df, se, df2, est2, lo, hi, c0, c1;
    py::array_t<int32_t> status = arr(int32_t{0});
    py::array_t<int8_t> decision = arr(int8_t{0});
    py::array_t<uint64_t> n_x, n_y;
    mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
    out.p_value = pv.mutable_data();
    out.statistic = stat.mutable_data();
    if (!const_df) {
        df = arr(0.0);
        out.df = df.mutable_data();
    }
    out.estimate = est.mutable_data();
    if (!var) {
        se = arr(0.0);
        out.std_error = se.mutable_data();
    }
    out.status = status.mutable_data();
    out.decision = decision.mutable_data();
    if (a.kind == Kind::V2 && !const_df) {
        df2 = arr(0.0);
        out.df2 = df2.mutable_data();
    }
    if (a.kind == Kind::T2 || a.kind == Kind::T2P) {
        est2 = arr(0.0);
        out.estimate2 = est2.mutable_data();
    }
    if (a.intervals) {
        lo = arr(0.0);
        hi = arr(0.0);
        c0 = arr(0.0);
        c1 = arr(0.0);
        out.conf_lo = lo.mutable_data();
        out.conf_hi = hi.mutable_data();
        out.critical_lo = c0.mutable_data();
        out.critical_hi = c1.mutable_data();
    }
    if (a.omit_nan) { // the sizes differ by pixel only when NaN are left out
        n_x = arr(uint64_t{0});
        out.n_x = n_x.mutable_data();
        if (two) {
            n_y = arr(uint64_t{0});
            out.n_y = n_y.mutable_data();
        }
    }
    mcstat_pixels_options opt = MCSTAT_PIXELS_OPTIONS_INIT;
    opt.flags = (a.intervals ? 0u : MCSTAT_ROWS_NO_INTERVALS) | (a.omit_nan ? MCSTAT_ROWS_OMIT_NAN : 0u);
    opt.threads = std::min(a.threads > 0 ? a.threads : num_threads(), 64);
    int test = test_code(a.kind);
    // the arguments on an empty range first: theirs raise, a pixel's only sets its status
    int st = mcstat_pixels_test(test, &px, two ? &py_ : nullptr, 0, 0, a.null_value, a.alternative, a.alpha, &opt,
                                &out);
    if (st)
        throw_status(st, "mcstat_pixels_test");
    {
        py::gil_scoped_release nogil;
        st = mcstat_pixels_test(test, &px, two ? &py_ : nullptr, 0, rows, a.null_value, a.alternative, a.alpha, &opt,
                                &out);
    }
    py::dict f;
    f["pvalue"] = pv;
    f["statistic"] = stat;
    f["df"] = const_df ? py::none() : py::object(df);
    f["df2"] = a.kind == Kind::V2 && !const_df ? py::object(df2) : py::none();
    if (const_df) { // the df of a pixel that succeeded
        double nx = static_cast<double>(px.n), ny = two ? static_cast<double>(py_.n) : 0.0;
        if (a.kind == Kind::V2)
            f["df_const"] = py::make_tuple(nx - 1.0, ny - 1.0);
        else
            f["df_const"] = py::make_tuple(a.kind == Kind::T2P ? nx + ny - 2.0 : nx - 1.0);
    }
    f["std_error"] = var ? py::none() : py::object(se);
    f["estimate"] = est;
    f["estimate2"] = a.kind == Kind::T2 || a.kind == Kind::T2P ? py::object(est2) : py::none();
    f["conf_lo"] = a.intervals ? py::object(lo) : py::none();
    f["conf_hi"] = a.intervals ? py::object(hi) : py::none();
    f["critical_lo"] = a.intervals ? py::object(c0) : py::none();
    f["critical_hi"] = a.intervals ? py::object(c1) : py::none();
    f["status"] = status;
    f["decision"] = decision;
    f["n_x"] = a.omit_nan ? py::object(n_x) : py::int_(px.n);
    f["n_y"] = !two_out ? py::none() : a.omit_nan ? py::object(n_y) : py::int_(py_.n);
    py::object nan_rows = py::none();
    if (a.propagate_nan && st != MCSTAT_OK) { // only a failed pixel can be a NaN row to excuse
        py::object isnan = np.attr("isnan");
        py::object m = isnan(xv).attr("any")(-1);
        if (two)
            m = m.attr("__or__")(isnan(yv).attr("any")(-1));
        nan_rows = m;
    }
    static py::object make = py::module_::import("mcstat._result").attr("_make_pixel_batch");
    return make(kind_name(a.kind), f, a.alternative, a.alpha, a.null_value, a.errors_as_nan, a.intervals,
                py::arg("nan_rows") = nan_rows, py::arg("all_ok") = st == MCSTAT_OK);
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
