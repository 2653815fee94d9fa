# Writes tests/data/t_ref.tsv: R's t.test with var.equal = TRUE (Student's
# pooled test) and paired = TRUE, the oracle for mcstat_t_test_2_pooled and
# mcstat_t_test_paired (statistic, df, p-value, log p-value, interval,
# estimates, standard error, printed block), the interval at a second level
# (mcstat_result_conf_int), the same for Welch's and the one-sample test,
# var.test and the chi-squared variance interval at other levels, and
# pt(log.p = TRUE) / qt at given t and df for log p-values far below the
# smallest double.  Read by tests/c/test_t_extra.c and
# tests/python/test_t_scipy.py.  Run from the repository root:
#   Rscript tools/refgen/make_t_ref.R
# (R 4.2.2 produced the committed file.)
hex <- function(x) ifelse(is.na(x) & !is.nan(x), "NA",
                   ifelse(is.finite(x), sprintf("%a", x),
                          ifelse(is.nan(x), "NaN", ifelse(x > 0, "Inf", "-Inf"))))
hexlist <- function(v) if (is.null(v)) "-" else paste(sprintf("%a", v), collapse = ",")
esc <- function(s) gsub("\t", "\\\\t", gsub("\n", "\\\\n", s))
alts <- c("two.sided", "less", "greater")
rows <- character(0)
row <- function(...) rows[[length(rows) + 1]] <<- paste(c(...), collapse = "\t")

# The log of t.test's p-value from pt in log scale (finite where p underflows).
log_p_t <- function(t, df, alt) switch(alt,
  two.sided = log(2) + pt(-abs(t), df, log.p = TRUE),
  less = pt(t, df, log.p = TRUE),
  greater = pt(t, df, lower.tail = FALSE, log.p = TRUE))

# kind: pooled, paired, welch, one
# shift: R's means of data near a large offset are rounded to the offset's
# ulp (1e9: 1.2e-7), so the reference runs on the data minus shift (exact:
# Sterbenz) and adds it back to the estimates; the block is then not R's.
add_t <- function(kind, x, y, alt, mu = 0, conf = 0.95, conf2 = 0.5, shift = 0) {
  x0 <- x; y0 <- y
  x <- x - shift; if (!is.null(y)) y <- y - shift
  call <- function(cl) switch(kind,
    pooled = t.test(x, y, alternative = alt, mu = mu, var.equal = TRUE, conf.level = cl),
    paired = t.test(x, y, alternative = alt, mu = mu, paired = TRUE, conf.level = cl),
    welch = t.test(x, y, alternative = alt, mu = mu, conf.level = cl),
    one = t.test(x, alternative = alt, mu = mu, conf.level = cl))
  r <- call(conf)
  r2 <- call(conf2)
  est <- unname(r$estimate)
  if (kind != "paired") est <- est + shift
  txt <- if (shift == 0) esc(paste0(paste(capture.output(print(r)), collapse = "\n"), "\n")) else "-"
  row(kind, match(alt, alts) - 1, hex(mu), hex(1 - conf), hexlist(x0), if (kind == "one") "-" else hexlist(y0),
      hex(unname(r$statistic)), hex(unname(r$parameter)), hex(r$p.value),
      hex(log_p_t(unname(r$statistic), unname(r$parameter), alt)),
      hex(r$conf.int[1]), hex(r$conf.int[2]), hex(est[1]), hex(if (length(est) > 1) est[2] else NA),
      hex(r$stderr), hex(conf2), hex(r2$conf.int[1]), hex(r2$conf.int[2]), txt)
}

# R's qf (through qbeta) loses digits in the far tails at small df:
# qf(5e-7, 1, 1) is 6.16840e-13, the exact tan(pi p / 2)^2 is 6.16850e-13.
# pf and pchisq are accurate there, so the quantiles of the intervals are
# polished by Newton steps on the log of the tail.
polish <- function(q, p, lower, cdf, dens) {
  for (i in 1:4) {
    lp <- cdf(q, lower.tail = lower, log.p = TRUE)
    step <- (lp - log(p)) * exp(lp) / dens(q) * (if (lower) 1 else -1)
    if (!is.finite(step)) break
    q <- q - step
  }
  q
}
qf_ <- function(p, d1, d2, lower.tail = TRUE)
  polish(qf(p, d1, d2, lower.tail = lower.tail), p, lower.tail,
         function(q, ...) pf(q, d1, d2, ...), function(q) df(q, d1, d2))
qchisq_ <- function(p, d, lower.tail = TRUE)
  polish(qchisq(p, d, lower.tail = lower.tail), p, lower.tail,
         function(q, ...) pchisq(q, d, ...), function(q) dchisq(q, d))

# var.test (F) and the chi-squared variance test (no R function: its
# interval by the formula, its p-value from pchisq), at two levels.
add_var <- function(kind, x, y, alt, null, conf = 0.95, conf2 = 0.5) {
  if (kind == "var2") {
    r <- var.test(x, y, ratio = null, alternative = alt, conf.level = conf)
    stat <- unname(r$statistic); df <- unname(r$parameter); est <- unname(r$estimate)
    # var.test's interval, with the polished quantiles
    ci <- function(cl) {
      a <- 1 - cl
      switch(alt, two.sided = c(est / qf_(a / 2, df[1], df[2], FALSE), est / qf_(a / 2, df[1], df[2])),
             less = c(0, est / qf_(a, df[1], df[2])), greater = c(est / qf_(a, df[1], df[2], FALSE), Inf))
    }
    fin <- is.finite(r$conf.int)
    stopifnot(all(ci(conf)[!fin] == r$conf.int[!fin]),
              all(abs(ci(conf) - r$conf.int)[fin] <= 1e-4 * abs(r$conf.int[fin])))
    r$conf.int <- ci(conf)
    r2 <- list(conf.int = ci(conf2))
    lp <- switch(alt, two.sided = log(2) + min(pf(stat, df[1], df[2], log.p = TRUE),
                                               pf(stat, df[1], df[2], lower.tail = FALSE, log.p = TRUE)),
                 less = pf(stat, df[1], df[2], log.p = TRUE),
                 greater = pf(stat, df[1], df[2], lower.tail = FALSE, log.p = TRUE))
    # the p-value from the log tails: var.test's 1 - pf loses the small upper tail
    row(kind, match(alt, alts) - 1, hex(null), hex(1 - conf), hexlist(x), hexlist(y), hex(stat), hex(df[1]),
        hex(min(1, exp(lp))), hex(min(lp, 0)), hex(r$conf.int[1]), hex(r$conf.int[2]), hex(unname(r$estimate)),
        hex(df[2]), "NA", hex(conf2), hex(r2$conf.int[1]), hex(r2$conf.int[2]), "-")
  } else {
    n <- length(x); df <- n - 1; m2 <- sum((x - mean(x))^2); stat <- m2 / null
    ci <- function(cl) {
      a <- 1 - cl
      switch(alt, two.sided = c(m2 / qchisq_(a / 2, df, lower.tail = FALSE), m2 / qchisq_(a / 2, df)),
             less = c(0, m2 / qchisq_(a, df)), greater = c(m2 / qchisq_(a, df, lower.tail = FALSE), Inf))
    }
    lp <- switch(alt, two.sided = log(2) + min(pchisq(stat, df, log.p = TRUE),
                                               pchisq(stat, df, lower.tail = FALSE, log.p = TRUE)),
                 less = pchisq(stat, df, log.p = TRUE), greater = pchisq(stat, df, lower.tail = FALSE, log.p = TRUE))
    c1 <- ci(conf); c2 <- ci(conf2)
    row(kind, match(alt, alts) - 1, hex(null), hex(1 - conf), hexlist(x), "-", hex(stat), hex(df),
        hex(min(1, exp(lp))), hex(min(lp, 0)), hex(c1[1]), hex(c1[2]), hex(var(x)), "NA", "NA", hex(conf2),
        hex(c2[1]), hex(c2[2]), "-")
  }
}

# A t statistic and df alone (mcstat_result_conf_int and the log p-value of
# a result built by hand): the p-value in log scale and est -+ qt se.
add_tsyn <- function(t, df, alt, se, mu, conf2) {
  a <- 1 - conf2; est <- mu + t * se
  ci <- switch(alt, two.sided = est + c(-1, 1) * qt(a / 2, df, lower.tail = FALSE) * se,
               less = c(-Inf, est + qt(a, df, lower.tail = FALSE) * se),
               greater = c(est - qt(a, df, lower.tail = FALSE) * se, Inf))
  lp <- log_p_t(t, df, alt)
  row("tsyn", match(alt, alts) - 1, hex(mu), "NA", "-", "-", hex(t), hex(df), hex(min(1, exp(lp))), hex(lp),
      "NA", "NA", hex(est), "NA", hex(se), hex(conf2), hex(ci[1]), hex(ci[2]), "-")
}

set.seed(20261203)
levels2 <- c(0.5, 0.999999, 0.9, 0.99)
k <- 0
for (a in alts) {
  for (i in 1:6) {
    k <- k + 1
    nx <- sample(c(2, 3, 5, 10, 30, 100), 1); ny <- sample(c(2, 3, 5, 10, 30, 100), 1)
    x <- rnorm(nx, 10, 2); y <- rnorm(ny, 10 + rnorm(1), sample(c(0.5, 2, 5), 1))
    add_t("pooled", x, y, a, mu = sample(c(0, 0.5, -1), 1), conf = sample(c(0.95, 0.9, 0.99), 1),
          conf2 = levels2[(k %% 4) + 1])
    n <- sample(c(2, 3, 4, 8, 25, 200), 1)
    x <- rnorm(n, 5, 3); y <- x + rnorm(n, sample(c(0, 0.3, 1), 1), sample(c(0.1, 1), 1))
    add_t("paired", x, y, a, mu = sample(c(0, 0.2), 1), conf = sample(c(0.95, 0.8), 1),
          conf2 = levels2[((k + 1) %% 4) + 1])
    add_t("welch", x, y + rnorm(n), a, conf2 = levels2[((k + 2) %% 4) + 1])
    add_t("one", x, NULL, a, mu = 4, conf2 = levels2[((k + 3) %% 4) + 1])
    add_var("var2", x, y + rnorm(n) * 3, a, sample(c(1, 2.5), 1), conf2 = levels2[(k %% 4) + 1])
    add_var("var1", x, NULL, a, sample(c(9, 4), 1), conf2 = levels2[((k + 1) %% 4) + 1])
  }
  # one constant sample (pooled): fine, as in R
  add_t("pooled", rep(3, 5), c(2.5, 3.1, 4, 2.2), a)
  # a large common offset: the differences and the interval keep their digits
  x <- 1e9 + rnorm(12, 0, 1e-3); add_t("paired", x, x - 2e-4 + rnorm(12, 0, 1e-4), a, conf2 = 0.999999)
  add_t("pooled", 1e9 + rnorm(7, 0, 1e-3), 1e9 + 1e-3 + rnorm(9, 0, 1e-3), a, conf2 = 0.999999, shift = 1e9)
  # huge t: p underflows in double, its log does not
  add_t("pooled", 1000 + rnorm(60, 0, 1e-6), rnorm(60), a)
  add_t("paired", rnorm(120) + 1000, rnorm(120, 0, 1e-5), a)
  # the smallest df: paired n = 2 (df 1), pooled 2 + 2 (df 2), at 0.999999
  add_t("paired", c(1.5, 2.25), c(0.5, 0.5), a, conf2 = 0.999999)
  add_t("pooled", c(1, 2.5), c(0.1, 0.4), a, conf2 = 0.999999)
  # larger df: 600 + 400, and 1000 pairs (df 1e9 below, from t alone)
  add_t("pooled", rnorm(600), rnorm(400, 0.05), a, conf2 = 0.999999)
  x <- rnorm(1000); add_t("paired", x, x + rnorm(1000, -0.02, 1), a, conf2 = 0.5)
  # the F test's and the variance test's intervals at the extreme level
  add_var("var2", rnorm(4), rnorm(3), a, 1, conf2 = 0.999999)
  add_var("var1", rnorm(3), NULL, a, 1, conf2 = 0.999999)
  # log p from t and df alone, deep tails and extreme df
  add_tsyn(-1e5, 9, a, 0.01, 2, 0.95)
  add_tsyn(40, 1e9, a, 1, 0, 0.999999)
  add_tsyn(3e4, 1e-3 * 1000, a, 2.5, -1, 0.5)
  add_tsyn(-7, 0.5, a, 1e-3, 1e9, 0.999999)
  add_tsyn(1e150, 3, a, 1e-100, 0, 0.99)
  add_tsyn(0.3, 1e6, a, 3, 0, 0.5)
}

header <- c("# Generated by tools/refgen/make_t_ref.R (R 4.2.2); do not edit.",
            "# kind alt null alpha x y statistic df p log_p lo hi est est2_or_df2 stderr conf2 lo2 hi2 block")
writeLines(c(header, rows), "tests/data/t_ref.tsv")
cat(length(rows), "rows\n")
