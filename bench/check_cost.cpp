// check_cost.cpp - what a renderer check (mcstat_check_bsdf) costs beyond
// the renderer's own callbacks.
//
// The BSDF is the GGX conductor of examples/cpp_bsdf (ggx.hpp), in float32
// and in double.  One check at n samples (default 1e5, default options) is
// recorded once: every callback call with its inputs.  Then, for each of
// `reps` rounds, back to back:
//   check    mcstat_check_bsdf with the same callbacks (counting only);
//   replay   the recorded calls, same batches, same inputs, through the same
//            function pointers: the callbacks' share of the check;
// the check's own cost is check - replay (pilot tree, cubature bookkeeping,
// statistics, its uniforms), per sample divided by n, and is set against
// the BSDF's sample() cost per sample (the replayed sample() calls divided
// by their points).  Medians over the rounds, [fastest-slowest] beside them;
// the ratios are ratios of medians.  No timing is asserted.
//
// usage: check_cost [n] [reps]
#include "ggx.hpp"

#include "mcstat.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Stat {
    double med, lo, hi;
};

Stat stat(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    size_t m = v.size();
    double med = m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
    return {med, v.front(), v.back()};
}

// One recorded callback call.
struct Call {
    int which; // 0 sample, 1 pdf, 2 eval
    size_t n;
    std::vector<double> in; // u (n * 2) or x (n * 3)
};

template <class Bsdf> struct Recorder {
    ggx::Callbacks<Bsdf> inner;
    std::vector<Call> calls;

    static int sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
    {
        auto *r = static_cast<Recorder *>(user);
        try {
            r->calls.push_back({0, n, std::vector<double>(u, u + 2 * n)});
        } catch (...) {
            return 1;
        }
        return ggx::Callbacks<Bsdf>::sample(&r->inner, wi, u, n, x, w, p);
    }
    static int density(int which, void *user, const double *wi, const double *x, size_t n, double *out)
    {
        auto *r = static_cast<Recorder *>(user);
        try {
            r->calls.push_back({which, n, std::vector<double>(x, x + 3 * n)});
        } catch (...) {
            return 1;
        }
        return which == 1 ? ggx::Callbacks<Bsdf>::pdf(&r->inner, wi, x, n, out)
                          : ggx::Callbacks<Bsdf>::eval(&r->inner, wi, x, n, out);
    }
    static int pdf(void *u, const double *wi, const double *x, size_t n, double *o) { return density(1, u, wi, x, n, o); }
    static int eval(void *u, const double *wi, const double *x, size_t n, double *o) { return density(2, u, wi, x, n, o); }
};

volatile double sink;

template <class Real> int bench(const char *name, size_t n, int reps, const double wi[3], uint64_t seed)
{
    ggx::Ggx<Real> bsdf(Real(0.3), Real(0.15), Real(0.8));
    const double alpha = 0.01;
    mcstat_check_report rep;

    // the recording
    Recorder<ggx::Ggx<Real>> rec{{&bsdf}, {}};
    mcstat_check_model model = rec.inner.model();
    model.user = &rec;
    model.sample = &Recorder<ggx::Ggx<Real>>::sample;
    model.pdf = &Recorder<ggx::Ggx<Real>>::pdf;
    model.eval = &Recorder<ggx::Ggx<Real>>::eval;
    int st = mcstat_check_bsdf(&model, wi, n, seed, alpha, nullptr, nullptr, 0, &rep);
    if (st != MCSTAT_OK) {
        std::fprintf(stderr, "check_cost: %s: %s %s\n", name, mcstat_strerror(st), rep.message);
        return 1;
    }
    size_t max_n = 0;
    unsigned long long points[3] = {0, 0, 0}, ncalls[3] = {0, 0, 0};
    for (const Call &c : rec.calls) {
        max_n = std::max(max_n, c.n);
        points[c.which] += c.n;
        ncalls[c.which]++;
    }
    std::vector<double> x(3 * max_n), w(max_n), p(max_n);

    std::vector<double> t_check, t_replay, t_sample;
    for (int r = 0; r < reps; r++) {
        ggx::Callbacks<ggx::Ggx<Real>> cb{&bsdf};
        mcstat_check_model m = cb.model();
        double t0 = now();
        st = mcstat_check_bsdf(&m, wi, n, seed, alpha, nullptr, nullptr, 0, &rep);
        double t1 = now();
        if (st != MCSTAT_OK) {
            std::fprintf(stderr, "check_cost: %s: %s %s\n", name, mcstat_strerror(st), rep.message);
            return 1;
        }
        if (cb.sample_points != points[0] || cb.pdf_points != points[1] || cb.eval_points != points[2]) {
            std::fprintf(stderr, "check_cost: %s: the check's calls differ from the recording's\n", name);
            return 1;
        }
        // the same calls through the same pointers: the callbacks' share
        ggx::Callbacks<ggx::Ggx<Real>> cb2{&bsdf};
        mcstat_check_model m2 = cb2.model();
        double ts = 0, s = 0;
        double t2 = now();
        for (const Call &c : rec.calls) {
            if (c.which == 0) {
                double a = now();
                st |= m2.sample(m2.user, rep.wi, c.in.data(), c.n, x.data(), w.data(), p.data());
                ts += now() - a;
            } else {
                st |= (c.which == 1 ? m2.pdf : m2.eval)(m2.user, rep.wi, c.in.data(), c.n, w.data());
            }
            s += w[0];
        }
        double t3 = now();
        sink = s;
        if (st) {
            std::fprintf(stderr, "check_cost: %s: a replayed callback failed\n", name);
            return 1;
        }
        t_check.push_back(t1 - t0);
        t_replay.push_back(t3 - t2);
        t_sample.push_back(ts);
    }
    std::vector<double> own(reps);
    for (int r = 0; r < reps; r++)
        own[r] = (t_check[r] - t_replay[r]) / double(n) * 1e9;
    Stat check = stat(t_check), replay = stat(t_replay), sample = stat(t_sample), o = stat(own);
    double sample_ns = sample.med / double(points[0]) * 1e9;
    unsigned long long counted = ncalls[0] + ncalls[1] + ncalls[2];

    std::printf("%s BSDF, n = %zu (default options: %llu cells, %llu pilot samples, n_eval %llu)\n", name, n,
                (unsigned long long)rep.cells, (unsigned long long)rep.n_pilot, (unsigned long long)rep.n_eval);
    std::printf("  callback calls: %llu counted, %llu in the report (sample %llu, pdf %llu, eval %llu)\n", counted,
                (unsigned long long)rep.calls, ncalls[0], ncalls[1], ncalls[2]);
    std::printf("  points: sample %llu (%.2f n), pdf %llu (%.2f n), eval %llu (%.2f n)\n", points[0],
                double(points[0]) / double(n), points[1], double(points[1]) / double(n), points[2],
                double(points[2]) / double(n));
    std::printf("  full check (wall):                %8.1f ms [%.1f-%.1f]\n", check.med * 1e3, check.lo * 1e3,
                check.hi * 1e3);
    std::printf("  its callbacks, replayed:          %8.1f ms [%.1f-%.1f] (%.0f%% of the check)\n", replay.med * 1e3,
                replay.lo * 1e3, replay.hi * 1e3, 100 * replay.med / check.med);
    std::printf("    of which sample():              %8.1f ms, %.1f ns per sampled point\n", sample.med * 1e3,
                sample_ns);
    std::printf("  the check's own cost:             %8.1f ns per sample [%.1f-%.1f]\n", o.med, o.lo, o.hi);
    std::printf("  own cost / sample() cost:         %8.1f x\n", o.med / sample_ns);
    std::printf("  check wall / (n sample() calls):  %8.1f x\n", check.med / (double(n) * sample_ns * 1e-9));
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    double nd = argc > 1 ? std::atof(argv[1]) : 1e5;
    int reps = argc > 2 ? std::atoi(argv[2]) : 5;
    if (!(nd >= 1000 && nd <= 1e9) || reps < 1 || reps > 64) {
        std::fprintf(stderr, "usage: check_cost [n >= 1000] [reps 1..64]\n");
        return 2;
    }
    size_t n = size_t(nd);
    const double theta = 50 * ggx::pi / 180, phi = 30 * ggx::pi / 180;
    const double wi[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    std::printf("median [fastest-slowest] of %d rounds, one thread\n", reps);
    int st = bench<float>("float32", n, reps, wi, 20261203);
    st |= bench<double>("double", n, reps, wi, 20261203);
    return st;
}
