/*
 * options.c - options structs that grow: reading a caller's struct of any
 * released version, and initialising one of the caller's size.
 *
 * Every options struct starts with `uint32_t size`, the sizeof of the
 * struct the caller was compiled against.  A library newer than the caller
 * knows every released size of the struct: it reads exactly `size` bytes
 * and keeps its defaults for the fields the caller's version lacks (libgit2's
 * rule).  Sizes it does not know are refused: larger ones come from a newer
 * header (fields this library would ignore), others from a struct cut short
 * inside a field.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

int mcstat__options_size_known(size_t size, const uint32_t *known, size_t n_known)
{
    for (size_t i = 0; i < n_known; i++)
        if (size == known[i])
            return 1;
    return 0;
}

int mcstat__options_read(void *dst, size_t dst_size, const void *src, const uint32_t *known, size_t n_known)
{
    uint32_t size;
    if (!src)
        return MCSTAT_EINVAL;
    memcpy(&size, src, sizeof size); /* only the size is read before it is trusted */
    if (size > dst_size || !mcstat__options_size_known(size, known, n_known))
        return MCSTAT_EINVAL;
    memcpy(dst, src, size);
    return MCSTAT_OK;
}

int mcstat__options_init(void *dst, size_t size, const void *defaults, size_t defaults_size,
                         const uint32_t *known, size_t n_known)
{
    if (!dst || size > defaults_size || !mcstat__options_size_known(size, known, n_known))
        return MCSTAT_EINVAL;
    memcpy(dst, defaults, size);
    uint32_t s = (uint32_t)size;
    memcpy(dst, &s, sizeof s);
    return MCSTAT_OK;
}
