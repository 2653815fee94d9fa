/*
 * test_options.c - options structs that grow (options.c): a caller compiled
 * against an older, smaller version of a struct is read correctly by a
 * library that knows a newer one, and sizes no release had are refused.
 *
 * Today every public options struct has had one size (0.1.0's), so the
 * mechanism is exercised here on a struct family with a release history:
 * v1, and v2 which appended two fields.  test_abi checks the public structs
 * through the shared library.
 */
#include "harness.h"
#include "internal.h"

#include <string.h>

typedef struct {
    uint32_t size;
    int32_t a;
    double b;
} opts_v1; /* 16 bytes: the older release */

typedef struct {
    uint32_t size;
    int32_t a;
    double b;
    int64_t c; /* appended in v2 */
    double d;  /* appended in v2 */
} opts_v2; /* 32 bytes: the library's current struct */

static const uint32_t SIZES[] = {sizeof(opts_v1), sizeof(opts_v2)};
#define N_SIZES (sizeof SIZES / sizeof *SIZES)
static const opts_v2 DEFAULTS = {sizeof(opts_v2), 1, 2.0, 3, 4.0};

/* What a library function does with the caller's options. */
static int lib_read(const void *caller, opts_v2 *o)
{
    *o = DEFAULTS;
    return mcstat__options_read(o, sizeof *o, caller, SIZES, N_SIZES);
}

/* The caller's struct at the start of a poisoned buffer: the library must
 * not use a byte past caller->size. */
static unsigned char buf[64];
static void poison(void) { memset(buf, 0xAB, sizeof buf); }

static int poisoned_from(size_t from)
{
    for (size_t i = from; i < sizeof buf; i++)
        if (buf[i] != 0xAB)
            return 0;
    return 1;
}

static void test_read(void)
{
    opts_v2 o;
    /* an older caller: its fields, the library's defaults for the rest */
    poison();
    opts_v1 old = {sizeof(opts_v1), 10, 20.0};
    memcpy(buf, &old, sizeof old);
    CHECK_INT(lib_read(buf, &o), MCSTAT_OK);
    CHECK(o.size == sizeof(opts_v1) && o.a == 10 && o.b == 20.0);
    CHECK(o.c == 3 && o.d == 4.0);
    /* a current caller: every field its own */
    opts_v2 cur = {sizeof(opts_v2), 10, 20.0, 30, 40.0};
    CHECK_INT(lib_read(&cur, &o), MCSTAT_OK);
    CHECK(!memcmp(&o, &cur, sizeof o));
    /* refused, and the defaults untouched: a newer caller (fields this
     * library would silently ignore), a struct cut short inside or between
     * fields, and nonsense */
    const uint32_t bad[] = {sizeof(opts_v2) + 8, 24, 12, 8, 4, 0, UINT32_MAX};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        poison();
        memcpy(buf, &bad[i], sizeof bad[i]);
        CHECK_INT(lib_read(buf, &o), MCSTAT_EINVAL);
        CHECK(o.size == sizeof(opts_v2) && o.a == 1 && o.b == 2.0 && o.c == 3 && o.d == 4.0);
    }
    CHECK_INT(lib_read(NULL, &o), MCSTAT_EINVAL);
}

static void test_init(void)
{
    /* an older caller's initialiser writes its struct, nothing beyond */
    poison();
    CHECK_INT(mcstat__options_init(buf, sizeof(opts_v1), &DEFAULTS, sizeof DEFAULTS, SIZES, N_SIZES), MCSTAT_OK);
    opts_v1 old;
    memcpy(&old, buf, sizeof old);
    CHECK(old.size == sizeof(opts_v1) && old.a == 1 && old.b == 2.0);
    CHECK(poisoned_from(sizeof(opts_v1)));
    /* and the struct it wrote is accepted, with v2's defaults for the rest */
    opts_v2 o;
    CHECK_INT(lib_read(buf, &o), MCSTAT_OK);
    CHECK(!memcmp(&o.a, &DEFAULTS.a, sizeof o - offsetof(opts_v2, a)));
    /* the current size: the whole struct */
    poison();
    CHECK_INT(mcstat__options_init(buf, sizeof(opts_v2), &DEFAULTS, sizeof DEFAULTS, SIZES, N_SIZES), MCSTAT_OK);
    CHECK(!memcmp(buf, &DEFAULTS, sizeof DEFAULTS) && poisoned_from(sizeof(opts_v2)));
    /* unknown sizes: nothing written */
    const size_t bad[] = {sizeof(opts_v2) + 8, 24, 4, 0};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        poison();
        CHECK_INT(mcstat__options_init(buf, bad[i], &DEFAULTS, sizeof DEFAULTS, SIZES, N_SIZES), MCSTAT_EINVAL);
        CHECK(poisoned_from(0));
    }
    CHECK_INT(mcstat__options_init(NULL, sizeof(opts_v1), &DEFAULTS, sizeof DEFAULTS, SIZES, N_SIZES),
              MCSTAT_EINVAL);
}

int main(void)
{
    test_read();
    test_init();
    return h_report("test_options");
}
