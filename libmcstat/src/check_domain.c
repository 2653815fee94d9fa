/*
 * check_domain.c - the domains of the renderer checks and their equal-area
 * squares (check.h): a point of any domain is (s, t) in [0, 1]^2 under a
 * map of constant Jacobian, so that cells are rectangles and a uniform
 * point of a cell is a uniform (s, t).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check.h"

#include <string.h>

#define TWO_PI 6.283185307179586476925286766559

static const char *const domain_names[] = {"sphere", "hemisphere", "square", "disk", "interval"};

int mcstat__domain_get(int kind, mcstat__domain *d)
{
    static const mcstat__domain table[] = {
        {MCSTAT_CHECK_DOMAIN_SPHERE, 3, 1, 12.566370614359172953850573533118},
        {MCSTAT_CHECK_DOMAIN_HEMISPHERE, 3, 1, 6.283185307179586476925286766559},
        {MCSTAT_CHECK_DOMAIN_SQUARE, 2, 1, 1.0},
        {MCSTAT_CHECK_DOMAIN_DISK, 2, 1, 3.1415926535897932384626433832795},
        {MCSTAT_CHECK_DOMAIN_INTERVAL, 1, 0, 1.0},
    };
    if (kind < 0 || kind > MCSTAT_CHECK_DOMAIN_INTERVAL)
        return MCSTAT_EINVAL;
    *d = table[kind];
    return MCSTAT_OK;
}

int mcstat_check_domain_dims(int domain)
{
    mcstat__domain d;
    return mcstat__domain_get(domain, &d) == MCSTAT_OK ? d.dims : 0;
}

const char *mcstat_check_domain_name(int domain)
{
    return domain >= 0 && domain <= MCSTAT_CHECK_DOMAIN_INTERVAL ? domain_names[domain] : NULL;
}

int mcstat_check_domain_parse(const char *name, int *domain)
{
    if (!name || !domain)
        return MCSTAT_EINVAL;
    for (int i = 0; i <= MCSTAT_CHECK_DOMAIN_INTERVAL; i++)
        if (strcmp(name, domain_names[i]) == 0) {
            *domain = i;
            return MCSTAT_OK;
        }
    return MCSTAT_EINVAL;
}

void mcstat__domain_point(const mcstat__domain *d, double s, double t, double *x)
{
    double phi = TWO_PI * t, r;
    switch (d->kind) {
    case MCSTAT_CHECK_DOMAIN_SPHERE:
        /* r = sin(theta) = sqrt(1 - z^2) = 2 sqrt(s (1 - s)): no cancellation near the poles */
        r = 2.0 * sqrt(s * (1.0 - s));
        x[0] = r * cos(phi);
        x[1] = r * sin(phi);
        x[2] = 1.0 - 2.0 * s;
        break;
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        r = sqrt(s * (2.0 - s));
        x[0] = r * cos(phi);
        x[1] = r * sin(phi);
        x[2] = 1.0 - s;
        break;
    case MCSTAT_CHECK_DOMAIN_SQUARE:
        x[0] = s;
        x[1] = t;
        break;
    case MCSTAT_CHECK_DOMAIN_DISK:
        r = sqrt(s);
        x[0] = r * cos(phi);
        x[1] = r * sin(phi);
        break;
    default:
        x[0] = s;
        break;
    }
}

static double clamp01(double v)
{
    return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v);
}

/* t = phi/(2 pi) in [0, 1). */
static double azimuth(double x, double y)
{
    double t = atan2(y, x) / TWO_PI;
    if (t < 0.0)
        t += 1.0;
    return t >= 1.0 ? 0.0 : t;
}

int mcstat__domain_coords(const mcstat__domain *d, const double *x, double *s, double *t)
{
    for (int i = 0; i < d->dims; i++)
        if (!isfinite(x[i]))
            return 1;
    if (d->dims == 3) {
        double len2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        if (!(fabs(len2 - 1.0) <= 2e-4))
            return 1;
        double len = sqrt(len2), z = x[2] / len, rho2 = (x[0] * x[0] + x[1] * x[1]) / len2;
        /* 1 - z = rho^2 / (1 + z) for z >= 0: no cancellation near the pole */
        double one_minus_z = z >= 0.0 ? rho2 / (1.0 + z) : 1.0 - z;
        if (d->kind == MCSTAT_CHECK_DOMAIN_SPHERE) {
            *s = clamp01(0.5 * one_minus_z);
        } else {
            if (z < -1e-4)
                return 1;
            *s = clamp01(one_minus_z);
        }
        *t = azimuth(x[0], x[1]);
        return 0;
    }
    if (d->kind == MCSTAT_CHECK_DOMAIN_DISK) {
        double r2 = x[0] * x[0] + x[1] * x[1];
        if (r2 > 1.0 + 1e-6)
            return 1;
        *s = clamp01(r2);
        *t = azimuth(x[0], x[1]);
        return 0;
    }
    for (int i = 0; i < d->dims; i++)
        if (x[i] < -1e-6 || x[i] > 1.0 + 1e-6)
            return 1;
    *s = clamp01(x[0]);
    *t = d->dims == 2 ? clamp01(x[1]) : 0.5;
    return 0;
}

static uint64_t spread32(uint64_t x)
{
    x &= 0xffffffffull;
    x = (x | (x << 16)) & 0x0000ffff0000ffffull;
    x = (x | (x << 8)) & 0x00ff00ff00ff00ffull;
    x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0full;
    x = (x | (x << 2)) & 0x3333333333333333ull;
    x = (x | (x << 1)) & 0x5555555555555555ull;
    return x;
}

static uint64_t quantise(double v, double scale, uint64_t top)
{
    double q = floor(v * scale);
    return q <= 0.0 ? 0 : (q >= (double)top ? top : (uint64_t)q);
}

uint64_t mcstat__domain_key(const mcstat__domain *d, double s, double t)
{
    if (!d->two_d)
        return quantise(s, 0x1.0p64, UINT64_MAX - 2047); /* the largest double below 2^64 */
    uint64_t qs = quantise(s, 0x1.0p32, 0xffffffffull), qt = quantise(t, 0x1.0p32, 0xffffffffull);
    return (spread32(qs) << 1) | spread32(qt);
}
