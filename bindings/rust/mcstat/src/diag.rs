//! Estimator diagnostics (experimental in libmcstat): shape, tails, and
//! the batch size that keeps a t test's level.
use crate::{check, sys, Result};
use std::mem::{size_of, MaybeUninit};

/// Options of [`diagnose`]; `Default` is libmcstat's (alpha 0.05, tolerance
/// 0.2, tail threshold 2.2, the rest chosen from n).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiagOptions {
    /// The batch size in use (`None`: t_size is for k = 1).
    pub batch_size: Option<u64>,
    /// Batch means the t test sees (`None`: n / k, or 30 without a batch size).
    pub batch_means: Option<u64>,
    /// Order statistics per tail in Hill's estimate (`None`: max(10, min(4 sqrt(n), n/25))).
    pub tail_k: Option<u64>,
    /// The t test's level.
    pub alpha: f64,
    /// Allowed relative error of each tail's rejection rate, in (0, 1).
    pub tolerance: f64,
    /// heavy_tail when a tail index is below this.
    pub tail_threshold: f64,
}

fn c_defaults() -> sys::mcstat_diag_options {
    let mut o = MaybeUninit::<sys::mcstat_diag_options>::zeroed();
    unsafe {
        let st = sys::mcstat_diag_options_init_size(o.as_mut_ptr(), size_of::<sys::mcstat_diag_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for DiagOptions {
    fn default() -> Self {
        let o = c_defaults();
        DiagOptions {
            batch_size: None,
            batch_means: None,
            tail_k: None,
            alpha: o.alpha,
            tolerance: o.tolerance,
            tail_threshold: o.tail_threshold,
        }
    }
}

/// What [`diagnose`] found.
#[derive(Clone, Copy, Debug)]
pub struct Diagnostics {
    raw: sys::mcstat_diagnostics,
}

impl Diagnostics {
    pub fn n(&self) -> u64 {
        self.raw.n
    }
    /// Order statistics per tail asked for.
    pub fn tail_k(&self) -> u64 {
        self.raw.tail_k
    }
    /// Batch size and number of batch means `t_size` is for.
    pub fn batch_size(&self) -> u64 {
        self.raw.k
    }
    pub fn batch_means(&self) -> u64 {
        self.raw.m
    }
    /// The batch size rule's k for `batch_means()` batch means.
    pub fn recommended_batch_size(&self) -> u64 {
        self.raw.recommended_k
    }
    /// A tail index is below the threshold: the variance may be infinite.
    pub fn heavy_tail(&self) -> bool {
        self.raw.heavy_tail != 0
    }
    pub fn mean(&self) -> f64 {
        self.raw.mean
    }
    pub fn sd(&self) -> f64 {
        self.raw.sd
    }
    /// (g1, its standard error under normality).
    pub fn skewness(&self) -> (f64, f64) {
        (self.raw.skewness, self.raw.skewness_se)
    }
    /// (excess g2, its standard error under normality).
    pub fn kurtosis(&self) -> (f64, f64) {
        (self.raw.kurtosis, self.raw.kurtosis_se)
    }
    /// Hill's index of the lower and upper tail (+Inf: no Pareto tail).
    pub fn tail_index(&self) -> [f64; 2] {
        self.raw.tail_index
    }
    /// index / sqrt(k) of each tail; `None` where no order statistic was used.
    pub fn tail_index_se(&self) -> [Option<f64>; 2] {
        let s = self.raw.tail_index_se;
        let f = |v: f64| if v.is_nan() { None } else { Some(v) };
        [f(s[0]), f(s[1])]
    }
    /// max_i (x_i - mean)^2 / sum_i (x_i - mean)^2.
    pub fn max_share(&self) -> f64 {
        self.raw.max_share
    }
    /// Predicted rejection rates of the lower and upper tail of the
    /// two-sided t test at alpha (alpha/2 each when the batch means are normal).
    pub fn t_size(&self) -> [f64; 2] {
        self.raw.t_size
    }
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    pub fn tolerance(&self) -> f64 {
        self.raw.tolerance
    }
    pub fn raw(&self) -> &sys::mcstat_diagnostics {
        &self.raw
    }
}

/// All diagnostics of the primary estimates `x` (allocates 16 n bytes).
pub fn diagnose(x: &[f64], opt: &DiagOptions) -> Result<Diagnostics> {
    let mut o = c_defaults();
    o.k = opt.batch_size.unwrap_or(0);
    o.m = opt.batch_means.unwrap_or(0);
    o.tail_k = opt.tail_k.unwrap_or(0);
    o.alpha = opt.alpha;
    o.tolerance = opt.tolerance;
    o.tail_threshold = opt.tail_threshold;
    let mut out = MaybeUninit::<sys::mcstat_diagnostics>::zeroed();
    check(unsafe { sys::mcstat_diag_compute(x.as_ptr(), x.len(), &o, out.as_mut_ptr()) })?;
    Ok(Diagnostics { raw: unsafe { out.assume_init() } })
}

/// Hill's tail index of the lower and upper tail from `tail_k` order
/// statistics (`None`: the default).
pub fn tail_index(x: &[f64], tail_k: Option<usize>) -> Result<[f64; 2]> {
    let mut idx = [f64::NAN; 2];
    check(unsafe { sys::mcstat_diag_tail_index(x.as_ptr(), x.len(), tail_k.unwrap_or(0), idx.as_mut_ptr()) })?;
    Ok(idx)
}

/// The Edgeworth-predicted rejection rates (lower tail, upper tail) of the
/// two-sided t test at alpha on `m` batch means of `k` values of the given
/// skewness and excess kurtosis.
pub fn t_size(skewness: f64, kurtosis: f64, k: u64, m: u64, alpha: f64) -> Result<[f64; 2]> {
    let mut s = [f64::NAN; 2];
    check(unsafe { sys::mcstat_diag_t_size(skewness, kurtosis, k, m, alpha, s.as_mut_ptr()) })?;
    Ok(s)
}

/// The smallest batch size whose predicted tail rates are within
/// tolerance * alpha/2 of alpha/2 for `m` batch means.
pub fn batch_size(skewness: f64, kurtosis: f64, m: u64, alpha: f64, tolerance: f64) -> Result<u64> {
    let mut k = 0u64;
    check(unsafe { sys::mcstat_diag_batch_size(skewness, kurtosis, m, alpha, tolerance, &mut k) })?;
    Ok(k)
}
