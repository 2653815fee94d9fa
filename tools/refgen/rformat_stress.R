# R's format(x, digits = d) on ~19,500 values for d = 1..15 (~290,000 lines):
# decimal rounding ties N.5 * 10^k (N of d digits) and their two neighbouring
# doubles, for k near 0 and near the ends of the double range, plus random
# magnitudes.  Written as "hex<TAB>digits<TAB>text" to the file given;
# tools/refgen/rformat_stress.c compares libmcstat's formatting with it:
#   Rscript tools/refgen/rformat_stress.R /tmp/rformat_stress.tsv
#   cc -O2 -Ilibmcstat/src -Ilibmcstat/include tools/refgen/rformat_stress.c \
#      libmcstat/src/rformat.c -lm -o /tmp/rformat_stress
#   /tmp/rformat_stress /tmp/rformat_stress.tsv
# (add -mlong-double-64 to check a 64-bit long double build).  Near-tie values
# where R's own arithmetic decides were copied into make_rformat.R from it.
args <- commandArgs(trailingOnly = TRUE)
set.seed(1)
v <- c()
for (i in 1:6000) {
  d <- sample(1:15, 1)
  N <- floor(runif(1, 10^(d-1), 10^d))
  k <- sample(c(-340:-300, -40:40, 280:300), 1)
  x <- as.numeric(sprintf("%.0f5e%d", N, k - d))
  if (is.finite(x) && x > 0) v <- c(v, x, x * (1 + 2^-52), x * (1 - 2^-53))
}
v <- c(v, runif(3000) * 10^runif(3000, -320, 300), 4.9406564584124654e-324, 2.2250738585072014e-308,
       1.7976931348623157e308, 9.999, 485.1)
v <- v[is.finite(v) & v > 0]
v <- c(v, -v[1:500])
lines <- c()
for (d in 1:15)
  lines <- c(lines, sprintf("%a\t%d\t%s", v, d, sapply(v, function(x) format(x, digits = d))))
writeLines(lines, args[1])
