# Reference adjusted p-values from R's p.adjust, for tests/c/test_p_adjust.c
# and tests/python/test_p_adjust.py.  Writes tests/data/p_adjust_ref.txt:
#   Rscript tools/refgen/make_p_adjust_ref.R
#
# Format, one record per line, numbers as %.17g, NaN for R's NA:
#   case NAME METHOD N       then a line "p ..." and a line "adj ..." (N values each)
#   large METHOD N           the generated p-values gen(N) below, then lines
#   at K VALUE               adjusted value at 0-based index K (every 997th)
#   sum VALUE COUNT05        sum of the non-NA adjusted values, number <= 0.05
# gen(N) uses only integer arithmetic, correctly rounded * and /, and floor,
# so C and Python rebuild exactly the same doubles.
methods <- c("bonferroni", "holm", "hochberg", "hommel", "BH", "BY")
out <- file("tests/data/p_adjust_ref.txt", "w")
fmt <- function(x) ifelse(is.na(x), "NaN", sprintf("%.17g", x))

write_case <- function(name, p) {
  for (m in methods) {
    a <- p.adjust(p, method = m)
    writeLines(sprintf("case %s %s %d", name, m, length(p)), out)
    writeLines(paste("p", paste(fmt(p), collapse = " ")), out)
    writeLines(paste("adj", paste(fmt(a), collapse = " ")), out)
  }
}

set.seed(20261123)
write_case("n1", c(0.03))
write_case("n1_na", c(NA, 0.03, NA))
write_case("n2", c(0.04, 0.01))
write_case("n3", c(0.02, 0.5, 0.011))
write_case("zeros_ones", c(0, 1, 0, 0.5, 1, 1e-300, 0.05))
write_case("ties", c(0.01, 0.02, 0.02, 0.02, 0.03, 0.01, 0.5, 0.5, 0.04, 0.001))
write_case("all_equal", rep(0.2, 9))
write_case("with_na", c(0.01, NA, 0.04, 0.03, NA, 0.005, 0.9, 0.2))
write_case("uniform50", runif(50))
write_case("mixed200", c(runif(150), rbeta(50, 0.1, 5)))
write_case("rounded300", round(c(runif(200), rbeta(100, 0.2, 3)), 3))
write_case("tiny", c(1e-12, 3e-10, 2e-9, 1e-8, 0.3, 0.7, 5e-11))

gen <- function(N) {
  k <- 0:(N - 1)
  u <- ((k * 7919 + 12345) %% 1000003) / 1000003
  p <- u
  r <- k %% 7 == 0
  p[r] <- floor(u[r] * 1000) / 1000          # ties
  s <- k %% 10 == 0
  p[s] <- u[s] * u[s] * u[s] * u[s] * 1e-3   # signals
  p[k %% 5000 == 1] <- 0
  p[k %% 5000 == 2] <- 1
  p[k %% 1000 == 999] <- NA
  p
}
for (m in methods) {
  N <- if (m == "hommel") 20000 else 1000000   # R's Hommel is O(N^2)
  p <- gen(N)
  a <- p.adjust(p, method = m)
  writeLines(sprintf("large %s %d", m, N), out)
  idx <- seq(0, N - 1, by = 997)
  writeLines(sprintf("at %d %s", idx, fmt(a[idx + 1])), out)
  writeLines(sprintf("sum %s %d", fmt(sum(a, na.rm = TRUE)), sum(a <= 0.05, na.rm = TRUE)), out)
}
close(out)
