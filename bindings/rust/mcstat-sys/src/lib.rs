//! Raw FFI bindings to libmcstat (`mcstat.h`), written by hand from the
//! header: the plain structs mirrored field by field (`#[repr(C)]`), the
//! enums as integer constants, the functions as declared.  The safe API is
//! the `mcstat` crate; the tests below check every mirrored size against the
//! library's own `mcstat_sizeof_*`.
#![allow(non_camel_case_types)]

use std::os::raw::{c_char, c_int, c_uint};

// ---- status codes -----------------------------------------------------------
pub const MCSTAT_OK: c_int = 0;
pub const MCSTAT_EINVAL: c_int = 1;
pub const MCSTAT_ETOOFEW: c_int = 2;
pub const MCSTAT_ENONFINITE: c_int = 3;
pub const MCSTAT_EDEGENERATE: c_int = 4;
pub const MCSTAT_ENOMEM: c_int = 5;
pub const MCSTAT_ENUMERIC: c_int = 6;
pub const MCSTAT_EBUFSIZE: c_int = 7;
pub const MCSTAT_ECORRUPT: c_int = 8;
pub const MCSTAT_ETOOBIG: c_int = 9;
pub const MCSTAT_ECALLBACK: c_int = 10;

// ---- alternatives, tests, methods, weights ------------------------------------
pub const MCSTAT_TWO_SIDED: c_int = 0;
pub const MCSTAT_LESS: c_int = 1;
pub const MCSTAT_GREATER: c_int = 2;

// ---- values of mcstat_result.decision ---------------------------------------
pub const MCSTAT_DECISION_LESS: i32 = -1;
pub const MCSTAT_DECISION_EQUAL: i32 = 0;
pub const MCSTAT_DECISION_GREATER: i32 = 1;

pub const MCSTAT_TEST_T_1: i32 = 1;
pub const MCSTAT_TEST_T_2: i32 = 2;
pub const MCSTAT_TEST_VAR_1: i32 = 3;
pub const MCSTAT_TEST_VAR_2: i32 = 4;
pub const MCSTAT_TEST_KS_2: i32 = 5;

pub const MCSTAT_METHOD_ANALYTIC: i32 = 0;
pub const MCSTAT_METHOD_AUTO: i32 = 1;
pub const MCSTAT_METHOD_EXACT: i32 = 2;
pub const MCSTAT_METHOD_SIMULATE: i32 = 3;
pub const MCSTAT_METHOD_ASYMPTOTIC: i32 = 4;

pub const MCSTAT_KS_WEIGHT_NONE: i32 = 0;
pub const MCSTAT_KS_WEIGHT_CANNER: i32 = 1;
pub const MCSTAT_KS_DEFAULT_N_SIM: i64 = 10000;

pub const MCSTAT_MOMENTS_VERSION: u32 = 1;
pub const MCSTAT_MOMENTS_BYTES: usize = 96;
pub const MCSTAT_ROWS_NO_INTERVALS: c_uint = 1;
pub const MCSTAT_ROWS_OMIT_NAN: c_uint = 2;

/// `mcstat_moments`: 128 bytes, caller-owned.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_moments {
    pub n: u64,
    pub scale: i32,
    pub version: u32,
    pub mean: f64,
    pub mean_lo: f64,
    pub m2: f64,
    pub m3: f64,
    pub m4: f64,
    pub min: f64,
    pub max: f64,
    pub reserved: [f64; 7],
}

/// `mcstat_result`: what every test fills.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_result {
    pub test: i32,
    pub method: i32,
    pub alternative: i32,
    pub reject: i32,
    pub decision: i32,
    /// The per-test integer outputs (C names them in a union over this
    /// storage): `[0]` ks_weight, `[1]` chisq_cells, `[2]` chisq_n_estimated.
    pub reserved_i: [i32; 3],
    pub n: [u64; 2],
    pub statistic: f64,
    pub df: [f64; 2],
    pub p_value: f64,
    pub p_value_se: f64,
    pub conf_int: [f64; 2],
    pub estimate: [f64; 2],
    pub null_value: f64,
    pub alpha: f64,
    pub critical: [f64; 2],
    pub std_error: f64,
    /// The per-test outputs (C names them in a union over this storage):
    /// K-S `[0]` ks_critical_se, `[1]` ks_n_sim; TOST `[0..6]` tost_t_lower,
    /// tost_t_upper, tost_p_lower, tost_p_upper, tost_lower, tost_upper;
    /// binomial `[2]` binom_log_p_value; chi-squared `[2..5]`
    /// chisq_cells_given, chisq_min_expected, chisq_pool_below.
    pub reserved: [f64; 7],
}

/// Opaque K-S simulation cache.
#[repr(C)]
pub struct mcstat_ks_cache {
    _private: [u8; 0],
}

/// `mcstat_ks_options`; start from `mcstat_ks_options_init_size(&mut o,
/// size_of::<mcstat_ks_options>())`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_ks_options {
    pub size: u32,
    pub weight: i32,
    pub method: i32,
    pub threads: i32,
    pub n_sim: i64,
    pub seed: u64,
    pub cache: *mut mcstat_ks_cache,
    pub critical: i32,
    pub reserved: i32,
}

extern "C" {
    pub fn mcstat_version_number() -> c_uint;
    pub fn mcstat_version() -> *const c_char;
    pub fn mcstat_strerror(status: c_int) -> *const c_char;
    pub fn mcstat_alternative_parse(name: *const c_char, alternative: *mut c_int) -> c_int;
    pub fn mcstat_alternative_name(alternative: c_int) -> *const c_char;
    pub fn mcstat_decision_name(decision: c_int) -> *const c_char;

    pub fn mcstat_moments_init(m: *mut mcstat_moments) -> c_int;
    pub fn mcstat_moments_add(m: *mut mcstat_moments, x: f64) -> c_int;
    pub fn mcstat_moments_add_array(m: *mut mcstat_moments, x: *const f64, n: usize) -> c_int;
    pub fn mcstat_moments_add_array_omit_nan(
        m: *mut mcstat_moments,
        x: *const f64,
        n: usize,
        n_omitted: *mut usize,
    ) -> c_int;
    pub fn mcstat_moments_merge(dst: *mut mcstat_moments, src: *const mcstat_moments) -> c_int;
    pub fn mcstat_moments_mean(m: *const mcstat_moments) -> f64;
    pub fn mcstat_moments_var(m: *const mcstat_moments) -> f64;
    pub fn mcstat_moments_sd(m: *const mcstat_moments) -> f64;
    pub fn mcstat_moments_skewness(m: *const mcstat_moments) -> f64;
    pub fn mcstat_moments_kurtosis(m: *const mcstat_moments) -> f64;
    pub fn mcstat_moments_to_bytes(m: *const mcstat_moments, buf: *mut u8, size: usize) -> c_int;
    pub fn mcstat_moments_from_bytes(buf: *const u8, size: usize, m: *mut mcstat_moments) -> c_int;

    pub fn mcstat_result_format(
        r: *const mcstat_result,
        x_name: *const c_char,
        y_name: *const c_char,
        buf: *mut c_char,
        size: usize,
        length: *mut usize,
    ) -> c_int;

    pub fn mcstat_t_test_1(x: *const f64, n: usize, mu0: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_t_test_1_moments(x: *const mcstat_moments, mu0: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_t_test_2(
        x: *const f64,
        nx: usize,
        y: *const f64,
        ny: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_t_test_2_moments(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_var_test_1(x: *const f64, n: usize, sigma2: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_var_test_1_moments(x: *const mcstat_moments, sigma2: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_var_test_2(
        x: *const f64,
        nx: usize,
        y: *const f64,
        ny: usize,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_var_test_2_moments(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;

    pub fn mcstat_ks_cache_new(max_bytes: usize, cache: *mut *mut mcstat_ks_cache) -> c_int;
    pub fn mcstat_ks_cache_free(cache: *mut mcstat_ks_cache);
    pub fn mcstat_ks_cache_stats(cache: *const mcstat_ks_cache, hits: *mut u64, misses: *mut u64, entries: *mut u64) -> c_int;
    /// Writes the defaults into the first `size` bytes (the caller's struct).
    pub fn mcstat_ks_options_init_size(opt: *mut mcstat_ks_options, size: usize) -> c_int;
    /// 0.1.0's initialiser: writes 0.1.0's size (`MCSTAT_KS_OPTIONS_SIZE_0_1`).
    pub fn mcstat_ks_options_init(opt: *mut mcstat_ks_options) -> c_int;
    pub fn mcstat_sizeof_ks_options() -> usize;
    pub fn mcstat_ks_test_2(
        x: *const f64,
        nx: usize,
        y: *const f64,
        ny: usize,
        alternative: c_int,
        alpha: f64,
        opt: *const mcstat_ks_options,
        out: *mut mcstat_result,
    ) -> c_int;

    pub fn mcstat_t_cdf(x: f64, df: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_t_logcdf(x: f64, df: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_t_quantile(p: f64, df: f64, upper: c_int, x: *mut f64) -> c_int;
    pub fn mcstat_chisq_cdf(x: f64, df: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_chisq_logcdf(x: f64, df: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_chisq_quantile(p: f64, df: f64, upper: c_int, x: *mut f64) -> c_int;
    pub fn mcstat_f_cdf(x: f64, df1: f64, df2: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_f_logcdf(x: f64, df1: f64, df2: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_f_quantile(p: f64, df1: f64, df2: f64, upper: c_int, x: *mut f64) -> c_int;

    pub fn mcstat_sizeof_moments() -> usize;
    pub fn mcstat_sizeof_result() -> usize;
    pub fn mcstat_sizeof_moments_bytes() -> usize;
    /// The 0.1 name of `mcstat_sizeof_moments_bytes`, kept so that code
    /// using it still builds.
    #[deprecated(note = "use mcstat_sizeof_moments_bytes")]
    pub fn mcstat_moments_bytes() -> usize;

    pub fn mcstat_gsl_handler_off();
    pub fn mcstat_gsl_handler_off_if_default() -> c_int;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_match_the_library() {
        unsafe {
            assert_eq!(std::mem::size_of::<mcstat_moments>(), mcstat_sizeof_moments());
            assert_eq!(std::mem::size_of::<mcstat_moments>(), 128);
            assert_eq!(std::mem::size_of::<mcstat_result>(), mcstat_sizeof_result());
            assert_eq!(std::mem::size_of::<mcstat_ks_options>(), mcstat_sizeof_ks_options());
            assert_eq!(mcstat_sizeof_moments_bytes(), MCSTAT_MOMENTS_BYTES);
        }
    }

    /// MAJOR.MINOR.PATCH of the repository's mcstat.h, the one source of
    /// the version: Cargo.toml's must follow it.
    fn header_version() -> (u32, u32, u32) {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../libmcstat/include/mcstat.h");
        let text = std::fs::read_to_string(path).expect("the repository's mcstat.h");
        let get = |name: &str| -> u32 {
            let key = format!("#define MCSTAT_VERSION_{name} ");
            let line = text.lines().find(|l| l.starts_with(&key)).expect("a version macro");
            line[key.len()..].trim().parse().expect("a number")
        };
        (get("MAJOR"), get("MINOR"), get("PATCH"))
    }

    #[test]
    fn version_is_the_header_version() {
        let (major, minor, patch) = header_version();
        let want = format!("{major}.{minor}.{patch}");
        assert_eq!(env!("CARGO_PKG_VERSION"), want, "Cargo.toml's version differs from mcstat.h's");
        let v = unsafe { std::ffi::CStr::from_ptr(mcstat_version()) };
        assert_eq!(v.to_str().unwrap(), want);
        assert_eq!(unsafe { mcstat_version_number() }, major * 10000 + minor * 100 + patch);
    }

    #[test]
    fn ks_options_initialiser_writes_the_callers_size() {
        // a buffer larger than the struct: the sized initialiser writes the
        // struct, nothing beyond; the default starts no thread
        let n = std::mem::size_of::<mcstat_ks_options>();
        let mut buf = [0xABu8; 128];
        let st = unsafe { mcstat_ks_options_init_size(buf.as_mut_ptr() as *mut mcstat_ks_options, n) };
        assert_eq!(st, MCSTAT_OK);
        assert!(buf[n..].iter().all(|&b| b == 0xAB));
        let o: mcstat_ks_options = unsafe { std::ptr::read_unaligned(buf.as_ptr() as *const mcstat_ks_options) };
        assert_eq!((o.size as usize, o.threads), (n, 1));
        let st = unsafe { mcstat_ks_options_init_size(buf.as_mut_ptr() as *mut mcstat_ks_options, n + 8) };
        assert_eq!(st, MCSTAT_EINVAL);
    }
}
