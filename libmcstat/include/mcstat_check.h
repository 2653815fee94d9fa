/*
 * mcstat_check.h - the old name of mcstat/embedded.h: the checks embedded
 * in a renderer (MCSTAT_CHECK_ADD, MCSTAT_CHECK_MEAN, MCSTAT_CHECK_SEQ_PUSH,
 * ...), whose name read as that of the renderer checks (mcstat_check_bsdf
 * and the rest, mcstat/check.h).  Deprecated in 0.3: include
 * <mcstat/embedded.h>; this name stays through 0.4.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_CHECK_H
#define MCSTAT_CHECK_H
#include "mcstat/embedded.h"
#endif /* MCSTAT_CHECK_H */
