// estimators.cpp - mcstat._estimators: libmcest (the reference estimators of
// the paper's case studies) for Python; mcstat/estimators.py is its face.
//
// A second extension module rather than more of _core: libmcest is its own
// library (its own status codes, no GSL), optional in the build
// (MCSTAT_BUILD_ESTIMATORS), and the hypothesis tests must not depend on
// it.  As in _core the layer is thin: it converts arrays and arguments,
// maps mcest's status codes to the exceptions of mcstat.estimators, and
// splits batches over threads.  Every libmcest batch call is a pure
// function of (seed, first_index + k), so thread t computing the contiguous
// indices [t n / T, (t + 1) n / T) gives the numbers one call would:
// results never depend on the number of threads.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "mcest.h"
#include "real_array.hpp"
#include "kwargs.hpp"
#include "threads.hpp"

namespace py = pybind11;

namespace {

using carray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Batches shorter than this per thread run on fewer threads: starting a
// thread (~30 us) costs about what 1000-3000 estimates do.
constexpr size_t MIN_PER_THREAD = 8192;

// ---- errors -------------------------------------------------------------------

[[noreturn]] void throw_est(int status, const std::string &detail = std::string())
{
    py::module_ m = py::module_::import("mcstat.estimators");
    py::dict by_status = m.attr("_BY_STATUS");
    py::int_ key(status);
    py::object cls = by_status.contains(key) ? py::object(by_status[key]) : py::object(m.attr("EstimatorError"));
    // Python's words for a bad argument (the C sentence speaks of NULL
    // pointers), as mcstat's own errors (errors.cpp)
    std::string msg = status == MCEST_EINVAL ? "invalid argument" : mcest_strerror(status);
    if (!detail.empty())
        msg += " (" + detail + ")";
    PyErr_SetString(cls.ptr(), msg.c_str());
    throw py::error_already_set();
}

// A bad argument with a message of its own, naming it: the message alone.
[[noreturn]] void throw_invalid(const std::string &message)
{
    py::module_ m = py::module_::import("mcstat.estimators");
    py::dict by_status = m.attr("_BY_STATUS");
    py::int_ key(static_cast<int>(MCEST_EINVAL));
    py::object cls = by_status.contains(key) ? py::object(by_status[key]) : py::object(m.attr("EstimatorError"));
    PyErr_SetString(cls.ptr(), message.c_str());
    throw py::error_already_set();
}

// ---- arguments -------------------------------------------------------------------

std::string show(py::handle o)
{
    return py::str(py::repr(o));
}

uint64_t to_u64(py::handle o, const char *name)
{
    return mcs_kwargs::to_u64(o.ptr(), name, [](const std::string &m) { throw_invalid(m); });
}

size_t to_count(py::handle o, const char *name)
{
    uint64_t v = to_u64(o, name);
    if (v > (uint64_t{1} << 48))
        throw_invalid(std::string(name) + " is too large: " + show(o));
    return static_cast<size_t>(v);
}

// The number of worker threads: given (1..256), or mcstat's default.
int to_threads(py::handle o)
{
    if (o.is_none())
        return py::module_::import("mcstat._core").attr("get_num_threads")().cast<int>();
    uint64_t t = PyBool_Check(o.ptr()) ? 0 : to_u64(o, "threads");
    if (t < 1 || t > 256)
        throw_invalid("threads must be in 1..256, got " + show(o));
    return static_cast<int>(t);
}

// first_index + n must not wrap around 2^64 (indices name random streams).
void check_range(uint64_t first, size_t n)
{
    if (n > 0 && first > UINT64_MAX - (n - 1))
        throw_invalid("first_index + n exceeds 2**64");
}

// A fixed number of doubles from an array-like of the given shape.
void fixed(py::handle o, const char *name, size_t count, double *out, const char *shape)
{
    if (o.is_none())
        throw py::type_error(std::string(name) + " is required (" + shape + ")");
    carray a = carray::ensure(mcs::real_array(o, name));
    if (!a)
        throw py::type_error(std::string(name) + " must be array-like of numbers " + shape + ", got " + show(o));
    if (static_cast<size_t>(a.size()) != count || (count == 3 && a.ndim() != 1) ||
        (count == 9 && !(a.ndim() == 2 && a.shape(0) == 3 && a.shape(1) == 3) && a.ndim() != 1))
        throw_invalid(std::string(name) + " must have shape " + shape);
    std::memcpy(out, a.data(), count * sizeof(double));
}

mcest_scene scene_of(py::handle triangle, py::handle point, py::handle normal, double radiance)
{
    mcest_scene s;
    fixed(triangle, "triangle", 9, s.triangle, "(3, 3): three vertices");
    fixed(point, "point", 3, s.point, "(3,)");
    fixed(normal, "normal", 3, s.normal, "(3,)");
    s.radiance = radiance;
    return s;
}

const char *SCENE_RULES = "triangle, point and normal must be finite, the normal non-zero, radiance finite and >= 0";

// Directions: an array of shape (..., 3), C-contiguous float64; k = count.
carray directions(py::handle o, const char *name, size_t &k)
{
    carray a = carray::ensure(mcs::real_array(o, name));
    if (!a)
        throw py::type_error(std::string(name) + " must be array-like of shape (..., 3), got " + show(o));
    if (a.ndim() < 1 || a.shape(a.ndim() - 1) != 3)
        throw_invalid(std::string(name) + " must have shape (..., 3)");
    k = static_cast<size_t>(a.size() / 3);
    return a;
}

std::vector<py::ssize_t> lead_shape(const carray &a)
{
    std::vector<py::ssize_t> s(a.shape(), a.shape() + a.ndim() - 1);
    return s;
}

int parse_method(py::handle o)
{
    if (!py::isinstance<py::str>(o))
        throw py::type_error("method must be a str ('U', 'C', 'A' or 'S'), got " + show(o));
    std::string s = o.cast<std::string>();
    int m;
    if (mcest_method_parse(s.c_str(), &m) != MCEST_OK)
        throw_invalid("method must be 'U', 'C', 'A' or 'S', got '" + s + "'");
    return m;
}

int parse_bug(py::handle o)
{
    if (o.is_none())
        return MCEST_BUG_NONE;
    if (!py::isinstance<py::str>(o))
        throw py::type_error("bug must be None or a str, got " + show(o));
    std::string s = o.cast<std::string>();
    int b;
    if (s.empty() || mcest_bug_parse(s.c_str(), &b) != MCEST_OK)
        throw_invalid("bug must be None, 'no_cosine', 'barycentric' or 'no_jacobian', got '" + s + "'");
    return b;
}

int parse_rr_method(py::handle o)
{
    if (!py::isinstance<py::str>(o))
        throw py::type_error("method must be a str, got " + show(o));
    std::string s = o.cast<std::string>();
    if (s == "sampling")
        return MCEST_RR_SAMPLING;
    if (s == "rejection")
        return MCEST_RR_REJECTION;
    if (s == "rejection_unbiased")
        return MCEST_RR_REJECTION_UNBIASED;
    throw_invalid("method must be 'sampling', 'rejection' or 'rejection_unbiased', got '" + s + "'");
}

// ---- threads -------------------------------------------------------------------

// Runs f(start, count) -> status over [0, n) in `threads` contiguous
// chunks of at least MIN_PER_THREAD (threads.hpp); the status of the first
// failing chunk, in index order.  Call without the GIL; f must not touch
// Python.
template <typename F> int run_chunks(size_t n, int threads, F f)
{
    return mcs_threads::split_ranges(n, static_cast<size_t>(threads), MIN_PER_THREAD,
                                     [&f](size_t b, size_t e) { return f(b, e - b); });
}

// ---- irradiance ----------------------------------------------------------------------

struct IrradiancePlan {
    mcest_irradiance_plan p;
};

py::array_t<double> irradiance_estimates(const mcest_irradiance_plan &plan, py::handle method, size_t n,
                                         py::handle seed_o, py::handle bug_o, py::handle first_o,
                                         py::handle threads_o)
{
    int m = parse_method(method), bug = parse_bug(bug_o);
    uint64_t seed = to_u64(seed_o, "seed"), first = to_u64(first_o, "first_index");
    int threads = to_threads(threads_o);
    check_range(first, n);
    if (bug != MCEST_BUG_NONE && m != MCEST_A)
        throw_est(MCEST_EUNSUPPORTED, "bug='" + std::string(mcest_bug_name(bug)) + "' with method '" +
                                          mcest_method_name(m) + "'; the paper plants the bugs in A");
    py::array_t<double> out(static_cast<py::ssize_t>(n));
    double *o = out.mutable_data();
    mcest_irradiance_plan P = plan;
    int st;
    {
        py::gil_scoped_release nogil;
        st = run_chunks(n, threads, [&](size_t a, size_t k) {
            return mcest_irradiance_estimates(&P, m, bug, seed, first + a, k, o + a);
        });
    }
    if (st)
        throw_est(st);
    return out;
}

IrradiancePlan make_irradiance_plan(py::handle triangle, py::handle point, py::handle normal, double radiance)
{
    mcest_scene s = scene_of(triangle, point, normal, radiance);
    IrradiancePlan P;
    int st = mcest_irradiance_plan_init(&s, &P.p);
    if (st)
        throw_est(st, SCENE_RULES);
    return P;
}

py::dict paper_scene()
{
    mcest_scene s;
    mcest_scene_paper(&s);
    py::array_t<double> tri({3, 3}), pt(3), nr(3);
    std::memcpy(tri.mutable_data(), s.triangle, sizeof s.triangle);
    std::memcpy(pt.mutable_data(), s.point, sizeof s.point);
    std::memcpy(nr.mutable_data(), s.normal, sizeof s.normal);
    py::dict d;
    d["triangle"] = tri;
    d["point"] = pt;
    d["normal"] = nr;
    d["radiance"] = s.radiance;
    return d;
}

// ---- BRDFs -------------------------------------------------------------------------

struct BRDF {
    mcest_brdf b;
};

struct BRDFPlan {
    mcest_brdf_plan p;
};

const char *model_name(int model)
{
    return model == MCEST_WARD ? "ward" : model == MCEST_ASHIKHMIN_SHIRLEY ? "ashikhmin_shirley" : "unknown";
}

void wo_of(py::handle o, double *wo)
{
    fixed(o, "wo", 3, wo, "(3,)");
}

py::object direction_sample(py::array directions, py::object pdf, py::array keys, uint64_t trials)
{
    py::object cls = py::module_::import("mcstat.estimators").attr("DirectionSample");
    return cls(directions, pdf, keys, trials);
}

// keys of n directions (no GIL, threads)
int keys_of(const double *w, size_t n, uint64_t *keys, int threads)
{
    return run_chunks(n, threads, [&](size_t a, size_t k) { return mcest_direction_key(w + 3 * a, k, keys + a); });
}

BRDFPlan make_brdf_plan(const BRDF &brdf, py::handle wo_o, bool albedo, double rel_tol);

double compute_albedo(BRDFPlan &self, double rel_tol, bool strict)
{
    if (!(rel_tol >= 1e-13 && rel_tol <= 1e-2))
        throw_invalid("rel_tol must be in [1e-13, 1e-2], got " + std::to_string(rel_tol));
    mcest_brdf_plan P = self.p;
    int st;
    {
        py::gil_scoped_release nogil;
        st = mcest_brdf_plan_albedo(&P, rel_tol);
    }
    if (st == MCEST_ENUMERIC && !strict && P.has_albedo) {
        self.p = P;
        return P.albedo;
    }
    if (st)
        throw_est(st, st == MCEST_ENUMERIC ? "albedo " + std::to_string(P.albedo) + " +- " +
                                                 std::to_string(P.albedo_err) + "; strict=False accepts it"
                                           : std::string());
    self.p = P;
    return P.albedo;
}

BRDFPlan make_brdf_plan(const BRDF &brdf, py::handle wo_o, bool albedo, double rel_tol)
{
    double wo[3];
    wo_of(wo_o, wo);
    BRDFPlan P;
    int st = mcest_brdf_plan_init(&brdf.b, wo, &P.p);
    if (st)
        throw_est(st, "wo must be finite with wo.z > 0 (at least 1e-12 after normalisation)");
    if (albedo)
        compute_albedo(P, rel_tol, true);
    return P;
}

// ---- docstrings -------------------------------------------------------------------

const char *IRRADIANCE_DOC = R"doc(irradiance(method, n, *, triangle, point, normal, radiance=1.0, seed=0, bug=None, first_index=0, threads=None)

Primary estimates of the irradiance at a point from a triangular emitter
(paper, section 3.1).

The emitter is a two-sided Lambertian triangle of uniform radiance L; the
part of it below the receiver's tangent plane contributes nothing;
nothing occludes.  The mean of the estimates is `irradiance_exact`.

Parameters
----------
method : {"U", "C", "A", "S"}
    "U": uniform direction on the hemisphere (2 pi L cos if it hits, else
    0); "C": cosine-weighted direction (pi L if it hits); "A": uniform
    point on the triangle (L area cos cos' / r^2); "S": uniform direction
    in the emitter's solid angle (L Omega cos; Arvo's sampler, rewritten
    to keep its precision on tiny and sliver emitters).
n : int
    Number of estimates.
triangle : array_like, shape (3, 3)
    The emitter's vertices, one per row.
point, normal : array_like, shape (3,)
    The receiver (the normal need not be unit length).
radiance : float, optional
    L, finite and >= 0.
seed : int, optional
    In [0, 2**64).  Each method (and each bug) draws from its own stream
    of the counter-based generator (Philox4x64-10), so two estimators with
    the same seed are independent.
bug : {None, "no_cosine", "barycentric", "no_jacobian"}, optional
    Plants one of the paper's errors (section 3.4) in estimator A:
    the receiver's cosine omitted, a non-area-preserving barycentric map
    (b1 = u1, b2 = (1 - u1) u2), or the Jacobian ``n_tri.z/|z|^3`` omitted.
first_index : int, optional
    Index of the first estimate: estimate number first_index + k is a pure
    function of (seed, method, bug, first_index + k), so a run split into
    calls (first_index = 0, n1, n1 + n2, ...) gives the same numbers as one.
threads : int, optional
    Worker threads (default: mcstat.get_num_threads()); the numbers do not
    depend on it.  The GIL is released.

Returns
-------
ndarray of float64, shape (n,)

Raises
------
InvalidEstimatorArgument
    Bad method or bug, non-finite geometry, zero normal, negative radiance,
    wrong shapes, negative seed.
UnsupportedError
    A bug with a method other than "A".

Examples
--------
>>> from mcstat import estimators as est
>>> scene = est.paper_scene()
>>> e = est.irradiance("S", 100000, **scene, seed=1)
>>> e.mean(), est.irradiance_exact(**scene)
)doc";

const char *IRRADIANCE_EXACT_DOC = R"doc(irradiance_exact(*, triangle, point, normal, radiance=1.0)

Lambert's formula: the exact irradiance, E = ``(L/2) |sum_k Theta_k n.gamma_k|``
over the emitter clipped to the receiver's upper half-space.

Accurate to a few ulps (within 4e-16 of 60-digit references on tiny,
large, far and straddling emitters); slivers and emitters at grazing
elevation lose digits to the cancellation of their long edges (a
1e-7-wide needle: 4e-13).  A receiver in the emitter's plane, or a
degenerate triangle, gives 0.

Parameters and Raises as for `irradiance`.
)doc";

const char *IRRADIANCE_PLAN_DOC = R"doc(IrradiancePlan(*, triangle, point, normal, radiance=1.0)

A scene prepared once for many calls of the estimators (what
`irradiance` builds on every call), with its geometry.

Attributes
----------
exact : float
    Lambert's formula (= `irradiance_exact`).
solid_angle : float
    Of the emitter's visible part (steradians).
proj_solid_angle : float
    Projected solid angle (exact / radiance).
area, height : float
    The triangle's area; the receiver's distance to its plane.
straddles : bool
    The triangle crosses the receiver's horizon.
n_poly, n_fan : int
    Vertices of the visible polygon (0, 3 or 4); spherical triangles S
    samples (0, 1 or 2).
radiance : float
)doc";

const char *DIRECTION_KEYS_DOC = R"doc(direction_keys(w, *, threads=None)

64-bit Morton keys of directions w (shape (..., 3), any non-zero length).

Lambert's equal-area cylindrical map, s = (1 - z)/2, t = atan2(y, x)/(2 pi)
mod 1, each quantised to 32 bits and interleaved (s's bits the more
significant): nearby directions get nearby keys, and equal areas of the
sphere map to equal ranges of the square.  Distinct directions tie only
within about 2**-32 in both coordinates.  For a K-S test pass
``keys.astype(float)``: the rounding to 53 bits keeps their order and makes
ties only between directions within ~2**-26 in both coordinates.

Returns
-------
ndarray of uint64, shape (...)
)doc";

// ---- chi-squared route for direction samplers --------------------------------------
// Planted sampler bugs (BRDFPlan.sample_bug) and equal-probability direction
// cells (_brdf_cells, cells_count, cells_locate, cells_bounds); the Python
// face is mcstat.estimators.direction_cells / direction_gof.

int parse_sampler_bug(py::handle o)
{
    if (o.is_none())
        return MCEST_SAMPLER_BUG_NONE;
    if (!py::isinstance<py::str>(o))
        throw py::type_error("bug must be None or a str, got " + show(o));
    int bug;
    if (mcest_sampler_bug_parse(o.cast<std::string>().c_str(), &bug))
        throw_invalid("unknown sampler bug " + show(o) +
                      "; expected None, 'roughness', 'axes_swapped', 'phi_half' or 'jacobian'");
    return bug;
}

int cells_depth(py::handle o)
{
    uint64_t d = PyBool_Check(o.ptr()) ? 0 : to_u64(o, "depth");
    if (d < 1 || d > MCEST_CELLS_MAX_DEPTH)
        throw_invalid("depth must be in 1.." + std::to_string(MCEST_CELLS_MAX_DEPTH) + ", got " + show(o));
    return static_cast<int>(d);
}

carray cell_splits(py::handle o, int depth)
{
    carray a = carray::ensure(mcs::real_array(o, "split"));
    if (!a || a.ndim() != 1 || static_cast<size_t>(a.size()) != (size_t{1} << depth) - 1)
        throw_invalid("split must be a 1-D array of 2**depth - 1 values");
    return a;
}

void register_sampler_gof(py::module_ &m)
{
    py::object cls = m.attr("BRDFPlan");
    cls.attr("sample_bug") = py::cpp_function(
        [](const BRDFPlan &s, py::object n_o, py::object bug_o, py::object seed_o, py::object first_o,
           py::object threads_o) {
            size_t n = to_count(n_o, "n");
            int bug = parse_sampler_bug(bug_o);
            uint64_t seed = to_u64(seed_o, "seed"), first = to_u64(first_o, "first_index");
            int threads = to_threads(threads_o);
            check_range(first, n);
            py::array_t<double> wi({static_cast<py::ssize_t>(n), py::ssize_t{3}}), pdf(static_cast<py::ssize_t>(n));
            py::array_t<uint64_t> keys(static_cast<py::ssize_t>(n));
            double *w = wi.mutable_data(), *p = pdf.mutable_data();
            uint64_t *k = keys.mutable_data();
            mcest_brdf_plan P = s.p;
            int st;
            {
                py::gil_scoped_release nogil;
                st = run_chunks(n, threads, [&](size_t a, size_t c) {
                    int r = mcest_brdf_sample_bug(&P, bug, seed, first + a, c, w + 3 * a);
                    if (!r)
                        r = mcest_brdf_pdf(&P, w + 3 * a, c, p + a);
                    return r ? r : mcest_direction_key(w + 3 * a, c, k + a);
                });
            }
            if (st)
                throw_est(st);
            return direction_sample(wi, pdf, keys, n);
        },
        py::name("sample_bug"), py::is_method(cls), py::sibling(py::getattr(cls, "sample_bug", py::none())),
        py::arg("n"), py::arg("bug"), py::kw_only(), py::arg("seed") = 0, py::arg("first_index") = 0,
        py::arg("threads") = py::none(), R"doc(sample_bug(n, bug, *, seed=0, first_index=0, threads=None)

n directions from the BRDF's sampler with a planted bug: bug in
None (exactly `sample`), "roughness" (lobe 10% too wide), "axes_swapped"
(anisotropy axes swapped), "phi_half" (azimuth over half its range),
"jacobian" (the sin(theta) of d(omega) forgotten in the polar warp: a
half-normal instead of a Rayleigh polar radius).  ``pdf`` is the density
the sampler *claims* (the correct one, `pdf`), not the one it draws from.
Each bug draws from its own random stream.

Returns
-------
DirectionSample
)doc");

    m.def(
        "_brdf_cells",
        [](const BRDFPlan &s, py::object depth_o, double rel_tol) {
            int depth = cells_depth(depth_o);
            if (!(rel_tol >= 1e-12 && rel_tol <= 1e-2))
                throw_invalid("rel_tol must be in [1e-12, 1e-2]");
            size_t cells = size_t{1} << depth;
            std::vector<double> work(mcest_cells_work_size(depth));
            py::array_t<double> split(static_cast<py::ssize_t>(cells - 1)), prob(static_cast<py::ssize_t>(cells));
            double *sp = split.mutable_data(), *pp = prob.mutable_data(), err = NAN;
            mcest_brdf_plan P = s.p;
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcest_brdf_cells(&P, depth, rel_tol, work.data(), sp, pp, &err);
            }
            if (st && st != MCEST_ENUMERIC)
                throw_est(st);
            return py::make_tuple(split, prob, err, st);
        },
        py::arg("plan"), py::arg("depth"), py::arg("rel_tol"),
        "(split, prob, err, status) of mcest_brdf_cells (use mcstat.estimators.direction_cells).");

    m.def(
        "cells_count",
        [](py::object split_o, py::object depth_o, py::object w_o) {
            int depth = cells_depth(depth_o);
            carray split = cell_splits(split_o, depth);
            size_t k;
            carray w = directions(w_o, "w", k);
            py::array_t<double> counts(static_cast<py::ssize_t>(size_t{1} << depth));
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcest_cells_count(split.data(), depth, w.data(), k, counts.mutable_data());
            }
            if (st)
                throw_est(st, "directions must be finite and non-zero");
            return counts;
        },
        py::arg("split"), py::arg("depth"), py::arg("w"),
        "Counts of directions w (shape (..., 3)) in each of the 2**depth cells.");

    m.def(
        "cells_locate",
        [](py::object split_o, py::object depth_o, py::object w_o) {
            int depth = cells_depth(depth_o);
            carray split = cell_splits(split_o, depth);
            size_t k;
            carray w = directions(w_o, "w", k);
            py::array_t<uint32_t> cell(lead_shape(w));
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcest_cells_locate(split.data(), depth, w.data(), k, cell.mutable_data());
            }
            if (st)
                throw_est(st, "directions must be finite and non-zero");
            return cell;
        },
        py::arg("split"), py::arg("depth"), py::arg("w"), "The cell of each direction w (shape (..., 3)).");

    m.def(
        "cells_bounds",
        [](py::object split_o, py::object depth_o) {
            int depth = cells_depth(depth_o);
            carray split = cell_splits(split_o, depth);
            size_t cells = size_t{1} << depth;
            py::array_t<double> b({static_cast<py::ssize_t>(cells), py::ssize_t{4}});
            int st = mcest_cells_bounds(split.data(), depth, b.mutable_data());
            if (st)
                throw_est(st);
            return b;
        },
        py::arg("split"), py::arg("depth"), "Rectangles (s0, s1, t0, t1) of the cells in the equal-area square.");
}

} // namespace

PYBIND11_MODULE(_estimators, m)
{
    m.doc() = "libmcest bound for Python (use mcstat.estimators, not this module).";
    m.attr("__libmcest_version__") = mcest_version();

    // ---- irradiance ----
    py::class_<IrradiancePlan>(m, "IrradiancePlan", IRRADIANCE_PLAN_DOC)
        .def(py::init([](py::object triangle, py::object point, py::object normal, double radiance) {
                 return make_irradiance_plan(triangle, point, normal, radiance);
             }),
             py::kw_only(), py::arg("triangle"), py::arg("point"), py::arg("normal"), py::arg("radiance") = 1.0)
        .def_property_readonly("exact", [](const IrradiancePlan &s) { return s.p.exact; })
        .def_property_readonly("solid_angle", [](const IrradiancePlan &s) { return s.p.solid_angle; })
        .def_property_readonly("proj_solid_angle", [](const IrradiancePlan &s) { return s.p.proj_solid_angle; })
        .def_property_readonly("area", [](const IrradiancePlan &s) { return s.p.area; })
        .def_property_readonly("height", [](const IrradiancePlan &s) { return s.p.height; })
        .def_property_readonly("radiance", [](const IrradiancePlan &s) { return s.p.radiance; })
        .def_property_readonly("straddles", [](const IrradiancePlan &s) { return s.p.straddles != 0; })
        .def_property_readonly("n_poly", [](const IrradiancePlan &s) { return s.p.n_poly; })
        .def_property_readonly("n_fan", [](const IrradiancePlan &s) { return s.p.n_fan; })
        .def(
            "estimates",
            [](const IrradiancePlan &s, py::object method, py::object n, py::object seed, py::object bug,
               py::object first_index, py::object threads) {
                return irradiance_estimates(s.p, method, to_count(n, "n"), seed, bug, first_index, threads);
            },
            py::arg("method"), py::arg("n"), py::kw_only(), py::arg("seed") = 0, py::arg("bug") = py::none(),
            py::arg("first_index") = 0, py::arg("threads") = py::none(),
            "estimates(method, n, *, seed=0, bug=None, first_index=0, threads=None)\n\n"
            "n primary estimates of `method` on this scene; as `irradiance`.")
        .def("__repr__", [](const IrradiancePlan &s) {
            char b[200];
            std::snprintf(b, sizeof b, "<IrradiancePlan E=%.15g, solid_angle=%.6g, straddles=%s>", s.p.exact,
                          s.p.solid_angle, s.p.straddles ? "True" : "False");
            return std::string(b);
        });

    m.def(
        "irradiance",
        [](py::object method, py::object n, py::object triangle, py::object point, py::object normal,
           double radiance, py::object seed, py::object bug, py::object first_index, py::object threads) {
            size_t count = to_count(n, "n");
            parse_method(method); // argument errors before geometry errors
            parse_bug(bug);
            IrradiancePlan P = make_irradiance_plan(triangle, point, normal, radiance);
            return irradiance_estimates(P.p, method, count, seed, bug, first_index, threads);
        },
        py::arg("method"), py::arg("n"), py::kw_only(), py::arg("triangle"), py::arg("point"), py::arg("normal"),
        py::arg("radiance") = 1.0, py::arg("seed") = 0, py::arg("bug") = py::none(), py::arg("first_index") = 0,
        py::arg("threads") = py::none(), IRRADIANCE_DOC);

    m.def(
        "irradiance_exact",
        [](py::object triangle, py::object point, py::object normal, double radiance) {
            mcest_scene s = scene_of(triangle, point, normal, radiance);
            double E;
            int st = mcest_irradiance_exact(&s, &E);
            if (st)
                throw_est(st, SCENE_RULES);
            return E;
        },
        py::kw_only(), py::arg("triangle"), py::arg("point"), py::arg("normal"), py::arg("radiance") = 1.0,
        IRRADIANCE_EXACT_DOC);

    m.def("paper_scene", &paper_scene, R"doc(paper_scene()

The built-in scene of section 3.1 (what ``mcstat reproduce`` uses), as a
dict of keyword arguments for `irradiance`, `irradiance_exact` and
`IrradiancePlan`: receiver at the origin facing +z, radiance 1, triangle
(-0.6, -0.4, 1.0), (0.9, -0.3, 1.3), (0.1, 0.9, 0.8): E = 0.6645371516643,
solid angle 0.7166 sr; standard deviations of the primary estimates order
as sigma_U > sigma_C > sigma_A > sigma_S (about 1.86, 1.28, 0.202, 0.042).

Returns
-------
dict
    ``triangle`` (ndarray (3, 3)), ``point``, ``normal`` (ndarray (3,)),
    ``radiance`` (float); fresh arrays on each call.
)doc");

    // ---- BRDFs ----
    py::class_<BRDF>(m, "BRDF", R"doc(An anisotropic BRDF: Ward's or Ashikhmin-Shirley's (section 3.2).

Made by `ward` or `ashikhmin_shirley`.  Directions live in the shading
frame: normal +z, first tangent +x (the direction of alpha_x / n_u).

Attributes
----------
model : {"ward", "ashikhmin_shirley"}
diffuse, specular, rough_x, rough_y : float
    Ward's (rho_d, rho_s, alpha_x, alpha_y) or Ashikhmin-Shirley's
    (Rd, Rs, n_u, n_v).
)doc")
        .def_property_readonly("model", [](const BRDF &s) { return model_name(s.b.model); })
        .def_property_readonly("diffuse", [](const BRDF &s) { return s.b.diffuse; })
        .def_property_readonly("specular", [](const BRDF &s) { return s.b.specular; })
        .def_property_readonly("rough_x", [](const BRDF &s) { return s.b.rough_x; })
        .def_property_readonly("rough_y", [](const BRDF &s) { return s.b.rough_y; })
        .def(
            "eval",
            [](const BRDF &s, py::object wi_o, py::object wo_o) {
                double wo[3];
                wo_of(wo_o, wo);
                size_t k;
                carray wi = directions(wi_o, "wi", k);
                py::array_t<double> f(lead_shape(wi));
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = mcest_brdf_eval(&s.b, wo, wi.data(), k, f.mutable_data());
                }
                if (st)
                    throw_est(st, "wo needs wo.z > 0; directions must be finite and non-zero");
                return f;
            },
            py::arg("wi"), py::arg("wo"), R"doc(eval(wi, wo)

f(wi, wo) at directions wi (shape (..., 3)) for the fixed direction wo
(wo.z > 0); 0 where wi.z <= 0.  Returns an array of shape (...).)doc")
        .def(
            "plan",
            [](const BRDF &s, py::object wo, bool albedo, double rel_tol) {
                return make_brdf_plan(s, wo, albedo, rel_tol);
            },
            py::arg("wo"), py::kw_only(), py::arg("albedo") = false, py::arg("rel_tol") = 1e-6,
            R"doc(plan(wo, *, albedo=False, rel_tol=1e-6)

The BRDF with a fixed outgoing direction wo, ready to sample (a
`BRDFPlan`).  albedo=True also computes the albedo by cubature (10-40 ms;
needed by the "rejection" reflected-radiance estimator).)doc")
        .def("__repr__", [](const BRDF &s) {
            char b[200];
            std::snprintf(b, sizeof b, "<BRDF %s: diffuse=%g, specular=%g, rough=(%g, %g)>", model_name(s.b.model),
                          s.b.diffuse, s.b.specular, s.b.rough_x, s.b.rough_y);
            return std::string(b);
        });

    m.def(
        "ward",
        [](double rho_d, double rho_s, double alpha_x, double alpha_y) {
            BRDF b;
            if (int st = mcest_brdf_ward(rho_d, rho_s, alpha_x, alpha_y, &b.b))
                throw_est(st, "Ward needs rho_d, rho_s >= 0 and alpha in [1e-4, 10], all finite");
            return b;
        },
        py::arg("rho_d"), py::arg("rho_s"), py::arg("alpha_x"), py::arg("alpha_y"), R"doc(ward(rho_d, rho_s, alpha_x, alpha_y)

Ward's (1992) anisotropic BRDF, with Walter's (2005) density of its
half-vector sampler:
f = rho_d/pi + rho_s exp(-(hx^2/ax^2 + hy^2/ay^2)/hz^2) / (4 pi ax ay sqrt(cos_i cos_o)).
rho_d, rho_s >= 0; alpha_x, alpha_y in [1e-4, 10].  Returns a `BRDF`.)doc");

    m.def(
        "ashikhmin_shirley",
        [](double rd, double rs, double n_u, double n_v) {
            BRDF b;
            if (int st = mcest_brdf_ashikhmin_shirley(rd, rs, n_u, n_v, &b.b))
                throw_est(st, "Ashikhmin-Shirley needs Rd, Rs in [0, 1] and exponents in [0, 1e7], all finite");
            return b;
        },
        py::arg("rd"), py::arg("rs"), py::arg("n_u"), py::arg("n_v"), R"doc(ashikhmin_shirley(rd, rs, n_u, n_v)

Ashikhmin and Shirley's (2000) anisotropic Phong BRDF: a specular lobe
with Fresnel reflectance rs at normal incidence and exponents n_u, n_v,
plus their coupled diffuse term with reflectance rd.  rd, rs in [0, 1];
n_u, n_v in [0, 1e7].  Returns a `BRDF`.)doc");

    py::class_<BRDFPlan>(m, "BRDFPlan", R"doc(A BRDF with a fixed outgoing direction wo: its samplers and estimators.

Made by ``brdf.plan(wo)``.  When the diffuse term is not zero, "the BRDF's
sampler" is the mixture drawing a cosine-weighted direction with
probability `mix` and the half-vector sampler otherwise.

Attributes
----------
brdf : BRDF
wo : ndarray, shape (3,)
    The outgoing direction, normalised.
mix : float
    Probability of the cosine-weighted component.
bound_d, bound_s, bound : float
    The rejection sampler's envelope: f cos / q <= bound = bound_d +
    bound_s (a proof, not a fit: see mcest.h).
has_albedo : bool
albedo, albedo_d, albedo_s, albedo_err : float
    The integral of f cos over the hemisphere (diffuse part in closed
    form, specular by cubature) and its estimated error; NaN until
    computed (`compute_albedo`).
acceptance : float
    Expected acceptance rate of `sample_exact`, albedo / bound (NaN
    without the albedo).
)doc")
        .def_property_readonly("brdf", [](const BRDFPlan &s) { return BRDF{s.p.brdf}; })
        .def_property_readonly("wo", [](const BRDFPlan &s) {
            py::array_t<double> w(3);
            std::memcpy(w.mutable_data(), s.p.wo, sizeof s.p.wo);
            return w;
        })
        .def_property_readonly("mix", [](const BRDFPlan &s) { return s.p.mix; })
        .def_property_readonly("bound_d", [](const BRDFPlan &s) { return s.p.bound_d; })
        .def_property_readonly("bound_s", [](const BRDFPlan &s) { return s.p.bound_s; })
        .def_property_readonly("bound", [](const BRDFPlan &s) { return s.p.bound; })
        .def_property_readonly("has_albedo", [](const BRDFPlan &s) { return s.p.has_albedo != 0; })
        .def_property_readonly("albedo", [](const BRDFPlan &s) { return s.p.has_albedo ? s.p.albedo : NAN; })
        .def_property_readonly("albedo_d", [](const BRDFPlan &s) { return s.p.albedo_d; })
        .def_property_readonly("albedo_s", [](const BRDFPlan &s) { return s.p.has_albedo ? s.p.albedo_s : NAN; })
        .def_property_readonly("albedo_err", [](const BRDFPlan &s) { return s.p.has_albedo ? s.p.albedo_err : NAN; })
        .def_property_readonly("acceptance", [](const BRDFPlan &s) {
            return s.p.has_albedo && s.p.bound > 0 ? s.p.albedo / s.p.bound : NAN;
        })
        .def("compute_albedo", &compute_albedo, py::arg("rel_tol") = 1e-6, py::kw_only(), py::arg("strict") = true,
             R"doc(compute_albedo(rel_tol=1e-6, *, strict=True)

Computes and stores the albedo by adaptive Gauss-Legendre cubature
(10-40 ms, the GIL released); rel_tol in [1e-13, 1e-2] (the kink at the
horizon limits it to about 1e-6..1e-8).  Returns the albedo.  If the
tolerance is not reached, raises EstimatorNumericalError (strict) or keeps
the value reached (strict=False).)doc")
        .def(
            "sample",
            [](const BRDFPlan &s, py::object n_o, py::object seed_o, py::object first_o, py::object threads_o) {
                size_t n = to_count(n_o, "n");
                uint64_t seed = to_u64(seed_o, "seed"), first = to_u64(first_o, "first_index");
                int threads = to_threads(threads_o);
                check_range(first, n);
                py::array_t<double> wi({static_cast<py::ssize_t>(n), py::ssize_t{3}}), pdf(static_cast<py::ssize_t>(n));
                py::array_t<uint64_t> keys(static_cast<py::ssize_t>(n));
                double *w = wi.mutable_data(), *p = pdf.mutable_data();
                uint64_t *k = keys.mutable_data();
                mcest_brdf_plan P = s.p;
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = run_chunks(n, threads, [&](size_t a, size_t c) {
                        int r = mcest_brdf_sample(&P, seed, first + a, c, w + 3 * a, p + a);
                        return r ? r : mcest_direction_key(w + 3 * a, c, k + a);
                    });
                }
                if (st)
                    throw_est(st);
                return direction_sample(wi, pdf, keys, n);
            },
            py::arg("n"), py::kw_only(), py::arg("seed") = 0, py::arg("first_index") = 0,
            py::arg("threads") = py::none(), R"doc(sample(n, *, seed=0, first_index=0, threads=None)

n directions from the BRDF's own sampler (Ward: Walter's reading of Ward's
half-vector sampler; Ashikhmin-Shirley's), with the true density of each.
Some fall below the horizon (the half-vector reflection does that); they
are returned as drawn.  Direction number first_index + k is a pure
function of (seed, model, first_index + k); threads do not change them.

Returns
-------
DirectionSample
    ``directions`` (n, 3), ``pdf`` (n,) in solid-angle measure (the
    density the sampler really draws from, ERRATA 9), ``keys`` (n,)
    uint64 Morton keys (`direction_keys`), ``trials`` = n.
)doc")
        .def(
            "sample_exact",
            [](const BRDFPlan &s, py::object n_o, py::object seed_o, py::object first_o, py::object max_o,
               py::object threads_o) {
                size_t n = to_count(n_o, "n");
                uint64_t seed = to_u64(seed_o, "seed"), first = to_u64(first_o, "first_index");
                uint64_t max_trials = to_u64(max_o, "max_trials");
                int threads = to_threads(threads_o);
                check_range(first, n);
                if (!(s.p.bound > 0.0))
                    throw_invalid("this BRDF is zero (rho_s = rho_d = 0): nothing to sample");
                py::array_t<double> wi({static_cast<py::ssize_t>(n), py::ssize_t{3}});
                py::array_t<uint64_t> keys(static_cast<py::ssize_t>(n));
                double *w = wi.mutable_data();
                uint64_t *k = keys.mutable_data();
                mcest_brdf_plan P = s.p;
                std::atomic<uint64_t> total{0}; // a sum of integers: the same in any order
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = run_chunks(n, threads, [&](size_t a, size_t c) {
                        uint64_t t = 0;
                        int r = mcest_brdf_sample_exact(&P, seed, first + a, c, max_trials, w + 3 * a, &t);
                        total += t;
                        return r ? r : mcest_direction_key(w + 3 * a, c, k + a);
                    });
                }
                if (st)
                    throw_est(st, st == MCEST_ELIMIT ? "max_trials=" + std::to_string(max_trials) : std::string());
                return direction_sample(wi, py::none(), keys, total.load());
            },
            py::arg("n"), py::kw_only(), py::arg("seed") = 0, py::arg("first_index") = 0, py::arg("max_trials") = 0,
            py::arg("threads") = py::none(), R"doc(sample_exact(n, *, seed=0, first_index=0, max_trials=0, threads=None)

n directions with density exactly f(wi, wo) cos_i / albedo on the upper
hemisphere, by rejection from the BRDF's sampler with the envelope
`bound`.  At most max_trials proposals per direction (0: no cap).

Returns
-------
DirectionSample
    ``directions`` (n, 3), ``pdf`` None, ``keys`` (n,) uint64, ``trials``:
    the total number of proposals (n / trials estimates `acceptance`).

Raises
------
TrialLimitError
    A direction needed more than max_trials proposals.
)doc")
        .def(
            "pdf",
            [](const BRDFPlan &s, py::object wi_o) {
                size_t k;
                carray wi = directions(wi_o, "wi", k);
                py::array_t<double> p(lead_shape(wi));
                mcest_brdf_plan P = s.p;
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = mcest_brdf_pdf(&P, wi.data(), k, p.mutable_data());
                }
                if (st)
                    throw_est(st, "directions must be finite and non-zero");
                return p;
            },
            py::arg("wi"), R"doc(pdf(wi)

The density (solid-angle measure, on the whole sphere) of the BRDF's
sampler at directions wi (shape (..., 3)).  Returns shape (...).)doc")
        .def(
            "reflected_radiance",
            [](const BRDFPlan &s, py::object method, py::object n_o, py::object seed_o, py::object first_o,
               py::object max_o, py::object threads_o) {
                int m = parse_rr_method(method);
                size_t n = to_count(n_o, "n");
                uint64_t seed = to_u64(seed_o, "seed"), first = to_u64(first_o, "first_index");
                uint64_t max_trials = to_u64(max_o, "max_trials");
                int threads = to_threads(threads_o);
                check_range(first, n);
                py::array_t<double> out(static_cast<py::ssize_t>(n));
                double *o = out.mutable_data();
                mcest_brdf_plan P = s.p;
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = run_chunks(n, threads, [&](size_t a, size_t c) {
                        return mcest_reflected_radiance(&P, m, seed, first + a, c, max_trials, o + a);
                    });
                }
                if (st)
                    throw_est(st);
                return out;
            },
            py::arg("method"), py::arg("n"), py::kw_only(), py::arg("seed") = 0, py::arg("first_index") = 0,
            py::arg("max_trials") = 0, py::arg("threads") = py::none(),
            R"doc(reflected_radiance(method, n, *, seed=0, first_index=0, max_trials=0, threads=None)

n primary estimates of the reflected radiance Lr(wo), the integral of
f(wi, wo) Lenv(wi) cos_i over the hemisphere, under the analytic
environment of `environment_radiance` (section 3.3).

method : {"sampling", "rejection", "rejection_unbiased"}
    "sampling": wi from `sample`, f Lenv cos / p(wi) with the sampler's true
    density.  "rejection": wi from `sample_exact`, albedo * Lenv(wi) (needs
    the albedo: its cubature error is the estimator's bias, below the
    rel_tol given).  "rejection_unbiased": the same direction times an
    independent unbiased estimate of the albedo (no quadrature, more
    variance).

Raises NotReadyError for "rejection" without the albedo, TrialLimitError
past max_trials.)doc")
        .def(
            "reflected_radiance_reference",
            [](const BRDFPlan &s, double rel_tol, bool strict) {
                if (!(rel_tol >= 1e-13 && rel_tol <= 1e-2))
                    throw_invalid("rel_tol must be in [1e-13, 1e-2]");
                mcest_brdf_plan P = s.p;
                double Lr = NAN;
                int st;
                {
                    py::gil_scoped_release nogil;
                    st = mcest_reflected_radiance_reference(&P, rel_tol, &Lr);
                }
                if (st == MCEST_ENUMERIC && !strict && std::isfinite(Lr))
                    return Lr;
                if (st)
                    throw_est(st, st == MCEST_ENUMERIC ? "reached " + std::to_string(Lr) + "; strict=False accepts it"
                                                       : std::string());
                return Lr;
            },
            py::arg("rel_tol") = 1e-6, py::kw_only(), py::arg("strict") = true,
            R"doc(reflected_radiance_reference(rel_tol=1e-6, *, strict=True)

Lr(wo) by the cubature of `compute_albedo` (the reference the estimators'
means are tested against); rel_tol and strict as there.)doc")
        .def("__repr__", [](const BRDFPlan &s) {
            char b[300];
            std::snprintf(b, sizeof b, "<BRDFPlan %s wo=(%.6g, %.6g, %.6g): mix=%g, bound=%g, albedo=%g>",
                          model_name(s.p.brdf.model), s.p.wo[0], s.p.wo[1], s.p.wo[2], s.p.mix, s.p.bound,
                          s.p.has_albedo ? s.p.albedo : NAN);
            return std::string(b);
        });

    // ---- directions ----
    m.def(
        "direction_keys",
        [](py::object w_o, py::object threads_o) {
            size_t k;
            carray w = directions(w_o, "w", k);
            int threads = to_threads(threads_o);
            py::array_t<uint64_t> keys(lead_shape(w));
            int st;
            {
                py::gil_scoped_release nogil;
                st = keys_of(w.data(), k, keys.mutable_data(), threads);
            }
            if (st)
                throw_est(st, "directions must be finite and non-zero");
            return keys;
        },
        py::arg("w"), py::kw_only(), py::arg("threads") = py::none(), DIRECTION_KEYS_DOC);

    m.def(
        "direction_square",
        [](py::object w_o) {
            size_t k;
            carray w = directions(w_o, "w", k);
            std::vector<py::ssize_t> shape = lead_shape(w);
            shape.push_back(2);
            py::array_t<double> st_out(shape);
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcest_direction_square(w.data(), k, st_out.mutable_data());
            }
            if (st)
                throw_est(st, "directions must be finite and non-zero");
            return st_out;
        },
        py::arg("w"), R"doc(direction_square(w)

Lambert's equal-area cylindrical coordinates (s, t) in [0, 1]^2 of
directions w (shape (..., 3)): s = (1 - z)/2 (s <= 1/2 on the upper
hemisphere), t = atan2(y, x)/(2 pi) mod 1.  Returns shape (..., 2).)doc");

    m.def(
        "environment_radiance",
        [](py::object w_o) {
            size_t k;
            carray w = directions(w_o, "w", k);
            py::array_t<double> L(lead_shape(w));
            int st;
            {
                py::gil_scoped_release nogil;
                st = mcest_environment_radiance(w.data(), k, L.mutable_data());
            }
            if (st)
                throw_est(st, "directions must be finite and non-zero");
            return L;
        },
        py::arg("w"), R"doc(environment_radiance(w)

The analytic environment of section 3.3 at directions w (shape (..., 3),
normalised first), in the shading frame:
Lenv(w) = 1 + 0.5 (x^3 - 3 x y^2) + 0.3 cos(12 y) + 4 exp(20 (w.d - 1)),
d = (0.3, -0.4, sqrt(0.75)).  Returns shape (...).)doc");

    register_sampler_gof(m); // chi-squared route, planted sampler bugs
}
