/*
 * test_abi.c - linked against the shared library: the sizes, versions and
 * constants an FFI caller reads at run time agree with the header.
 */
#include "harness.h"
#include "mcstat.h"

#include <stddef.h>
#include <string.h>

int main(void)
{
    CHECK_INT(mcstat_version_number(), MCSTAT_VERSION_NUMBER);
    char v[32];
    snprintf(v, sizeof v, "%d.%d.%d", MCSTAT_VERSION_MAJOR, MCSTAT_VERSION_MINOR, MCSTAT_VERSION_PATCH);
    CHECK(!strcmp(mcstat_version(), v));
    CHECK_INT(mcstat_sizeof_moments(), sizeof(mcstat_moments));
    CHECK_INT(mcstat_sizeof_result(), sizeof(mcstat_result));
    CHECK_INT(mcstat_moments_bytes(), MCSTAT_MOMENTS_BYTES);
    /* the documented, fixed layout of the accumulator (FFI callers mirror it) */
    CHECK_INT(sizeof(mcstat_moments), 128);
    CHECK_INT(offsetof(mcstat_moments, n), 0);
    CHECK_INT(offsetof(mcstat_moments, scale), 8);
    CHECK_INT(offsetof(mcstat_moments, mean), 16);
    CHECK_INT(offsetof(mcstat_moments, m2), 32);
    CHECK_INT(offsetof(mcstat_moments, max), 64);
    CHECK_INT(offsetof(mcstat_result, n), 32);
    CHECK_INT(offsetof(mcstat_result, statistic), 48);
    /* the embedded-check accumulator: a fixed 4096-byte layout */
    CHECK_INT(mcstat_sizeof_stream(), sizeof(mcstat_stream));
    CHECK_INT(sizeof(mcstat_stream), MCSTAT_STREAM_BYTES);
    CHECK_INT(offsetof(mcstat_stream, count), 128);
    CHECK_INT(offsetof(mcstat_stream, buf), 160);
    /* enum values are part of the ABI */
    CHECK_INT(MCSTAT_TWO_SIDED, 0);
    CHECK_INT(MCSTAT_LESS, 1);
    CHECK_INT(MCSTAT_GREATER, 2);
    CHECK_INT(MCSTAT_EINVAL, 1);
    CHECK_INT(MCSTAT_ECORRUPT, 8);
    /* one call through the shared library */
    const double x[4] = {1.0, 2.0, 3.0, 5.0};
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1(x, 4, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_INT(r.test, MCSTAT_TEST_T_1);
    return h_report("test_abi");
}
