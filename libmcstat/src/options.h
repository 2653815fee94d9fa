/*
 * options.h - options structs that grow (options.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_OPTIONS_H
#define MCSTAT_OPTIONS_H

/* ---- options structs that grow (options.c) --------------------------------
 * known[0..n_known) are the sizes of every released version of a struct
 * (MCSTAT_*_OPTIONS_SIZE_*), the last its current sizeof.
 * _read: *dst holds the defaults (dst_size bytes, the current struct); the
 *   caller's struct src (starting with its uint32_t size) is copied over its
 *   first `size` bytes, so fields src's version lacks keep their defaults;
 *   dst's size field is then the caller's.  MCSTAT_EINVAL (nothing copied)
 *   for src NULL or a size not in known.
 * _init: writes the first `size` bytes of `defaults` (a current struct) to
 *   dst, with size in its size field; MCSTAT_EINVAL for an unknown size. */
MCSTAT_HIDDEN int mcstat__options_size_known(size_t size, const uint32_t *known, size_t n_known);
MCSTAT_HIDDEN int mcstat__options_read(void *dst, size_t dst_size, const void *src, const uint32_t *known,
                                       size_t n_known);
MCSTAT_HIDDEN int mcstat__options_init(void *dst, size_t size, const void *defaults, size_t defaults_size,
                                       const uint32_t *known, size_t n_known);
/* *r <- the caller's power options o read as above (power.c); used by
 * format.c too.  MCSTAT_EINVAL for NULL or an unknown size. */
MCSTAT_HIDDEN int mcstat__power_options_read(const mcstat_power_options *o, mcstat_power_options *r);

#endif /* MCSTAT_OPTIONS_H */
