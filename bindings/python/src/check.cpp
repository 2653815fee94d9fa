// check.cpp - check_bsdf, check_emitter, check_warp: the renderer checks of
// libmcstat (mcstat_check_*), with Python callables as the callbacks, and
// CheckReport, the C report behind read-only attributes.  Every number,
// decision and sentence comes from the C library; this file moves arrays.
//
// Callbacks run with the GIL held, on the calling thread.  A callable that
// raises stops the check: the C callback returns non-zero, and the
// original exception is re-raised with a note naming the callback.  One that
// returns the wrong shape or type stops it with CallbackError naming the
// callable, the shape it gave and the shape expected.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"
#include "kwargs.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace mcs {

namespace {

struct Callbacks {
    py::object sample, eval, pdf, lobes;
    int kind = MCSTAT_CHECK_KIND_BSDF;
    bool has_wi = true; // BSDFs and phase functions: callables take wi first
    int dims = 3, nu = 3;
    py::object wi; // ndarray (3,) for BSDFs
    // the first failure inside a callback: a Python exception, or our message
    bool failed = false;
    py::object exc_type, exc_value, exc_tb;
    std::string message;
};

void remember_python_error(Callbacks *cb, const char *which)
{
    PyObject *t, *v, *tb;
    PyErr_Fetch(&t, &v, &tb);
    PyErr_NormalizeException(&t, &v, &tb);
    cb->exc_type = py::reinterpret_steal<py::object>(t);
    cb->exc_value = py::reinterpret_steal<py::object>(v ? v : Py_None);
    if (!v)
        Py_INCREF(Py_None);
    cb->exc_tb = py::reinterpret_steal<py::object>(tb ? tb : Py_None);
    if (!tb)
        Py_INCREF(Py_None);
    cb->failed = true;
    cb->message = std::string("the ") + which + " callable raised";
}

void remember_message(Callbacks *cb, const std::string &msg)
{
    cb->failed = true;
    cb->message = msg;
}

std::string shape_of(const py::array &a)
{
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); i++)
        s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

// A float64 copy of what a callable returned, of n values per row of k rows
// (n == 0: shape (k,)); false with a message when it cannot be.
bool to_rows(Callbacks *cb, const char *which, const char *what, py::handle obj, size_t k, int n, double *out)
{
    py::array a;
    try {
        a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    } catch (py::error_already_set &) {
        PyErr_Clear();
    }
    if (!a) {
        // objects that only know __array__ (array libraries' tensors)
        try {
            py::object np = py::module_::import("numpy");
            a = np.attr("asarray")(obj, "float64");
            a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
        } catch (py::error_already_set &) {
            PyErr_Clear();
        }
    }
    if (!a) {
        remember_message(cb, std::string(which) + " returned " + what + " of type " +
                                 std::string(py::str(py::type::of(obj).attr("__name__"))) +
                                 ", which is not an array of numbers");
        return false;
    }
    bool ok;
    if (n == 0 || n == 1)
        ok = (a.ndim() == 1 && static_cast<size_t>(a.shape(0)) == k) ||
             (n == 1 && a.ndim() == 2 && static_cast<size_t>(a.shape(0)) == k && a.shape(1) == 1);
    else
        ok = a.ndim() == 2 && static_cast<size_t>(a.shape(0)) == k && a.shape(1) == n;
    if (!ok) {
        std::string want = n == 0 || n == 1 ? "(" + std::to_string(k) + ",)"
                                            : "(" + std::to_string(k) + ", " + std::to_string(n) + ")";
        remember_message(cb, std::string(which) + " returned " + what + " of shape " + shape_of(a) +
                                 ", expected " + want);
        return false;
    }
    std::memcpy(out, a.data(), k * static_cast<size_t>(n == 0 ? 1 : n) * sizeof(double));
    return true;
}

py::array rows_array(const double *x, size_t k, int n)
{
    if (n == 1)
        return py::array_t<double>({static_cast<py::ssize_t>(k)}, x);
    return py::array_t<double>({static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(n)}, x);
}

int sample_cb(void *user, const double *, const double *u, size_t n, double *x, double *weight, double *pdf)
{
    auto *cb = static_cast<Callbacks *>(user);
    try {
        py::array ua = py::array_t<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(cb->nu)}, u);
        py::object r = cb->has_wi ? cb->sample(cb->wi, ua) : cb->sample(ua);
        if (cb->kind == MCSTAT_CHECK_KIND_WARP) {
            return to_rows(cb, "sample", "points", r, n, cb->dims, x) ? 0 : 1;
        }
        if (!py::isinstance<py::tuple>(r) || py::len(r) != 3) {
            remember_message(cb, "sample returned " + std::string(py::str(py::type::of(r).attr("__name__"))) +
                                     ", expected a tuple (points, weight, pdf)");
            return 1;
        }
        py::tuple t = r;
        if (!to_rows(cb, "sample", "points", t[0], n, cb->dims, x) ||
            !to_rows(cb, "sample", "weight", t[1], n, 0, weight) || !to_rows(cb, "sample", "pdf", t[2], n, 0, pdf))
            return 1;
        return 0;
    } catch (py::error_already_set &e) {
        e.restore();
        remember_python_error(cb, "sample");
        return 1;
    }
}

int density_cb(Callbacks *cb, py::object &fn, const char *which, const double *wi, const double *x, size_t n,
               double *out)
{
    try {
        py::array xa = rows_array(x, n, cb->dims);
        py::object r;
        if (cb->has_wi) {
            // wi is the check's own direction, or (reciprocity) a sampled one
            r = fn(py::array_t<double>({3}, wi), xa);
        } else {
            r = fn(xa);
        }
        return to_rows(cb, which, "values", r, n, 0, out) ? 0 : 1;
    } catch (py::error_already_set &e) {
        e.restore();
        remember_python_error(cb, which);
        return 1;
    }
}

int pdf_cb(void *user, const double *wi, const double *x, size_t n, double *out)
{
    auto *cb = static_cast<Callbacks *>(user);
    return density_cb(cb, cb->pdf, "pdf", wi, x, n, out);
}

int eval_cb(void *user, const double *wi, const double *x, size_t n, double *out)
{
    auto *cb = static_cast<Callbacks *>(user);
    return density_cb(cb, cb->eval, "eval", wi, x, n, out);
}

// lobes(wi) -> (directions (K, 3), mass (K,), value (K,)), K <= MCSTAT_CHECK_MAX_LOBES
int lobes_cb(void *user, const double *wi, double *x, double *mass, double *value, size_t *count)
{
    auto *cb = static_cast<Callbacks *>(user);
    try {
        py::object r = cb->lobes(py::array_t<double>({3}, wi));
        if (!py::isinstance<py::tuple>(r) || py::len(r) != 3) {
            remember_message(cb, "lobes returned " + std::string(py::str(py::type::of(r).attr("__name__"))) +
                                     ", expected a tuple (directions, mass, value)");
            return 1;
        }
        py::tuple t = r;
        py::array d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t[0]);
        if (!d || d.ndim() != 2 || d.shape(1) != 3) {
            remember_message(cb, "lobes returned directions " +
                                     (d ? "of shape " + shape_of(d) : std::string("that are not an array")) +
                                     ", expected (k, 3)");
            return 1;
        }
        size_t k = static_cast<size_t>(d.shape(0));
        if (k > MCSTAT_CHECK_MAX_LOBES) {
            remember_message(cb, "lobes returned " + std::to_string(k) + " lobes: at most " +
                                     std::to_string(MCSTAT_CHECK_MAX_LOBES));
            return 1;
        }
        std::memcpy(x, d.data(), k * 3 * sizeof(double));
        if (!to_rows(cb, "lobes", "mass", t[1], k, 0, mass) || !to_rows(cb, "lobes", "value", t[2], k, 0, value))
            return 1;
        *count = k;
        return 0;
    } catch (py::error_already_set &e) {
        e.restore();
        remember_python_error(cb, "lobes");
        return 1;
    }
}

// ---- the report -----------------------------------------------------------------

struct Route {
    mcstat_check_route_result r;
    int index;
};

struct Report {
    mcstat_check_report r;
};

py::object nan_to_none(double v)
{
    return std::isnan(v) ? py::none() : py::object(py::float_(v));
}

const char *state_name(int s)
{
    return s == MCSTAT_CHECK_STATE_RAN ? "ran" : (s == MCSTAT_CHECK_STATE_SKIPPED ? "skipped" : "invalid");
}

std::string report_text(const mcstat_check_report &r)
{
    size_t len = 0;
    mcstat_check_format(&r, nullptr, 0, &len);
    std::string s(len + 1, '\0');
    mcstat_check_format(&r, &s[0], s.size(), nullptr);
    s.resize(len);
    return s;
}

// "'a', 'b', ..." from a C name function (the library's names, not a copy)
std::string choices_of(const char *(*name_of)(int))
{
    std::string out;
    for (int i = 0; name_of(i); i++)
        out += (i ? ", '" : "'") + std::string(name_of(i)) + "'";
    return out;
}

int parse_enum(PyObject *o, const char *name, int (*parse)(const char *, int *), const std::string &choices)
{
    const char *s = get_str(o, name);
    int v;
    if (parse(s, &v) != MCSTAT_OK)
        throw_invalid(std::string(name) + " must be one of " + choices + ", got '" + s + "'");
    return v;
}

int parse_weight(const char *s, int *v)
{
    if (std::string(s) == "over_pdf")
        *v = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    else if (std::string(s) == "value")
        *v = MCSTAT_CHECK_WEIGHT_VALUE;
    else
        return MCSTAT_EINVAL;
    return MCSTAT_OK;
}

uint64_t get_count(py::handle o, const char *name)
{
    if (PyBool_Check(o.ptr()) || !PyIndex_Check(o.ptr()))
        throw py::type_error(std::string(name) + " must be an int, got " + repr(o.ptr()));
    py::int_ v = py::reinterpret_steal<py::int_>(PyNumber_Index(o.ptr()));
    int overflow = 0;
    long long t = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (overflow || t < 0)
        throw_invalid(std::string(name) + " must be a non-negative int below 2^63, got " + repr(o.ptr()));
    return static_cast<uint64_t>(t);
}

void check_callable(py::handle f, const char *name)
{
    if (!PyCallable_Check(f.ptr()))
        throw py::type_error(std::string(name) + " must be callable, got " + repr(f.ptr()));
}

py::object run(int kind, py::object sample, py::object eval, py::object pdf, py::object wi, py::dict kw)
{
    auto get = [&](const char *key, py::object dflt) -> py::object {
        return kw.contains(key) ? py::object(kw[key]) : dflt;
    };
    Callbacks cb;
    cb.kind = kind;
    cb.has_wi = kind == MCSTAT_CHECK_KIND_BSDF || kind == MCSTAT_CHECK_KIND_PHASE;
    const char *fname = kind == MCSTAT_CHECK_KIND_BSDF      ? "check_bsdf"
                        : kind == MCSTAT_CHECK_KIND_EMITTER ? "check_emitter"
                        : kind == MCSTAT_CHECK_KIND_PHASE   ? "check_phase"
                        : kind == MCSTAT_CHECK_KIND_MEDIUM  ? "check_medium"
                                                            : "check_warp";
    check_callable(sample, "sample");
    check_callable(pdf, "pdf");
    if (kind != MCSTAT_CHECK_KIND_WARP)
        check_callable(eval, "eval");
    cb.sample = sample;
    cb.eval = eval;
    cb.pdf = pdf;

    mcstat_check_model m{};
    const char *domain_default = kind == MCSTAT_CHECK_KIND_WARP     ? "square"
                                 : kind == MCSTAT_CHECK_KIND_MEDIUM ? "interval"
                                                                    : "sphere";
    m.domain = parse_enum(get("domain", py::str(domain_default)).ptr(), "domain", mcstat_check_domain_parse,
                          choices_of(mcstat_check_domain_name));
    cb.dims = mcstat_check_domain_dims(m.domain);
    int nu_default = kind == MCSTAT_CHECK_KIND_BSDF ? 3 : (m.domain == MCSTAT_CHECK_DOMAIN_INTERVAL ? 1 : 2);
    if (kind == MCSTAT_CHECK_KIND_PHASE)
        nu_default = 2;
    uint64_t nu = get_count(get("n_uniforms", py::int_(nu_default)), "n_uniforms");
    cb.nu = m.n_uniforms = nu > static_cast<uint64_t>(INT32_MAX) ? INT32_MAX : static_cast<int>(nu); // C's range
    m.weight = parse_enum(get("weight", py::str("over_pdf")).ptr(), "weight", parse_weight, "'over_pdf', 'value'");
    m.sample_reports = kind == MCSTAT_CHECK_KIND_WARP ? 0 : 1;
    m.user = &cb;
    m.sample = sample_cb;
    m.pdf = pdf_cb;
    m.eval = kind == MCSTAT_CHECK_KIND_WARP ? nullptr : eval_cb;
    if (kw.contains("lobes") && !py::object(kw["lobes"]).is_none()) {
        if (kind != MCSTAT_CHECK_KIND_BSDF)
            throw py::type_error(std::string(fname) + "() got an unexpected keyword argument 'lobes'");
        cb.lobes = kw["lobes"];
        check_callable(cb.lobes, "lobes");
        m.lobes = lobes_cb;
    }
    double sigma_ref = 0.0;
    if (kind == MCSTAT_CHECK_KIND_MEDIUM) {
        if (!kw.contains("sigma_ref"))
            throw py::type_error("check_medium() missing required keyword argument 'sigma_ref'");
        sigma_ref = get_double(py::object(kw["sigma_ref"]).ptr(), "sigma_ref");
    }

    mcstat_check_options o;
    mcstat_check_options_init(&o);
    py::object routes = get("routes", py::none());
    if (!routes.is_none()) {
        if (py::isinstance<py::str>(routes))
            throw py::type_error("routes must be an iterable of route names, not a str");
        o.routes = 0;
        for (py::handle h : routes) {
            int r = parse_enum(h.ptr(), "routes", mcstat_check_route_parse, choices_of(mcstat_check_route_name));
            o.routes |= 1u << r;
        }
    }
    if (!py::bool_(get("energy", py::bool_(true))))
        o.routes &= ~(1u << MCSTAT_CHECK_ROUTE_ENERGY);
    o.stochastic = py::bool_(get("stochastic", py::bool_(false))) ? 1 : 0;
    o.reciprocal = py::bool_(get("reciprocal", py::bool_(false))) ? 1 : 0;
    // A route asked for by its flag but left out of `routes` would silently
    // not run: refused instead.
    if (!routes.is_none()) {
        if (o.reciprocal && !(o.routes & (1u << MCSTAT_CHECK_ROUTE_RECIPROCITY)))
            throw_invalid(std::string("reciprocal=True asks for the '") +
                          mcstat_check_route_name(MCSTAT_CHECK_ROUTE_RECIPROCITY) + "' route, which routes leaves out");
        if (kind != MCSTAT_CHECK_KIND_EMITTER && kind != MCSTAT_CHECK_KIND_WARP && kw.contains("energy") && py::bool_(kw["energy"]) &&
            !(o.routes & (1u << MCSTAT_CHECK_ROUTE_ENERGY)))
            throw_invalid(std::string("energy=True asks for the '") + mcstat_check_route_name(MCSTAT_CHECK_ROUTE_ENERGY) +
                          "' route, which routes leaves out");
    }
    // conversions only: the ranges are C's (its reason is raised below)
    uint64_t cells = get_count(get("cells", py::int_(0)), "cells");
    o.cells = cells > static_cast<uint64_t>(INT32_MAX) ? INT32_MAX : static_cast<int32_t>(cells);
    o.n_pilot = get_count(get("n_pilot", py::int_(0)), "n_pilot");
    o.n_eval = get_count(get("n_eval", py::int_(0)), "n_eval");
    o.batch = get_count(get("batch", py::int_(65536)), "batch");
    o.rtol = get_double(get("rtol", py::float_(1e-3)).ptr(), "rtol");
    o.tolerated = get_double(get("tolerated", py::float_(1e-4)).ptr(), "tolerated");
    o.resolution = get_double(get("resolution", py::float_(0.0)).ptr(), "resolution");

    // escape_transmittance, as C, Rust and Go name it; transmittance, 0.3's
    // Python name, is a deprecated alias until 0.4
    const char *esc = "escape_transmittance";
    if (kw.contains("transmittance") && !py::object(kw["transmittance"]).is_none()) {
        if (kw.contains(esc) && !py::object(kw[esc]).is_none())
            throw py::type_error(std::string(fname) + "() got both escape_transmittance and its old name transmittance");
        if (PyErr_WarnEx(PyExc_DeprecationWarning,
                         "transmittance= is now escape_transmittance= (its name in C, Rust and Go); the old name "
                         "goes in 0.4", 1) < 0)
            throw py::error_already_set();
        esc = "transmittance";
    }
    if (kw.contains(esc) && !py::object(kw[esc]).is_none()) {
        if (kind != MCSTAT_CHECK_KIND_MEDIUM)
            throw py::type_error(std::string(fname) + "() got an unexpected keyword argument '" + esc + "'");
        o.escape_transmittance = get_double(py::object(kw[esc]).ptr(), esc); // its range is C's
    }
    uint64_t n = get_count(get("n", py::int_(100000)), "n");
    uint64_t seed = mcs_kwargs::to_u64(get("seed", py::int_(0)).ptr(), "seed",
                                       [](const std::string &m) { throw_invalid(m); });
    double alpha = get_double(get("alpha", py::float_(0.01)).ptr(), "alpha");

    double wiv[3] = {0, 0, 1};
    if (cb.has_wi) {
        py::array a = as_float_array(wi, "wi");
        if (a.ndim() != 1 || a.shape(0) != 3)
            throw_invalid("wi must be a direction of 3 numbers, got shape " + shape_of(a));
        auto *d = static_cast<const double *>(a.data());
        // C refuses a wi that is not finite or is zero (its reason raised
        // below) and normalises it; the callbacks see the unit vector
        double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), unit[3];
        for (int c = 0; c < 3; c++) {
            wiv[c] = d[c];
            unit[c] = d[c] / len;
        }
        cb.wi = py::array_t<double>({3}, unit);
    }
    for (auto item : kw) {
        static const char *known[] = {"domain", "n_uniforms", "weight", "routes", "energy", "stochastic",
                                      "reciprocal", "cells", "n_pilot", "n_eval", "batch", "rtol", "tolerated", "n",
                                      "seed", "alpha", "sigma_ref", "lobes", "transmittance", "escape_transmittance",
                                      "resolution"};
        std::string k = py::str(item.first);
        if (k == "sigma_ref" && kind != MCSTAT_CHECK_KIND_MEDIUM)
            throw py::type_error(std::string(fname) + "() got an unexpected keyword argument 'sigma_ref'");
        bool ok = false;
        for (const char *s : known)
            ok = ok || k == s;
        if (!ok)
            throw py::type_error("unexpected keyword argument '" + k + "'");
    }

    Report rep{};
    int st;
    if (kind == MCSTAT_CHECK_KIND_BSDF)
        st = mcstat_check_bsdf(&m, wiv, n, seed, alpha, &o, nullptr, 0, &rep.r);
    else if (kind == MCSTAT_CHECK_KIND_EMITTER)
        st = mcstat_check_emitter(&m, n, seed, alpha, &o, nullptr, 0, &rep.r);
    else if (kind == MCSTAT_CHECK_KIND_PHASE)
        st = mcstat_check_phase(&m, wiv, n, seed, alpha, &o, nullptr, 0, &rep.r);
    else if (kind == MCSTAT_CHECK_KIND_MEDIUM)
        st = mcstat_check_medium(&m, sigma_ref, n, seed, alpha, &o, nullptr, 0, &rep.r);
    else
        st = mcstat_check_warp(&m, n, seed, alpha, &o, nullptr, 0, &rep.r);
    if (st == MCSTAT_ECALLBACK && cb.exc_type) {
        PyErr_Restore(cb.exc_type.release().ptr(), cb.exc_value.release().ptr(), cb.exc_tb.release().ptr());
        py::error_already_set e;
        // a note for the reader of the traceback (Python 3.11+)
        if (py::hasattr(e.value(), "add_note"))
            e.value().attr("add_note")(std::string("(raised inside mcstat's check: ") + cb.message + ")");
        throw e;
    }
    if (st == MCSTAT_ECALLBACK) {
        std::string msg = cb.failed ? cb.message : std::string(rep.r.message);
        PyErr_SetString(error_class(MCSTAT_ECALLBACK).ptr(), msg.c_str());
        throw py::error_already_set();
    }
    if (st)
        throw_refusal(st, fname);
    return py::cast(rep);
}

const char *BSDF_DOC = R"doc(check_bsdf(sample, eval, pdf, wi, *, n=100_000, alpha=0.01, seed=0, domain="sphere", n_uniforms=3, weight="over_pdf", stochastic=False, reciprocal=False, lobes=None, energy=True, routes=None, cells=0, n_pilot=0, n_eval=0, batch=65536, rtol=1e-3, tolerated=1e-4, resolution=0)

Do a BSDF's sample(), pdf(), eval() and sample weight agree?

A battery of checks ("routes") whose overall false-rejection rate is at
most alpha: chi-squared of the samples on cells of equal probability under
pdf() ("cells"), the mass of pdf() against the share of samples that
succeed ("mass"), the pdf sample() reports against pdf() ("pdf_value"),
the weight against eval/pdf ("weight"), eval() > 0 only where pdf() > 0
("support"), integrals of eval() over regions from the weights against an
eval-only estimator ("integrals"), albedo <= 1 ("energy"), the resampled
samples against rejection sampling from eval() by Canner's K-S ("ks") and,
when asked, reciprocity.  Deterministic routes reject on any point beyond rtol; the
statistical ones are Holm-adjusted across routes.  mcstat/check.h,
says what each route checks and cannot see.

Parameters
----------
sample : callable
    ``sample(wi, u) -> (wo, weight, pdf)``: wi an array (3,), u an array
    (k, n_uniforms) of uniforms in [0, 1) supplied by mcstat; wo (k, 3)
    directions in the shading frame (normal +z), weight (k,) the sample
    weight (eval/pdf, or eval with ``weight="value"``), pdf (k,) the density
    the sampler reports.  A failed sample has pdf 0 and weight 0.
eval : callable
    ``eval(wi, wo) -> (k,)``: f(wi, wo) ``|cos wo|`` (Mitsuba's eval).
pdf : callable
    ``pdf(wi, wo) -> (k,)``: the density, in solid angle.
wi : array_like (3,)
    The fixed direction (normalised here).
n : int
    Samples tested (>= 1000); the pilot (32 per cell) and the eval-only
    estimator (n_eval, default n) come on top.
alpha : float
    The level of the whole battery, in (0, 1).
seed : int
    The uniforms are a pure function of (seed, stream, index).
domain : str
    "sphere" (BSDFs with transmission) or "hemisphere" (reflection only).
stochastic : bool
    The weight and pdf are estimates (layered BSDFs): pdf_value and weight
    are skipped, "integrals" checks them statistically.
reciprocal : bool
    Check ``eval(wi, wo)/|cos wo| == eval(wo, wi)/|cos wi|`` at up to 1000
    sampled directions.
lobes : callable, optional
    Discrete (delta) lobes, for BSDFs whose sample() returns specular
    directions: ``lobes(wi) -> (directions, mass, value)``, directions
    (k, 3) with k <= 4, mass (k,) the probability sample() returns each
    (what it reports as pdf there), value (k,) the integral of ``f |cos wo|``
    over each (e.g. Fresnel's R).  eval and pdf are the smooth part only.
    A sample within 1e-4 of a lobe's direction is that lobe's: its pdf
    must equal the mass, its weight value/mass, and each lobe's count is
    tested against n mass ("mass"); the smooth routes see the rest.
energy : bool
    Check albedo <= 1 (turn off for BSDFs that scale radiance at
    refraction, e.g. Mitsuba's dielectrics in radiance mode).
routes : iterable of str, optional
    The routes to run (default: all that apply).  ``reciprocal=True`` (or
    an explicit ``energy=True``) with routes that leave its route out
    raises.
cells, n_pilot, n_eval, batch, rtol, tolerated
    Cells of the chi-squared (0: 2 n^0.4), pilot samples (0: 32 per cell),
    eval-only points (0: n), points per callback call, the deterministic
    routes' relative tolerance and the share of points they let differ
    beyond it (float32 renderers lose digits at grazing angles and miss a
    light's rim on a retraced point in ~1e-5 of samples).
resolution : float
    The relative resolution of the renderer's arithmetic: differences of
    integrals at that scale are rounding, not evidence (the statistical
    routes add it as an error of what they compare).  0 (default): derived
    from the values the callables return, ``2**-18`` (64 float32 ulps) when
    every pdf, weight and eval value is a float32, else ``2**-47``.

Returns
-------
CheckReport
    ``verdict`` ("consistent", "inconsistent" or "inconclusive": no route
    rejected but one the check needed could not answer, named in
    ``unanswered``), ``reject``, ``pvalue`` (smallest Holm-adjusted
    p-value; 0 when a deterministic route failed), ``routes`` (one
    CheckRoute each: name, state, why (when it could not answer),
    statistic, pvalue, p_adjusted, reject, effect, detectable, n_for_1pct,
    resolution, meaning, blind_spot), ``str(report)`` the text block.

Raises
------
CallbackError
    A callable returned the wrong shape, NaN, infinity, a negative density
    or weight, or a point off the domain; the message names it, the point
    and the value.  An exception raised by a callable propagates, with a
    note naming it.
InvalidArgumentError
    Bad arguments (n < 1000, alpha outside (0, 1), an unknown domain or
    route, ...).
)doc";

const char *EMITTER_DOC = R"doc(check_emitter(sample, eval, pdf, *, n=100_000, alpha=0.01, seed=0, domain="sphere", n_uniforms=2, weight="over_pdf", routes=None, cells=0, n_pilot=0, n_eval=0, batch=65536, rtol=1e-3, resolution=0)

Do an emitter's direction sampling, pdf and radiance agree (from a fixed
reference point)?  As check_bsdf without wi: ``sample(u) -> (d, weight,
pdf)`` with weight = radiance/pdf, ``eval(d)`` the radiance arriving along
d, ``pdf(d)`` the solid-angle density.  No energy or reciprocity routes.
)doc";

const char *WARP_DOC = R"doc(check_warp(sample, pdf, *, n=100_000, alpha=0.01, seed=0, domain="square", n_uniforms=2 (1 on "interval"), routes=None, cells=0, n_pilot=0, n_eval=0, batch=65536, resolution=0)

Does a warp draw what its density claims?  ``sample(u) -> points``, shape
(k, dims) (dims 3 on "sphere"/"hemisphere", 2 on "square"/"disk", 1 on
"interval": (k,) is accepted); ``pdf(points) -> (k,)``.  Runs the "cells"
and "mass" routes (the density must integrate to 1).
)doc";

const char *PHASE_DOC = R"doc(check_phase(sample, eval, pdf, wi, *, n=100_000, alpha=0.01, seed=0, n_uniforms=2, weight="over_pdf", stochastic=False, reciprocal=False, energy=True, routes=None, cells=0, n_pilot=0, n_eval=0, batch=65536, rtol=1e-3, tolerated=1e-4, resolution=0)

Do a phase function's sample(), pdf(), eval() and sample weight agree, and
is it normalised?  The routes of check_bsdf on the whole sphere, with
``eval(wi, wo)`` the phase function p itself (no cosine) and the weight
p/pdf (1 for an exactly sampled phase function).  What differs from
check_bsdf (mcstat_check_phase): "energy" tests that the albedo is 1
(two-sided; constant weights within rtol), not only at most 1, so a phase
function scaled by 0.9 together with its weight is caught; "reciprocity"
(``reciprocal=True``) compares p(wi, wo) with p(wo, wi), without cosines.
The callables and the report are those of check_bsdf; wi is the direction
the phase function is given (the renderer's convention: mcstat only holds it
fixed).
)doc";

const char *MEDIUM_DOC = R"doc(check_medium(sample, eval, pdf, *, sigma_ref, escape_transmittance=None, n=100_000, alpha=0.01, seed=0, n_uniforms=1, weight="over_pdf", routes=None, cells=0, n_pilot=0, n_eval=0, batch=65536, rtol=1e-3, tolerated=1e-4, resolution=0)

Does a medium's distance sampling along a ray agree with its density and
its weights?  ``sample(u) -> (t, weight, pdf)``: t (k,) distances >= 0 of
the sampled interactions, pdf (k,) their density in t (sigma_t
exp(-sigma_t t) for a homogeneous medium), weight (k,) the interaction's
weight (sigma_s T(t) / pdf, Mitsuba's); a flight that passes the surface at
tmax is a failed sample (pdf 0, weight 0).  ``pdf(t)`` the density
(0 beyond tmax), ``eval(t)`` the integrand the weight estimates, sigma_s
T(t).  Inside, t is mapped to x = 1 - exp(-sigma_ref t) on [0, 1]
(mcstat_check_medium) and checked by check_bsdf's routes: cells, mass (the
share of flights stopping before tmax against the integral of pdf(), so
the escape probability exp(-sigma_t tmax) is what is tested), pdf_value,
weight, support, integrals, energy (albedo <= 1), ks.  sigma_ref: a
positive coefficient near the medium's sigma_t (e.g. the majorant); t may
be asked at +inf.

escape_transmittance: None (default), the weight of a flight that passed the
surface is not checked (it must be 0).  A number in [0, 1], T(tmax), the
transmittance to the surface: such a flight reports pdf 0 and the weight
it carries on (1 for analog tracking, T(tmax)/P(escape) when the distances
follow another density), and "mass" also tests that the mean over the n
flights of the escapes' weights (0 for a scattering) equals T(tmax)
(report.escape_weight, escape_weight_se).
)doc";

int verdict_of(const mcstat_check_report &r)
{
    int v = MCSTAT_CHECK_INCONSISTENT;
    (void)mcstat_check_verdict(&r, &v, nullptr); // a report the library wrote: never refused
    return v;
}

} // namespace

void register_check(py::module_ &mod)
{
    // the derived numerical floors (mcstat.h), for mcstat.testing's exact estimators
    mod.attr("RESOLUTION_FLOAT32") = py::float_(MCSTAT_RESOLUTION_FLOAT32);
    mod.attr("RESOLUTION_FLOAT64") = py::float_(MCSTAT_RESOLUTION_FLOAT64);
    py::class_<Route>(mod, "CheckRoute", "One route of a renderer check (mcstat_check_route_result).")
        .def_property_readonly("name", [](const Route &r) { return mcstat_check_route_name(r.index); })
        .def_property_readonly("state", [](const Route &r) { return state_name(r.r.state); },
                               "'ran', 'skipped' (not asked or not applicable) or 'invalid' (an assumption "
                               "failed: no answer)")
        .def_property_readonly("deterministic", [](const Route &r) { return r.r.deterministic != 0; })
        .def_property_readonly("reject", [](const Route &r) { return r.r.reject != 0; })
        .def_property_readonly("statistic", [](const Route &r) { return nan_to_none(r.r.statistic); })
        .def_property_readonly("df", [](const Route &r) { return nan_to_none(r.r.df); })
        .def_property_readonly("pvalue", [](const Route &r) { return nan_to_none(r.r.p_value); })
        .def_property_readonly("p_adjusted", [](const Route &r) { return nan_to_none(r.r.p_adjusted); })
        .def_property_readonly("effect", [](const Route &r) { return nan_to_none(r.r.effect); })
        .def_property_readonly("detectable", [](const Route &r) { return nan_to_none(r.r.detectable); })
        .def_property_readonly("n_for_1pct", [](const Route &r) { return nan_to_none(r.r.n_for_1pct); })
        .def_property_readonly("checked", [](const Route &r) { return r.r.checked; })
        .def_property_readonly("count", [](const Route &r) { return r.r.count; })
        .def_property_readonly("where", [](const Route &r) {
            return py::make_tuple(nan_to_none(r.r.where[0]), nan_to_none(r.r.where[1]), nan_to_none(r.r.where[2]));
        })
        .def_property_readonly("values",
                               [](const Route &r) { return py::make_tuple(nan_to_none(r.r.value[0]),
                                                                          nan_to_none(r.r.value[1])); })
        .def_property_readonly("why", [](const Route &r) -> py::object {
            const char *t = mcstat_check_why_text(r.r.why);
            return r.r.state == MCSTAT_CHECK_STATE_INVALID && t ? py::object(py::str(t)) : py::none();
        }, "state 'invalid': why the route could not answer and what would let it (None otherwise).")
        .def_property_readonly("resolution", [](const Route &r) { return nan_to_none(r.r.resolution); },
                               "Statistical routes: the relative numerical floor applied (differences at that "
                               "scale are rounding, not evidence); None for the deterministic ones.")
        .def_property_readonly("meaning", [](const Route &r) { return mcstat_check_route_meaning(r.index); })
        .def_property_readonly("blind_spot", [](const Route &r) { return mcstat_check_route_blind_spot(r.index); })
        .def("__repr__", [](const Route &r) {
            std::string s = std::string("CheckRoute(") + mcstat_check_route_name(r.index) + ", " +
                            state_name(r.r.state);
            if (r.r.state == MCSTAT_CHECK_STATE_RAN)
                s += std::string(", ") + (r.r.reject ? "reject" : "pass");
            if (!std::isnan(r.r.p_value))
                s += ", p=" + std::string(py::str(py::float_(r.r.p_value)));
            return s + ")";
        });

    py::class_<Report>(mod, "CheckReport",
                       "The report of check_bsdf, check_emitter, check_warp, check_phase or check_medium.")
        .def_property_readonly("kind", [](const Report &r) {
            switch (r.r.kind) {
            case MCSTAT_CHECK_KIND_BSDF: return "bsdf";
            case MCSTAT_CHECK_KIND_EMITTER: return "emitter";
            case MCSTAT_CHECK_KIND_PHASE: return "phase";
            case MCSTAT_CHECK_KIND_MEDIUM: return "medium";
            default: return "warp";
            }
        })
        .def_property_readonly("sigma_ref", [](const Report &r) {
            return r.r.kind == MCSTAT_CHECK_KIND_MEDIUM ? py::object(py::float_(r.r.sigma_ref)) : py::none();
        }, "check_medium: the coefficient of the map x = 1 - exp(-sigma_ref t) (None otherwise).")
        .def_property_readonly("reject", [](const Report &r) { return r.r.reject != 0; })
        .def_property_readonly("verdict", [](const Report &r) { return mcstat_check_verdict_name(verdict_of(r.r)); },
                               "'consistent', 'inconsistent' (reject) or 'inconclusive': no route rejected but a "
                               "route the check needed could not answer (see unanswered).")
        .def_property_readonly("unanswered", [](const Report &r) {
            uint32_t mask = 0;
            int v;
            py::list l;
            if (mcstat_check_verdict(&r.r, &v, &mask) == MCSTAT_OK)
                for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
                    if (mask & (1u << i))
                        l.append(py::str(mcstat_check_route_name(i)));
            return l;
        }, "The names of the routes that could not answer and make the verdict 'inconclusive'.")
        .def_property_readonly("pvalue", [](const Report &r) { return r.r.p_value; })
        .def_property_readonly("alpha", [](const Report &r) { return r.r.alpha; })
        .def_property_readonly("domain", [](const Report &r) { return mcstat_check_domain_name(r.r.domain); })
        .def_property_readonly("wi", [](const Report &r) {
            return r.r.kind == MCSTAT_CHECK_KIND_BSDF || r.r.kind == MCSTAT_CHECK_KIND_PHASE
                       ? py::object(py::make_tuple(r.r.wi[0], r.r.wi[1], r.r.wi[2]))
                       : py::none();
        })
        .def_property_readonly("n", [](const Report &r) { return r.r.n; })
        .def_property_readonly("n_failed", [](const Report &r) { return r.r.n_failed; })
        .def_property_readonly("n_pilot", [](const Report &r) { return r.r.n_pilot; })
        .def_property_readonly("n_eval", [](const Report &r) { return r.r.n_eval; })
        .def_property_readonly("cells", [](const Report &r) { return r.r.cells; })
        .def_property_readonly("calls", [](const Report &r) { return r.r.calls; })
        .def_property_readonly("pdf_without_eval", [](const Report &r) { return r.r.pdf_without_eval; },
                               "Points where pdf() > 0 but eval() = 0 (samples wasted there; not an error).")
        .def_property_readonly("zero_weight", [](const Report &r) { return r.r.zero_weight; },
                               "Samples with weight 0 where the reported pdf and eval() are > 0, counted as successes (a sampler "
                               "that marks a failed sample by its weight alone shows here: it must return pdf 0).")
        .def_property_readonly("lobes", [](const Report &r) { return r.r.lobes; },
                               "Discrete lobes given by lobes() (0 without).")
        .def_property_readonly("n_lobe", [](const Report &r) { return r.r.n_lobe; },
                               "Tested samples that fell on a discrete lobe.")
        .def_property_readonly("lobe_mass", [](const Report &r) { return r.r.lobe_mass; },
                               "The sum of the discrete lobes' masses (probabilities).")
        .def_property_readonly("lobe_albedo", [](const Report &r) { return r.r.lobe_albedo; },
                               "The sum of the discrete lobes' values: the discrete part of the albedo.")
        .def_property_readonly("escape_weight", [](const Report &r) { return nan_to_none(r.r.escape_weight); },
                               "check_medium with escape_transmittance=: the mean over the n flights of the escapes' "
                               "weights (0 for a scattering), tested against it by the mass route (None otherwise).")
        .def_property_readonly("escape_weight_se", [](const Report &r) { return nan_to_none(r.r.escape_weight_se); },
                               "Its standard error (None with fewer than 2 escapes of weight > 0).")
        .def_property_readonly("mass_sampled", [](const Report &r) { return r.r.mass_sampled; })
        .def_property_readonly("mass_sampled_se", [](const Report &r) { return r.r.mass_sampled_se; })
        .def_property_readonly("mass", [](const Report &r) { return r.r.mass; })
        .def_property_readonly("mass_error", [](const Report &r) { return r.r.mass_error; })
        .def_property_readonly("albedo", [](const Report &r) { return nan_to_none(r.r.albedo); })
        .def_property_readonly("albedo_se", [](const Report &r) { return nan_to_none(r.r.albedo_se); })
        .def_property_readonly("albedo_eval", [](const Report &r) { return nan_to_none(r.r.albedo_eval); })
        .def_property_readonly("albedo_eval_se", [](const Report &r) { return nan_to_none(r.r.albedo_eval_se); })
        .def_property_readonly("tail_index", [](const Report &r) {
            return py::make_tuple(nan_to_none(r.r.tail_index[0]), nan_to_none(r.r.tail_index[1]));
        })
        .def_property_readonly("heavy_tailed", [](const Report &r) { return r.r.heavy_tailed != 0; })
        .def_property_readonly("routes", [](const Report &r) {
            py::list l;
            for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
                l.append(py::cast(Route{r.r.route[i], i}));
            return l;
        })
        .def("route", [](const Report &r, const std::string &name) {
            int i;
            if (mcstat_check_route_parse(name.c_str(), &i) != MCSTAT_OK)
                throw_invalid("no route named '" + name + "'");
            return Route{r.r.route[i], i};
        }, py::arg("name"), "The route of that name ('cells', 'mass', 'pdf_value', ...).")
        .def("__str__", [](const Report &r) { return report_text(r.r); })
        .def("__repr__", [](const Report &r) {
            return std::string("<CheckReport ") + mcstat_check_verdict_name(verdict_of(r.r)) +
                   ", p=" + std::string(py::str(py::float_(r.r.p_value))) + ">";
        })
        .def("__bool__", [](const Report &) -> bool {
            throw py::type_error("a CheckReport has no truth value: use report.reject");
        });

    mod.def(
        "check_bsdf",
        [](py::object sample, py::object eval, py::object pdf, py::object wi, py::kwargs kw) {
            return run(MCSTAT_CHECK_KIND_BSDF, sample, eval, pdf, wi, kw);
        },
        py::arg("sample"), py::arg("eval"), py::arg("pdf"), py::arg("wi"), BSDF_DOC);
    mod.def(
        "check_emitter",
        [](py::object sample, py::object eval, py::object pdf, py::kwargs kw) {
            for (const char *k : {"stochastic", "reciprocal", "energy"})
                if (kw.contains(k))
                    throw py::type_error(std::string("check_emitter() got an unexpected keyword argument '") + k +
                                         "'");
            kw["energy"] = py::bool_(false);
            return run(MCSTAT_CHECK_KIND_EMITTER, sample, eval, pdf, py::none(), kw);
        },
        py::arg("sample"), py::arg("eval"), py::arg("pdf"), EMITTER_DOC);
    mod.def(
        "check_warp",
        [](py::object sample, py::object pdf, py::kwargs kw) {
            for (const char *k : {"stochastic", "reciprocal", "energy", "weight"})
                if (kw.contains(k))
                    throw py::type_error(std::string("check_warp() got an unexpected keyword argument '") + k + "'");
            return run(MCSTAT_CHECK_KIND_WARP, sample, py::none(), pdf, py::none(), kw);
        },
        py::arg("sample"), py::arg("pdf"), WARP_DOC);
    mod.def(
        "check_phase",
        [](py::object sample, py::object eval, py::object pdf, py::object wi, py::kwargs kw) {
            if (kw.contains("domain"))
                throw py::type_error("check_phase() got an unexpected keyword argument 'domain' (always 'sphere')");
            return run(MCSTAT_CHECK_KIND_PHASE, sample, eval, pdf, wi, kw);
        },
        py::arg("sample"), py::arg("eval"), py::arg("pdf"), py::arg("wi"), PHASE_DOC);
    mod.def(
        "check_medium",
        [](py::object sample, py::object eval, py::object pdf, py::kwargs kw) {
            for (const char *k : {"stochastic", "reciprocal", "energy", "domain"})
                if (kw.contains(k))
                    throw py::type_error(std::string("check_medium() got an unexpected keyword argument '") + k + "'");
            return run(MCSTAT_CHECK_KIND_MEDIUM, sample, eval, pdf, py::none(), kw);
        },
        py::arg("sample"), py::arg("eval"), py::arg("pdf"), MEDIUM_DOC);
}

} // namespace mcs
