/*
 * test_irradiance_exact.c - Lambert's formula and the solid angle against
 * 60-digit references (ref_irradiance.h, made by
 * reference/make_irradiance_reference.py from two independent routes), and
 * where the textbook formulas lose their digits: acos-based Lambert, Arvo's
 * area as an angle excess, Arvo's sampler on tiny triangles.
 */
#include "harness.h"
#include "internal.h"
#include "mcest.h"
#include "ref_scene.h"

#include <float.h>
#include <string.h>



/* Cancellation in Lambert's sum: kappa = sum |Theta_k gamma_k.z| /
 * |sum Theta_k gamma_k.z| (computed here in plain double: only its size
 * matters).  For small emitters the library rearranges the sum and kappa
 * does not apply; slivers and emitters at grazing elevation keep it: their
 * long edges contribute nearly opposite terms (sliver: kappa ~ 2e4,
 * grazing: ~5e5), and the error bound of the summation is ~kappa*eps. */
static double kappa(const ref_scene *r)
{
    double v[3][3], sa = 0.0, s = 0.0;
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++)
            v[k][i] = r->tri[3 * k + i] - r->point[i];
    for (int k = 0; k < 3; k++) {
        double c[3];
        cross3(v[k], v[(k + 1) % 3], c);
        double th = atan2(norm3(c), dot3(v[k], v[(k + 1) % 3]));
        sa += fabs(th * c[2] / norm3(c));
        s += th * c[2] / norm3(c);
    }
    return sa / fabs(s);
}

/* The edge-on scene is ill-conditioned as a problem: its irradiance is
 * proportional to the receiver's distance h = 7e-9 from the emitter's
 * plane, which the inputs (coordinates ~1) carry only to ~eps; a
 * backward-stable result is within ~eps * size / h. */
static double tolerance(const ref_scene *r)
{
    if (!strcmp(r->name, "edge_on"))
        return 64 * DBL_EPSILON * 1.0 / 7e-9;
    if (!strcmp(r->name, "sliver") || !strcmp(r->name, "grazing"))
        return 8 * DBL_EPSILON * kappa(r);
    return 2e-14;
}

static void test_against_reference(void)
{
    for (int i = 0; i < N_REF_SCENES; i++) {
        const ref_scene *r = &ref_scenes[i];
        mcest_scene s = scene_of(r);
        double E = -1;
        CHECK_INT(mcest_irradiance_exact(&s, &E), MCEST_OK);
        double err = rel_err(E, r->E);
        printf("  %-13s E = %-24.17g ref %s  rel err %.2e\n", r->name, E, r->E_digits, err);
        CHECK_REL(E, r->E, tolerance(r), "scene %s (kappa %.3g)", r->name, r->E ? kappa(r) : 0.0);
        mcest_irradiance_plan P;
        CHECK_INT(mcest_irradiance_plan_init(&s, &P), MCEST_OK);
        CHECK_REL(P.solid_angle, r->omega, !strcmp(r->name, "edge_on") ? tolerance(r) : 1e-13, "omega %s", r->name);
        CHECK(P.exact == E);
        if (r->E == 0.0)
            CHECK(E == 0.0);
    }
}

/* Invariances that must hold to rounding: vertex order, orientation,
 * normal length, translation by a power of two. */
static void test_invariances(void)
{
    const ref_scene *r = find("straddle");
    mcest_scene s = scene_of(r), t;
    double E0, E1;
    mcest_irradiance_exact(&s, &E0);
    t = s;
    for (int i = 0; i < 3; i++) { /* reverse the vertex order */
        t.triangle[3 + i] = s.triangle[6 + i];
        t.triangle[6 + i] = s.triangle[3 + i];
    }
    mcest_irradiance_exact(&t, &E1);
    CHECK_REL(E1, E0, 4e-15, "reversed");
    /* the normal's length does not matter, down to 1e-300 and up to 1e300 */
    const double lengths[] = {1e-300, 1e-200, 1e-154, 1e154, 1e200, 1e300};
    for (int k = 0; k < 6; k++) {
        t = s;
        for (int i = 0; i < 3; i++)
            t.normal[i] *= lengths[k];
        E1 = NAN;
        CHECK_INT(mcest_irradiance_exact(&t, &E1), MCEST_OK);
        CHECK_REL(E1, E0, 4e-15, "normal of length %g", lengths[k]);
    }
    t = s;
    for (int i = 0; i < 9; i++)
        t.triangle[i] += 1024.0;
    for (int i = 0; i < 3; i++)
        t.point[i] += 1024.0;
    mcest_irradiance_exact(&t, &E1);
    CHECK_REL(E1, E0, 1e-12, "translated");
    t = s;
    t.radiance = 0.0;
    mcest_irradiance_exact(&t, &E1);
    CHECK(E1 == 0.0);
    /* receiver in the emitter's plane, degenerate triangle */
    mcest_scene flat = {{0, 0, 1, 1, 0, 1, 0, 1, 1}, {0.2, 0.2, 1}, {0, 0, 1}, 1};
    CHECK_INT(mcest_irradiance_exact(&flat, &E1), MCEST_OK);
    CHECK(E1 == 0.0);
    mcest_scene line = {{0, 0, 1, 1, 0, 1, 2, 0, 1}, {0, 0, 0}, {0, 0, 1}, 1};
    CHECK_INT(mcest_irradiance_exact(&line, &E1), MCEST_OK);
    CHECK(E1 == 0.0);
}

static void test_invalid(void)
{
    mcest_scene s;
    double E;
    mcest_scene_paper(&s);
    CHECK_INT(mcest_irradiance_exact(NULL, &E), MCEST_EINVAL);
    CHECK_INT(mcest_irradiance_exact(&s, NULL), MCEST_EINVAL);
    mcest_scene t = s;
    t.normal[0] = t.normal[1] = t.normal[2] = 0.0;
    CHECK_INT(mcest_irradiance_exact(&t, &E), MCEST_EINVAL);
    t = s;
    t.triangle[4] = NAN;
    CHECK_INT(mcest_irradiance_exact(&t, &E), MCEST_EINVAL);
    t = s;
    t.point[2] = INFINITY;
    CHECK_INT(mcest_irradiance_exact(&t, &E), MCEST_EINVAL);
    t = s;
    t.radiance = -1.0;
    CHECK_INT(mcest_irradiance_exact(&t, &E), MCEST_EINVAL);
    /* a normal near DBL_MAX is still a direction (|n| = 1.4e308 is finite) */
    t = s;
    t.normal[0] = 1e308, t.normal[1] = 1e308, t.normal[2] = 0.0;
    CHECK_INT(mcest_irradiance_exact(&t, &E), MCEST_OK);
    double E1 = NAN;
    t.normal[0] = 1.0, t.normal[1] = 1.0;
    CHECK_INT(mcest_irradiance_exact(&t, &E1), MCEST_OK);
    CHECK_REL(E, E1, 4e-15, "normal near DBL_MAX");
}

/* ---- the textbook formulas, to show where they fail ---------------------- */

static void local(const ref_scene *r, double v[3][3])
{
    /* these scenes have normal +z: translation only */
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++)
            v[k][i] = r->tri[3 * k + i] - r->point[i];
}

static void unit(double *a)
{
    double l = norm3(a);
    a[0] /= l, a[1] /= l, a[2] /= l;
}

/* Lambert with acos angles and normalised cross products of vertices. */
static double naive_lambert(const double v[3][3])
{
    double s = 0.0;
    for (int k = 0; k < 3; k++) {
        double a[3], b[3], c[3];
        memcpy(a, v[k], sizeof a);
        memcpy(b, v[(k + 1) % 3], sizeof b);
        unit(a), unit(b);
        cross3(a, b, c);
        unit(c);
        s += acos(dot3(a, b)) * c[2];
    }
    return 0.5 * fabs(s);
}

/* Arvo's area: the angle excess, angles from acos of normalised normals. */
static double arvo_angles(const double v[3][3], double ang[3])
{
    double u[3][3];
    for (int k = 0; k < 3; k++) {
        memcpy(u[k], v[k], sizeof u[k]);
        unit(u[k]);
    }
    for (int k = 0; k < 3; k++) {
        double n1[3], n2[3];
        cross3(u[k], u[(k + 1) % 3], n1);
        cross3(u[k], u[(k + 2) % 3], n2);
        unit(n1), unit(n2);
        ang[k] = acos(fmax(-1.0, fmin(1.0, dot3(n1, n2))));
    }
    return ang[0] + ang[1] + ang[2] - M_PI;
}

/* Arvo's sampler as published (1995), for the triangle A, B, C. */
static void arvo_sample(const double v[3][3], double u1, double u2, double *w)
{
    double A[3], B[3], C[3], ang[3];
    memcpy(A, v[0], sizeof A), memcpy(B, v[1], sizeof B), memcpy(C, v[2], sizeof C);
    unit(A), unit(B), unit(C);
    double area = arvo_angles(v, ang);
    double alpha = ang[0];
    double ah = u1 * area;
    double s = sin(ah - alpha), t = cos(ah - alpha);
    double uu = t - cos(alpha);
    double vv = s + sin(alpha) * dot3(A, B);
    double q = ((vv * t - uu * s) * cos(alpha) - vv) / ((vv * s + uu * t) * sin(alpha));
    q = fmax(-1.0, fmin(1.0, q));
    double T[3], ca = dot3(C, A);
    for (int i = 0; i < 3; i++)
        T[i] = C[i] - ca * A[i];
    unit(T);
    double Cp[3];
    for (int i = 0; i < 3; i++)
        Cp[i] = q * A[i] + sqrt(1.0 - q * q) * T[i];
    double z = 1.0 - u2 * (1.0 - dot3(Cp, B));
    double W[3], cb = dot3(Cp, B);
    for (int i = 0; i < 3; i++)
        W[i] = Cp[i] - cb * B[i];
    unit(W);
    for (int i = 0; i < 3; i++)
        w[i] = z * B[i] + sqrt(fmax(0.0, 1.0 - z * z)) * W[i];
}

static int inside(const mcest_irradiance_plan *P, const double *w)
{
    return dot3(w, P->edge_n[0]) >= 0 && dot3(w, P->edge_n[1]) >= 0 && dot3(w, P->edge_n[2]) >= 0;
}

static void test_where_textbook_fails(void)
{
    printf("  where the textbook formulas lose precision (relative errors):\n");
    printf("  %-10s %12s %12s %12s %12s %10s %10s\n", "scene", "Lambert-acos", "ours",
           "Omega-excess", "ours", "out-Arvo", "out-ours");
    const char *names[] = {"paper", "tiny", "tiny12", "sliver", "grazing"};
    for (int k = 0; k < 5; k++) {
        const ref_scene *r = find(names[k]);
        double v[3][3];
        local(r, v);
        mcest_scene s = scene_of(r);
        mcest_irradiance_plan P;
        mcest_irradiance_plan_init(&s, &P);
        double ang[3];
        double e_naive = rel_err(naive_lambert(v), r->E);
        double e_ours = rel_err(P.exact, r->E);
        double o_naive = rel_err(arvo_angles(v, ang), r->omega);
        double o_ours = rel_err(P.solid_angle, r->omega);
        /* fraction of sampled directions outside the triangle's cone */
        int n = 20000, out_arvo = 0, out_ours = 0;
        for (int j = 0; j < n; j++) {
            mcest_u64x4 b = mcest_random_block(7, 99, (uint64_t)j, 0);
            double u1 = u01(b.v[0]), u2 = u01(b.v[1]), w[3];
            arvo_sample(v, u1, u2, w);
            out_arvo += !inside(&P, w);
            mcest_sph_tri_sample(P.fan[0], 0.5 * u1 * P.fan[0][16], u2, w);
            out_ours += !inside(&P, w);
        }
        printf("  %-10s %12.2e %12.2e %12.2e %12.2e %9.2f%% %9.2f%%\n", names[k], e_naive, e_ours,
               o_naive, o_ours, 100.0 * out_arvo / n, 100.0 * out_ours / n);
        CHECK_MSG(e_ours <= tolerance(r) && o_ours <= 1e-13, "%s", names[k]);
        /* A direction on the boundary may round either way: a few in 1e4. */
        CHECK_MSG(out_ours <= n / 1000, "%s: %d of %d outside", names[k], out_ours, n);
        if (!strcmp(names[k], "tiny12")) {
            /* The demonstration is only worth something if it fails. */
            CHECK_MSG(o_naive > 1e-6, "angle excess unexpectedly accurate: %g", o_naive);
            CHECK_MSG(e_naive > 1e-6, "acos Lambert unexpectedly accurate: %g", e_naive);
            CHECK_MSG(out_arvo >= 5 && out_ours == 0, "Arvo's sampler: %d outside", out_arvo);
        }
    }
}

int main(void)
{
    test_against_reference();
    test_invariances();
    test_invalid();
    test_where_textbook_fails();
    return h_report("test_irradiance_exact");
}
