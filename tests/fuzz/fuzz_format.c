/*
 * fuzz_format.c - mcstat_result_format on arbitrary results, names and
 * buffer sizes, and the small string functions (alternative_parse/name,
 * strerror, decision_name, version).
 *
 * Input: the result's integer fields (small valid values or any int32) and
 * doubles (fz_double), the names (NULL or NUL-terminated strings of up to
 * 600 bytes, so they exceed any internal line buffer), the buffer size
 * (0..4096: the buffer is malloc'ed at exactly that size, so AddressSanitizer
 * sees a single byte written past it), then a string for alternative_parse
 * and integers for the name functions.
 * Invariants: the status is OK, EINVAL or EBUFSIZE; the reported length is
 * the same at every buffer size and equals strlen of the full text; a
 * buffer too small gets a NUL-terminated prefix of the full text; every
 * name the library returns parses back to its value.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#include <stdlib.h>

#define BIG 65536

static int32_t small_or_any(fz_input *in, int32_t lo, int32_t hi)
{
    uint8_t b = fz_u8(in);
    return b < 240 ? lo + b % (hi - lo + 1) : (int32_t)fz_u32(in);
}

/* A string of up to max bytes, or NULL when the length byte says so. */
static const char *fz_string(fz_input *in, char *buf, size_t max, int allow_null)
{
    uint16_t k = fz_u16(in);
    if (allow_null && k == 0xffff)
        return NULL;
    size_t n = fz_bytes(in, (uint8_t *)buf, k % (max + 1));
    buf[n] = '\0';
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    mcstat_result r;
    memset(&r, 0, sizeof r);
    r.test = small_or_any(&in, 0, 6);
    r.method = small_or_any(&in, 0, 5);
    r.alternative = small_or_any(&in, 0, 3);
    r.reject = small_or_any(&in, 0, 2);
    r.decision = small_or_any(&in, -1, 2);
    r.reserved_i[0] = small_or_any(&in, 0, 2);
    r.n[0] = fz_u8(&in) < 200 ? fz_u8(&in) : fz_u64(&in);
    r.n[1] = fz_u8(&in) < 200 ? fz_u8(&in) : fz_u64(&in);
    double *d[] = {&r.statistic, &r.df[0],       &r.df[1],       &r.p_value,     &r.p_value_se,
                   &r.conf_int[0], &r.conf_int[1], &r.estimate[0], &r.estimate[1], &r.null_value,
                   &r.alpha,       &r.critical[0], &r.critical[1], &r.std_error,   &r.reserved[0],
                   &r.reserved[1]};
    for (size_t i = 0; i < sizeof d / sizeof d[0]; i++)
        *d[i] = fz_double(&in);
    static char xname[601], yname[601];
    const char *xn = fz_string(&in, xname, 600, 1), *yn = fz_string(&in, yname, 600, 1);
    size_t bsize = (size_t)fz_range(&in, 0, 4096);

    static char full[BIG];
    size_t flen = 7777777;
    int st = mcstat_result_format(&r, xn, yn, full, BIG, &flen);
    FZ_ASSERT(st == MCSTAT_OK || st == MCSTAT_EINVAL || st == MCSTAT_EBUFSIZE, "format status %d", st);
    if (st == MCSTAT_OK) {
        FZ_ASSERT(flen == strlen(full), "length %zu, strlen %zu", flen, strlen(full));
        char *buf = malloc(bsize ? bsize : 1);
        size_t len = 7777777;
        int st2 = mcstat_result_format(&r, xn, yn, bsize ? buf : NULL, bsize, &len);
        if (bsize > flen) {
            FZ_ASSERT(st2 == MCSTAT_OK && len == flen && strcmp(buf, full) == 0, "size %zu: status %d, length %zu",
                      bsize, st2, len);
        } else {
            FZ_ASSERT(st2 == MCSTAT_EBUFSIZE || (bsize == 0 && st2 == MCSTAT_EINVAL), "size %zu of %zu: status %d",
                      bsize, flen, st2);
            if (st2 == MCSTAT_EBUFSIZE) {
                FZ_ASSERT(len == flen, "size %zu: length %zu, want %zu", bsize, len, flen);
                if (bsize > 0)
                    FZ_ASSERT(strlen(buf) < bsize && strncmp(buf, full, strlen(buf)) == 0,
                              "size %zu: not a prefix", bsize);
            }
        }
        /* length may be NULL */
        st2 = mcstat_result_format(&r, xn, yn, full, BIG, NULL);
        FZ_ASSERT(st2 == MCSTAT_OK, "NULL length: status %d", st2);
        free(buf);
    }
    FZ_ASSERT(mcstat_result_format(NULL, xn, yn, full, BIG, &flen) == MCSTAT_EINVAL, "NULL result");

    /* The string functions. */
    static char name[64];
    const char *s = fz_string(&in, name, 63, 1);
    int alt = -99;
    st = mcstat_alternative_parse(s, &alt);
    FZ_ASSERT(st == MCSTAT_OK || st == MCSTAT_EINVAL, "parse status %d", st);
    if (st == MCSTAT_OK) {
        const char *back = mcstat_alternative_name(alt);
        FZ_ASSERT(back != NULL, "parsed %d has no name", alt);
        int again = -1;
        FZ_ASSERT(mcstat_alternative_parse(back, &again) == MCSTAT_OK && again == alt, "name %s", back);
    } else {
        FZ_ASSERT(alt == -99, "parse wrote with status %d", st);
    }
    int k = (int)(int32_t)fz_u32(&in);
    const char *an = mcstat_alternative_name(k);
    FZ_ASSERT((an != NULL) == (k >= 0 && k <= 2), "alternative_name(%d)", k);
    if (an) {
        int a2 = -1;
        FZ_ASSERT(mcstat_alternative_parse(an, &a2) == MCSTAT_OK && a2 == k, "parse(name(%d))", k);
    }
    FZ_ASSERT((mcstat_decision_name(k) != NULL) == (k >= -1 && k <= 1), "decision_name(%d)", k);
    const char *e = mcstat_strerror(k);
    FZ_ASSERT(e != NULL && *e, "strerror(%d)", k);
    FZ_ASSERT(mcstat_version_number() == MCSTAT_VERSION_NUMBER && mcstat_version() != NULL, "version");
    return 0;
}
