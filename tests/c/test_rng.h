/*
 * test_rng.h - a small deterministic generator for the C tests (splitmix64).
 * The including file defines its seed first:
 *     static uint64_t rng_state = 777;
 *     #include "test_rng.h"
 */
#ifndef MCSTAT_TEST_RNG_H
#define MCSTAT_TEST_RNG_H

#include <math.h>
#include <stdint.h>

static double unif(void) /* splitmix64, 53 bits, in (0, 1) */
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

static double normal(void) /* Box-Muller, one of the pair */
{
    return sqrt(-2.0 * log(unif())) * cos(2.0 * M_PI * unif());
}

#endif
