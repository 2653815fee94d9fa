# Writes tests/data/r_blocks.json: R's printed t.test / var.test
# output for fixed data sets, with the data named as in a user's session
# (the "data:" line), the oracle for str(result) and result.format() in
# tests/python/test_format.py.  Run from the repository root:
#   Rscript tools/refgen/make_rblocks_python.R
# (R 4.2.2 produced the committed file; R is not needed at test time.)
set.seed(424242)
hex <- function(x) sprintf("\"%a\"", x)
jstr <- function(s) paste0("\"", gsub("\n", "\\\\n", gsub("\t", "\\\\t", gsub("\"", "\\\\\"", gsub("\\\\", "\\\\\\\\", s)))), "\"")
blocks <- character(0)
add <- function(call, test, xname, yname, x, y, null, alt, conf) {
  txt <- paste0(paste(capture.output(print(call)), collapse = "\n"), "\n")
  fields <- c(sprintf("\"test\": \"%s\"", test), sprintf("\"x_name\": %s", jstr(xname)),
              sprintf("\"y_name\": %s", if (is.null(yname)) "null" else jstr(yname)),
              sprintf("\"x\": [%s]", paste(hex(x), collapse = ", ")),
              sprintf("\"y\": %s", if (is.null(y)) "null" else sprintf("[%s]", paste(hex(y), collapse = ", "))),
              sprintf("\"null_value\": %s", hex(null)), sprintf("\"alternative\": \"%s\"", alt),
              sprintf("\"alpha\": %s", hex(1 - conf)), sprintf("\"r_text\": %s", jstr(txt)))
  blocks <<- c(blocks, paste0("  {", paste(fields, collapse = ", "), "}"))
}
alt_py <- c(two.sided = "two-sided", less = "less", greater = "greater")

new <- round(rnorm(12, 1.0, 0.4), 3)
trusted <- round(rnorm(15, 1.2, 0.3), 3)
add(t.test(new, trusted), "t_test", "new", "trusted", new, trusted, 0, "two-sided", 0.95)
add(t.test(new, trusted, alternative = "less", conf.level = 0.99), "t_test", "new", "trusted",
    new, trusted, 0, "less", 0.99)
add(t.test(new, mu = 1.1), "t_test", "new", NULL, new, NULL, 1.1, "two-sided", 0.95)
add(t.test(new, mu = 0.5, alternative = "greater", conf.level = 0.9), "t_test", "new", NULL,
    new, NULL, 0.5, "greater", 0.9)
add(var.test(new, trusted), "var_test", "new", "trusted", new, trusted, 1, "two-sided", 0.95)
add(var.test(new, trusted, ratio = 2, alternative = "greater"), "var_test", "new", "trusted",
    new, trusted, 2, "greater", 0.95)
estimator_U <- rexp(40, 2) * 1e-3
estimator_S <- rnorm(30, 0.5e-3, 1e-4)
add(t.test(estimator_U, estimator_S), "t_test", "estimator_U", "estimator_S",
    estimator_U, estimator_S, 0, "two-sided", 0.95)
add(var.test(estimator_U, estimator_S, alternative = "less", conf.level = 0.99), "var_test",
    "estimator_U", "estimator_S", estimator_U, estimator_S, 1, "less", 0.99)
x <- rnorm(25, 1e9, 1e-3)
add(t.test(x, mu = 1e9), "t_test", "x", NULL, x, NULL, 1e9, "two-sided", 0.95)
x <- rnorm(8); y <- rnorm(300, 3, 5)
add(t.test(x, y, mu = -2), "t_test", "x", "y", x, y, -2, "two-sided", 0.95)
for (i in 1:10) {
  a <- rnorm(sample(3:60, 1), runif(1, -3, 3), runif(1, 0.1, 4)) * 10^sample(-4:4, 1)
  b <- rnorm(sample(3:60, 1), runif(1, -3, 3), runif(1, 0.1, 4)) * 10^sample(-4:4, 1)
  alt <- sample(names(alt_py), 1); conf <- sample(c(0.9, 0.95, 0.99), 1)
  if (i %% 3 == 0) {
    add(var.test(a, b, alternative = alt, conf.level = conf), "var_test", "a", "b", a, b, 1, alt_py[[alt]], conf)
  } else if (i %% 3 == 1) {
    add(t.test(a, b, alternative = alt, conf.level = conf), "t_test", "a", "b", a, b, 0, alt_py[[alt]], conf)
  } else {
    add(t.test(a, mu = mean(a) * 0.9, alternative = alt, conf.level = conf), "t_test", "a", NULL, a, NULL,
        mean(a) * 0.9, alt_py[[alt]], conf)
  }
}
dir.create("tests/data", showWarnings = FALSE, recursive = TRUE)
writeLines(c("[", paste(blocks, collapse = ",\n"), "]"), "tests/data/r_blocks.json")
