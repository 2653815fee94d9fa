// ks.cpp - ks_test (two-sample Kolmogorov-Smirnov, unweighted or with
// Canner's weight) and KSCache (simulated null distributions kept for reuse).
//
// Thin over mcstat_ks_test_2: this file parses arguments (vectorcall, like
// t_test), chooses the seed when none is given, and releases the GIL for the
// whole test (sorting, exact recursion or simulation all run in C, the
// simulation on its own threads).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <algorithm>
#include <iterator>
#include <vector>
#include "kwargs.hpp"
#include "docs.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace mcs {

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

constexpr size_t DEFAULT_CACHE_BYTES = size_t{256} << 20;

// 64 bits from the operating system's entropy source (getrandom/urandom
// behind std::random_device on Linux).
uint64_t entropy_seed()
{
    std::random_device rd;
    return (static_cast<uint64_t>(rd()) << 32) ^ static_cast<uint64_t>(rd());
}

// A Python int in [0, 2^64) (numpy integers too); TypeError / InvalidArgumentError.
uint64_t get_u64(PyObject *o, const char *name)
{
    return mcs_kwargs::to_u64(o, name, [](const std::string &m) { throw_invalid(m); });
}

// A Python int as int64 (TypeError for other types).
int64_t get_i64(PyObject *o, const char *name)
{
    if (PyBool_Check(o) || !PyIndex_Check(o))
        throw py::type_error(std::string(name) + " must be an int, got " + repr(o));
    py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(o));
    if (!i)
        throw py::error_already_set();
    int overflow = 0;
    long long v = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (v == -1 && PyErr_Occurred())
        throw py::error_already_set();
    if (overflow)
        return overflow > 0 ? INT64_MAX : INT64_MIN;
    return static_cast<int64_t>(v);
}

} // namespace

// The Python object behind mcstat.KSCache.
struct KSCache {
    mcstat_ks_cache *c = nullptr;
    size_t max_bytes = 0;
    uint64_t seed = 0;

    KSCache(size_t bytes, uint64_t s) : max_bytes(bytes), seed(s)
    {
        int st = mcstat_ks_cache_new(bytes, &c);
        if (st)
            throw_status(st, "creating a KSCache");
    }
    KSCache(const KSCache &) = delete;
    KSCache &operator=(const KSCache &) = delete;
    ~KSCache() { mcstat_ks_cache_free(c); }

    void stats(uint64_t &hits, uint64_t &misses, uint64_t &entries) const
    {
        mcstat_ks_cache_stats(c, &hits, &misses, &entries);
    }
};

namespace {

struct KSParsed {
    PyObject *x = nullptr, *y = nullptr;
    PyObject *weight = nullptr, *alternative = nullptr, *alpha = nullptr, *method = nullptr;
    PyObject *n_sim = nullptr, *seed = nullptr, *threads = nullptr, *cache = nullptr, *critical = nullptr;
    PyObject *nan_policy = nullptr;
};

void ks_parse(PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames, KSParsed &p)
{
    mcs_kwargs::parse("ks_test", args, nargs, kwnames, {{"x", &p.x}, {"y", &p.y}},
                      {{"weight", &p.weight}, {"alternative", &p.alternative}, {"alpha", &p.alpha},
                       {"method", &p.method}, {"n_sim", &p.n_sim}, {"seed", &p.seed}, {"threads", &p.threads},
                       {"cache", &p.cache}, {"critical", &p.critical}, {"nan_policy", &p.nan_policy}});
    if (!p.x || !p.y)
        throw py::type_error(std::string("ks_test() missing required argument '") + (p.x ? "y" : "x") + "'");
    if (p.x == Py_None || p.y == Py_None)
        throw py::type_error("ks_test(): x and y must be array-like, not None");
}

// A 1-D C-contiguous float64 view (a copy only when needed).
carray sample_of(PyObject *o, const char *name)
{
    carray a = as_contiguous_array(o, name);
    if (a.ndim() != 1)
        throw_invalid(std::string("ks_test takes 1-D samples; ") + name + " is " + std::to_string(a.ndim()) + "-D");
    return a;
}

PyObject *ks_test(PyObject *, PyObject *const *args, Py_ssize_t nargs, PyObject *kwnames)
{
    return guarded([&]() -> py::object {
        KSParsed p;
        ks_parse(args, nargs, kwnames, p);
        mcstat_ks_options o;
        mcstat_ks_options_init(&o);

        if (p.weight) {
            const char *s = get_str(p.weight, "weight");
            if (!std::strcmp(s, "none"))
                o.weight = MCSTAT_KS_WEIGHT_NONE;
            else if (!std::strcmp(s, "canner"))
                o.weight = MCSTAT_KS_WEIGHT_CANNER;
            else
                throw_invalid(std::string("weight must be 'none' or 'canner', got '") + s + "'");
        }
        int alternative = p.alternative ? parse_alternative(p.alternative) : MCSTAT_TWO_SIDED;
        double alpha = p.alpha ? get_double(p.alpha, "alpha") : 0.05;
        if (!(alpha > 0.0 && alpha < 1.0))
            throw_invalid("alpha must be in (0, 1), got " + repr(p.alpha));
        if (p.method) {
            const char *s = get_str(p.method, "method");
            if (!std::strcmp(s, "auto"))
                o.method = MCSTAT_METHOD_AUTO;
            else if (!std::strcmp(s, "exact"))
                o.method = MCSTAT_METHOD_EXACT;
            else if (!std::strcmp(s, "simulate"))
                o.method = MCSTAT_METHOD_SIMULATE;
            else if (!std::strcmp(s, "asymptotic"))
                o.method = MCSTAT_METHOD_ASYMPTOTIC;
            else
                throw_invalid(std::string("method must be 'auto', 'exact', 'simulate' or 'asymptotic', got '") + s +
                              "'");
        }
        if (o.method == MCSTAT_METHOD_ASYMPTOTIC && o.weight == MCSTAT_KS_WEIGHT_CANNER)
            throw_invalid("method='asymptotic' needs weight='none': Canner's statistic has no usable limit "
                          "(its p-values would be off by factors at any size); use 'exact' or 'simulate'");
        // Simulation's arguments where nothing is simulated are refused, not
        // ignored.  (A cache is accepted: a battery shares one across
        // methods, and exact tests never touch it.)
        if (o.method == MCSTAT_METHOD_EXACT || o.method == MCSTAT_METHOD_ASYMPTOTIC) {
            const char *m = o.method == MCSTAT_METHOD_EXACT ? "exact" : "asymptotic";
            if (p.n_sim && p.n_sim != Py_None)
                throw_invalid(std::string("n_sim applies to method='simulate' or 'auto' (when it simulates), not "
                                          "method='") + m + "'");
            if (p.seed && p.seed != Py_None)
                throw_invalid(std::string("seed applies to method='simulate' or 'auto' (when it simulates), not "
                                          "method='") + m + "'");
        }
        if (p.n_sim && p.n_sim != Py_None) {
            int64_t n = get_i64(p.n_sim, "n_sim");
            if (n < 1)
                throw_invalid("n_sim must be a positive int, got " + repr(p.n_sim));
            o.n_sim = n;
        }
        o.threads = num_threads();
        if (p.threads && p.threads != Py_None) {
            int64_t t = get_i64(p.threads, "threads");
            if (t < 1 || t > 64)
                throw_invalid("threads must be in 1..64, got " + repr(p.threads));
            o.threads = static_cast<int32_t>(t);
        }
        o.threads = o.threads < 1 ? 1 : o.threads > 64 ? 64 : o.threads;
        py::object cache_ref; // keeps the cache alive while the GIL is released
        const KSCache *cache = nullptr;
        if (p.cache && p.cache != Py_None) {
            cache_ref = py::reinterpret_borrow<py::object>(p.cache);
            try {
                cache = &cache_ref.cast<const KSCache &>();
            } catch (py::cast_error &) {
                throw py::type_error("cache must be an mcstat.KSCache, got " + repr(p.cache));
            }
            o.cache = cache->c;
        }
        // The seed: given; else the cache's (so that a battery of tests
        // shares one simulated distribution); else fresh entropy, reported
        // in the result so that the run can be repeated.
        if (p.seed && p.seed != Py_None)
            o.seed = get_u64(p.seed, "seed");
        else
            o.seed = cache ? cache->seed : entropy_seed();
        if (p.critical) {
            int t = PyObject_IsTrue(p.critical);
            if (t < 0)
                throw py::error_already_set();
            o.critical = t != 0;
        }

        // nan_policy: "raise" (libmcstat refuses NaN), "omit" (dropped here)
        // or "propagate" (a NaN result, decided here: libmcstat never
        // returns NaN with success)
        int nan_policy = 0;
        if (p.nan_policy) {
            const char *s = get_str(p.nan_policy, "nan_policy");
            if (!std::strcmp(s, "omit"))
                nan_policy = 1;
            else if (!std::strcmp(s, "propagate"))
                nan_policy = 2;
            else if (std::strcmp(s, "raise"))
                throw_invalid(std::string("nan_policy must be 'raise', 'omit' or 'propagate', got '") + s + "'");
        }
        carray xa = sample_of(p.x, "x"), ya = sample_of(p.y, "y");
        const double *x = xa.data(), *y = ya.data();
        size_t nx = static_cast<size_t>(xa.size()), ny = static_cast<size_t>(ya.size());
        std::vector<double> kx, ky;
        auto nan_in = [](const double *v, size_t n) {
            return std::any_of(v, v + n, [](double a) { return std::isnan(a); });
        };
        Result res;
        if (nan_policy == 2 && (nan_in(x, nx) || nan_in(y, ny))) {
            mcstat_result &r = res.r;
            std::memset(&r, 0, sizeof r);
            r.test = MCSTAT_TEST_KS_2;
            r.method = o.method == MCSTAT_METHOD_AUTO ? MCSTAT_METHOD_EXACT : o.method;
            r.alternative = alternative;
            r.alpha = alpha;
            r.n[0] = nx;
            r.n[1] = ny;
            r.ks_weight = o.weight;
            r.statistic = r.df[0] = r.df[1] = r.p_value = r.p_value_se = NAN;
            r.conf_int[0] = r.conf_int[1] = r.estimate[0] = r.estimate[1] = r.null_value = NAN;
            r.critical[0] = r.critical[1] = r.std_error = r.ks_critical_se = NAN;
            return make_result(res);
        }
        if (nan_policy == 1) {
            std::copy_if(x, x + nx, std::back_inserter(kx), [](double a) { return !std::isnan(a); });
            std::copy_if(y, y + ny, std::back_inserter(ky), [](double a) { return !std::isnan(a); });
            if (kx.size() != nx) {
                x = kx.data();
                nx = kx.size();
            }
            if (ky.size() != ny) {
                y = ky.data();
                ny = ky.size();
            }
        }
        int st;
        {
            py::gil_scoped_release nogil;
            st = mcstat_ks_test_2(x, nx, y, ny, alternative, alpha, &o, &res.r);
        }
        if (st) {
            std::string detail;
            if (st == MCSTAT_ETOOFEW)
                detail = "x has " + std::to_string(nx) + " values, y has " + std::to_string(ny);
            else if (st == MCSTAT_ENONFINITE)
                detail = "NaN in the data; infinities are allowed";
            else if (st == MCSTAT_ETOOBIG && o.method == MCSTAT_METHOD_EXACT)
                detail = std::to_string(nx) + " + " + std::to_string(ny) + " values: use method='simulate'" +
                         (o.weight == MCSTAT_KS_WEIGHT_NONE ? " or 'asymptotic'" : "");
            throw_status(st, detail);
        }
        res.has_seed = res.r.method == MCSTAT_METHOD_SIMULATE;
        res.seed = o.seed;
        return make_result(res);
    });
}

PyMethodDef ks_methods[] = {{"ks_test", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)(void)>(ks_test)),
                             METH_FASTCALL | METH_KEYWORDS, KS_TEST_DOC},
                            {nullptr, nullptr, 0, nullptr}};

} // namespace

void register_ks(py::module_ &mod)
{
    py::class_<KSCache>(mod, "KSCache", KS_CACHE_DOC)
        .def(py::init([](py::object max_bytes, py::object seed) {
                 size_t bytes = DEFAULT_CACHE_BYTES;
                 if (!max_bytes.is_none())
                     bytes = static_cast<size_t>(get_u64(max_bytes.ptr(), "max_bytes"));
                 uint64_t s = seed.is_none() ? entropy_seed() : get_u64(seed.ptr(), "seed");
                 return new KSCache(bytes, s);
             }),
             py::arg("max_bytes") = py::none(), py::arg("seed") = py::none())
        .def_property_readonly("seed", [](const KSCache &c) { return c.seed; },
                               "The seed of tests that use this cache without a seed of their own.")
        .def_property_readonly("max_bytes", [](const KSCache &c) { return c.max_bytes; },
                               "Memory limit of the entries (least recently used are dropped beyond it).")
        .def_property_readonly("hits", [](const KSCache &c) {
            uint64_t h, m, e;
            c.stats(h, m, e);
            return h;
        }, "Lookups that found a simulated distribution.")
        .def_property_readonly("misses", [](const KSCache &c) {
            uint64_t h, m, e;
            c.stats(h, m, e);
            return m;
        }, "Lookups that did not (each was then simulated and stored).")
        .def_property_readonly("entries", [](const KSCache &c) {
            uint64_t h, m, e;
            c.stats(h, m, e);
            return e;
        }, "Simulated distributions held.")
        .def("__repr__", [](const KSCache &c) {
            uint64_t h, m, e;
            c.stats(h, m, e);
            return "<KSCache seed=" + std::to_string(c.seed) + ", " + std::to_string(e) + " entries, " +
                   std::to_string(h) + " hits, " + std::to_string(m) + " misses, max_bytes=" +
                   std::to_string(c.max_bytes) + ">";
        });

    for (PyMethodDef *d = ks_methods; d->ml_name; d++) {
        PyObject *f = PyCFunction_NewEx(d, mod.ptr(), mod.attr("__name__").ptr());
        if (!f)
            throw py::error_already_set();
        mod.add_object(d->ml_name, py::reinterpret_steal<py::object>(f));
    }
}

} // namespace mcs
