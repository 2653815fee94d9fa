//! The two-sample Kolmogorov-Smirnov test and its simulation cache.
use crate::{check, run, sys, Alternative, Error, KsWeight, Method, Result, TestResult};
use std::ptr;

/// Simulated null distributions shared by a battery of K-S tests (thread-safe:
/// libmcstat locks it).
pub struct KsCache {
    raw: *mut sys::mcstat_ks_cache,
}

// The C cache has its own lock and is documented as shareable by threads.
unsafe impl Send for KsCache {}
unsafe impl Sync for KsCache {}

impl KsCache {
    /// A cache holding at most `max_bytes` of distributions (least recently used dropped).
    pub fn new(max_bytes: usize) -> Result<KsCache> {
        let mut raw = ptr::null_mut();
        check(unsafe { sys::mcstat_ks_cache_new(max_bytes, &mut raw) })?;
        Ok(KsCache { raw })
    }
    /// (hits, misses, entries held).
    pub fn stats(&self) -> (u64, u64, u64) {
        let (mut h, mut m, mut e) = (0u64, 0u64, 0u64);
        unsafe { sys::mcstat_ks_cache_stats(self.raw, &mut h, &mut m, &mut e) };
        (h, m, e)
    }
}

impl Drop for KsCache {
    fn drop(&mut self) {
        unsafe { sys::mcstat_ks_cache_free(self.raw) }
    }
}

/// K-S options; `Default` is libmcstat's (Canner's weight, method auto, 1
/// thread (none started), 10000 simulations, seed 0, critical value computed).
#[derive(Clone, Copy)]
pub struct KsOptions<'a> {
    pub weight: KsWeight,
    pub method: Method,
    /// Threads for simulation and sorting, 1..=64.
    pub threads: i32,
    /// Replicates when simulating, >= 1.
    pub n_sim: i64,
    pub seed: u64,
    /// Compute the critical value (exact: 10-40 p-value computations).
    pub critical: bool,
    pub cache: Option<&'a KsCache>,
}

fn c_defaults() -> sys::mcstat_ks_options {
    let mut o = std::mem::MaybeUninit::<sys::mcstat_ks_options>::zeroed();
    unsafe {
        let st = sys::mcstat_ks_options_init_size(o.as_mut_ptr(), std::mem::size_of::<sys::mcstat_ks_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for KsOptions<'_> {
    fn default() -> Self {
        let o = c_defaults();
        KsOptions {
            weight: if o.weight == sys::MCSTAT_KS_WEIGHT_NONE { KsWeight::None } else { KsWeight::Canner },
            method: Method::Auto,
            threads: o.threads,
            n_sim: o.n_sim,
            seed: o.seed,
            critical: o.critical != 0,
            cache: None,
        }
    }
}

/// Two-sample Kolmogorov-Smirnov test of x against y (`Less`: x tends to be
/// smaller, its CDF lies above: R's and SciPy's "greater").
pub fn ks_test_2(x: &[f64], y: &[f64], alternative: Alternative, alpha: f64, opt: &KsOptions) -> Result<TestResult> {
    let mut o = c_defaults();
    o.weight = match opt.weight {
        KsWeight::None => sys::MCSTAT_KS_WEIGHT_NONE,
        KsWeight::Canner => sys::MCSTAT_KS_WEIGHT_CANNER,
    };
    if opt.method == Method::Analytic {
        return Err(Error::invalid("K-S method: Auto, Exact, Simulate or Asymptotic"));
    }
    o.method = opt.method.raw();
    o.threads = opt.threads;
    o.n_sim = opt.n_sim;
    o.seed = opt.seed;
    o.critical = opt.critical as i32;
    o.cache = opt.cache.map_or(ptr::null_mut(), |c| c.raw);
    run(|out| unsafe { sys::mcstat_ks_test_2(x.as_ptr(), x.len(), y.as_ptr(), y.len(), alternative.raw(), alpha, &o, out) })
}
