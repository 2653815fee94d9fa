//! Goodness of fit (experimental in libmcstat): Pearson's chi-squared test
//! of cell counts, the exact binomial test, and the battery meta-test.
use crate::{run, sys, Alternative, Error, Result, TestResult};
use std::mem::{size_of, MaybeUninit};

/// What the `expected` slice of [`gof_chisq_test`] holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Expected {
    /// Cell probabilities, summing to 1.
    #[default]
    Probabilities,
    /// Expected counts, summing to the observed total.
    Counts,
}

/// Options of [`gof_chisq_test`]; `Default` is libmcstat's (probabilities,
/// pooling below 5 expected, no rescaling, nothing estimated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GofOptions {
    pub expected: Expected,
    /// Pool consecutive cells until the expected count reaches `min_expected`.
    pub pool: bool,
    /// Scale `expected` to the right total instead of requiring it.
    pub rescale: bool,
    pub min_expected: f64,
    /// Parameters of the expected probabilities estimated from the counts.
    pub n_estimated: u32,
}

fn c_defaults() -> sys::mcstat_gof_options {
    let mut o = MaybeUninit::<sys::mcstat_gof_options>::zeroed();
    unsafe {
        let st = sys::mcstat_gof_options_init_size(o.as_mut_ptr(), size_of::<sys::mcstat_gof_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for GofOptions {
    fn default() -> Self {
        let o = c_defaults();
        GofOptions {
            expected: if o.expected == sys::MCSTAT_GOF_COUNTS { Expected::Counts } else { Expected::Probabilities },
            pool: o.pool != 0,
            rescale: o.rescale != 0,
            min_expected: default_min_expected(),
            n_estimated: o.n_estimated as u32,
        }
    }
}

/// Cochran's rule: 5 expected counts per (pooled) cell.
pub fn default_min_expected() -> f64 {
    unsafe { sys::mcstat_gof_default_min_expected() }
}

/// Pearson's chi-squared test of `observed` counts against `expected`
/// (same length).  [`crate::Details::ChisqGof`] holds the pooling.
pub fn gof_chisq_test(observed: &[f64], expected: &[f64], opt: &GofOptions, alpha: f64) -> Result<TestResult> {
    if observed.len() != expected.len() {
        return Err(Error::invalid(format!(
            "observed has {} cells and expected {}",
            observed.len(),
            expected.len()
        )));
    }
    if opt.n_estimated > i32::MAX as u32 {
        return Err(Error::invalid("n_estimated is too large"));
    }
    let mut o = c_defaults();
    o.expected = match opt.expected {
        Expected::Probabilities => sys::MCSTAT_GOF_PROBABILITIES,
        Expected::Counts => sys::MCSTAT_GOF_COUNTS,
    };
    o.pool = opt.pool as i32;
    o.rescale = opt.rescale as i32;
    o.min_expected = opt.min_expected;
    o.n_estimated = opt.n_estimated as i32;
    run(|out| unsafe { sys::mcstat_gof_chisq_test(observed.as_ptr(), expected.as_ptr(), observed.len(), &o, alpha, out) })
}

/// R's binom.test: `x` successes in `n` trials against P(success) = p.
/// [`crate::Details::Binom`] holds log(p-value), finite where it underflows.
pub fn binom_test(x: u64, n: u64, p: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_binom_test(x, n, p, alternative.raw(), alpha, out) })
}

/// The battery meta-test: are `rejections` among `k` tests at level `level`
/// consistent with that level?  (`Greater`: too many rejections.)
pub fn battery_test(rejections: u64, k: u64, level: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_battery_test(rejections, k, level, alternative.raw(), alpha, out) })
}

/// The battery meta-test from the battery's p-values (a test rejects when
/// its p-value is <= level).
pub fn battery_test_p_values(p_values: &[f64], level: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_battery_test_pvalues(p_values.as_ptr(), p_values.len(), level, alternative.raw(), alpha, out) })
}
