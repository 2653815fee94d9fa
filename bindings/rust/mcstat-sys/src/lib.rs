//! Raw FFI bindings to libmcstat (`mcstat.h`), written by hand from the
//! headers (mcstat/*.h), family by family: the plain structs mirrored field by field
//! (`#[repr(C)]`, the header's anonymous unions as named Rust unions), the
//! enums and macros as integer constants, every exported function as
//! declared (those of mcstat/deprecated.h too, marked
//! `#[deprecated]`).  The safe API is the `mcstat` crate.
//!
//! Layout: the sizes are asserted at compile time against the header's own
//! numbers (`MCSTAT_*_OPTIONS_SIZE_*`, the 128-byte accumulator, the
//! 4096-byte stream), and the tests compare every size with the library's
//! `mcstat_sizeof_*` and every field offset with the C compiler's.
//!
//! `mcstat_stream_add` is a `static inline` function in the header, not an
//! exported symbol: [`mcstat_stream_add`] is its body in Rust.
#![allow(non_camel_case_types)]

use std::os::raw::{c_char, c_int, c_uint, c_void};

// ============================================================================
// Conventions: statuses, alternatives.
// ============================================================================

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
/// A sequential test's kurtosis gate was still closed at its end (mcstat/sequential.h).
pub const MCSTAT_EHEAVYTAIL: c_int = 11;

pub const MCSTAT_TWO_SIDED: c_int = 0;
pub const MCSTAT_LESS: c_int = 1;
pub const MCSTAT_GREATER: c_int = 2;

// ============================================================================
// Accumulators.
// ============================================================================

pub const MCSTAT_MOMENTS_VERSION: u32 = 1;
/// Size of the serialized form written by `mcstat_moments_to_bytes`.
pub const MCSTAT_MOMENTS_BYTES: usize = 96;

/// `mcstat_moments`: 128 bytes, caller-owned.  Central sums are stored
/// scaled (see the header): read them through the accessors.
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

/// `enum mcstat_value_type`: the element type of an `mcstat_pixels_in`.
pub const MCSTAT_VALUE_FLOAT64: i32 = 0;
pub const MCSTAT_VALUE_FLOAT32: i32 = 1;

/// `mcstat_pixels_in`: where the values of each pixel are (value s of
/// pixel i at element `s * value_stride + i * pixel_stride` of `data`,
/// `channels` consecutive elements weighted by `weights`).  Start from
/// [`mcstat_pixels_in::init`] (the header's `MCSTAT_PIXELS_IN_INIT`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_pixels_in {
    pub size: u32,
    pub type_: i32,
    pub data: *const c_void,
    pub n: usize,
    pub value_stride: usize,
    pub pixel_stride: usize,
    pub channels: usize,
    pub weights: *const f64,
}

impl mcstat_pixels_in {
    /// `MCSTAT_PIXELS_IN_INIT`.
    pub fn init() -> Self {
        mcstat_pixels_in {
            size: std::mem::size_of::<Self>() as u32,
            type_: MCSTAT_VALUE_FLOAT64,
            data: std::ptr::null(),
            n: 0,
            value_stride: 0,
            pixel_stride: 0,
            channels: 1,
            weights: std::ptr::null(),
        }
    }
}

/// `mcstat_pixels_options`: flags (`MCSTAT_ROWS_*`) and threads (1..64).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_pixels_options {
    pub size: u32,
    pub flags: u32,
    pub threads: i32,
    pub reserved: i32,
    /// (0.3) `MCSTAT_PIXELS_RENDER`'s numerical floor; 0: from the inputs' type.
    pub resolution: f64,
}

impl mcstat_pixels_options {
    /// `MCSTAT_PIXELS_OPTIONS_INIT`.
    pub fn init() -> Self {
        mcstat_pixels_options { size: std::mem::size_of::<Self>() as u32, flags: 0, threads: 1, reserved: 0, resolution: 0.0 }
    }
}

/// `mcstat_pixels_out`: the caller's per-pixel output arrays of
/// `mcstat_pixels_test` and `mcstat_t_test_2_pixels` (indexed by pixel);
/// any may be null.  Start from [`mcstat_pixels_out::init`].
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_pixels_out {
    pub size: u32,
    pub reserved: u32,
    pub p_value: *mut f64,
    pub statistic: *mut f64,
    pub df: *mut f64,
    pub df2: *mut f64,
    pub estimate: *mut f64,
    pub estimate2: *mut f64,
    pub std_error: *mut f64,
    pub conf_lo: *mut f64,
    pub conf_hi: *mut f64,
    pub critical_lo: *mut f64,
    pub critical_hi: *mut f64,
    pub status: *mut i32,
    pub decision: *mut i8,
    pub n_x: *mut u64,
    pub n_y: *mut u64,
}

impl mcstat_pixels_out {
    /// `MCSTAT_PIXELS_OUT_INIT`: the size set, every array null.
    pub fn init() -> Self {
        let n = std::ptr::null_mut();
        mcstat_pixels_out {
            size: std::mem::size_of::<Self>() as u32,
            reserved: 0,
            p_value: n,
            statistic: n,
            df: n,
            df2: n,
            estimate: n,
            estimate2: n,
            std_error: n,
            conf_lo: n,
            conf_hi: n,
            critical_lo: n,
            critical_hi: n,
            status: std::ptr::null_mut(),
            decision: std::ptr::null_mut(),
            n_x: std::ptr::null_mut(),
            n_y: std::ptr::null_mut(),
        }
    }
}

/// sizeof of the per-pixel structs in each release that changed them.
pub const MCSTAT_PIXELS_IN_SIZE_0_2: usize = 56;
pub const MCSTAT_PIXELS_OPTIONS_SIZE_0_2: usize = 16;
pub const MCSTAT_PIXELS_OPTIONS_SIZE_0_3: usize = 24;
pub const MCSTAT_PIXELS_OUT_SIZE_0_2: usize = 128;

pub const MCSTAT_STREAM_VERSION: u32 = 1;
pub const MCSTAT_STREAM_BYTES: usize = 4096;
pub const MCSTAT_STREAM_CAPACITY: u32 = 492;

/// The named storage of `mcstat_stream`'s anonymous union.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_stream_overflow {
    /// Values left out because the count would pass 2^64 - 1.
    pub n_overflow: u64,
    pub reserved_1: u64,
}

/// `mcstat_stream`'s anonymous union: `reserved` is 0.1.0's name of the storage.
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_stream_union {
    pub reserved: [u64; 2],
    pub s: mcstat_stream_overflow,
}

/// `mcstat_stream`: a 4096-byte per-thread buffer in front of an accumulator.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct mcstat_stream {
    pub moments: mcstat_moments,
    pub count: u32,
    pub version: u32,
    pub n_nonfinite: u64,
    pub u: mcstat_stream_union,
    pub buf: [f64; MCSTAT_STREAM_CAPACITY as usize],
}

impl mcstat_stream {
    /// The union's `n_overflow` (every bit pattern is a valid `u64`).
    pub fn n_overflow(&self) -> u64 {
        unsafe { self.u.s.n_overflow }
    }
}

/// The header's `static inline mcstat_stream_add`, line for line: a store
/// and a counter, and a flush once every `MCSTAT_STREAM_CAPACITY` values
/// (whose status is dropped, as in C: an overflow is recorded in the stream
/// and every check on it returns `MCSTAT_ETOOBIG`).
///
/// # Safety
/// `s` must point to a stream initialised by `mcstat_stream_init` (whose
/// `count` is then always below the capacity).
#[inline]
pub unsafe fn mcstat_stream_add(s: *mut mcstat_stream, x: f64) {
    let s = &mut *s;
    s.buf[s.count as usize] = x;
    s.count += 1;
    if s.count == MCSTAT_STREAM_CAPACITY {
        let _ = mcstat_stream_flush(s);
    }
}

// ============================================================================
// The tests and their result.
// ============================================================================

pub const MCSTAT_TEST_T_1: i32 = 1;
pub const MCSTAT_TEST_T_2: i32 = 2;
pub const MCSTAT_TEST_VAR_1: i32 = 3;
pub const MCSTAT_TEST_VAR_2: i32 = 4;
pub const MCSTAT_TEST_KS_2: i32 = 5;
pub const MCSTAT_TEST_EQUIV_1: i32 = 6;
pub const MCSTAT_TEST_EQUIV_2: i32 = 7;
pub const MCSTAT_TEST_BINOM: i32 = 8;
pub const MCSTAT_TEST_CHISQ_GOF: i32 = 9;
pub const MCSTAT_TEST_T_2_POOLED: i32 = 10;
pub const MCSTAT_TEST_T_PAIRED: i32 = 11;
pub const MCSTAT_TEST_SEQ_MEAN_1: i32 = 13;
pub const MCSTAT_TEST_SEQ_MEAN_2: i32 = 14;
pub const MCSTAT_TEST_SEQ_VAR_1: i32 = 15;
pub const MCSTAT_TEST_SEQ_VAR_2: i32 = 16;
pub const MCSTAT_TEST_EFFICIENCY: i32 = 12;

pub const MCSTAT_METHOD_ANALYTIC: i32 = 0;
pub const MCSTAT_METHOD_AUTO: i32 = 1;
pub const MCSTAT_METHOD_EXACT: i32 = 2;
pub const MCSTAT_METHOD_SIMULATE: i32 = 3;
pub const MCSTAT_METHOD_ASYMPTOTIC: i32 = 4;

pub const MCSTAT_DECISION_LESS: i32 = -1;
pub const MCSTAT_DECISION_EQUAL: i32 = 0;
pub const MCSTAT_DECISION_GREATER: i32 = 1;

/// The named storage of `mcstat_result`'s integer union.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_ints_named {
    /// KS_2: enum mcstat_ks_weight.
    pub ks_weight: i32,
    /// CHISQ_GOF: cells after pooling.
    pub chisq_cells: i32,
    /// CHISQ_GOF: parameters estimated.
    pub chisq_n_estimated: i32,
}

/// The sequential tests' integer outputs (SEQ_*, mcstat/sequential.h).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_ints_seq {
    /// `MCSTAT_SEQ_CONTINUE` or `MCSTAT_SEQ_DECIDED`.
    pub seq_state: i32,
    /// Why no decision is allowed yet (`MCSTAT_SEQ_HOLD_*` bits).
    pub seq_hold: i32,
    pub seq_unused_: i32,
}

/// EFFICIENCY's integer outputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_ints_eff {
    /// Timed batches of x and of y (saturating at i32::MAX).
    pub eff_batches_x: i32,
    pub eff_batches_y: i32,
}

/// `mcstat_result`'s first anonymous union (`reserved_i` is 0.1.0's name).
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_result_ints {
    pub reserved_i: [i32; 3],
    pub s: mcstat_result_ints_named,
    pub seq: mcstat_result_ints_seq,
    pub eff: mcstat_result_ints_eff,
}

/// KS_2's per-test outputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_ks {
    pub ks_critical_se: f64,
    pub ks_n_sim: f64,
}

/// EQUIV_1 and EQUIV_2's per-test outputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_tost {
    pub tost_t_lower: f64,
    pub tost_t_upper: f64,
    pub tost_p_lower: f64,
    pub tost_p_upper: f64,
    pub tost_lower: f64,
    pub tost_upper: f64,
}

/// BINOM's per-test output.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_binom {
    pub binom_unused_: [f64; 2],
    pub binom_log_p_value: f64,
}

/// CHISQ_GOF's per-test outputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_chisq {
    pub chisq_unused_: [f64; 2],
    pub chisq_cells_given: f64,
    pub chisq_min_expected: f64,
    pub chisq_pool_below: f64,
}

/// The sequential tests' per-test outputs (SEQ_*, mcstat/sequential.h).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_seq {
    /// Pushes so far.
    pub seq_looks: f64,
    /// n (of x) at the look that decided; 0 while continuing.
    pub seq_n_decided: f64,
    /// Log of the e-value at the last look (-Inf while held).
    pub seq_log_e: f64,
    /// Its running maximum: p_value = min(1, exp(-seq_log_e_max)).
    pub seq_log_e_max: f64,
    /// Equivalence margin (0: none).
    pub seq_eps: f64,
    /// The n where the confidence sequence is tightest.
    pub seq_t_opt: f64,
    /// The n the kurtosis gate asks for (0 when open).
    pub seq_n_gate: f64,
}

/// EFFICIENCY's per-test outputs.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_result_eff {
    /// s_y^2 / s_x^2 and mean time y / mean time x.
    pub eff_var_ratio: f64,
    pub eff_time_ratio: f64,
    /// Delta-method standard errors of log s_x^2, log s_y^2 and the log mean times.
    pub eff_se_log_var_x: f64,
    pub eff_se_log_var_y: f64,
    pub eff_se_log_time_x: f64,
    pub eff_se_log_time_y: f64,
}

/// `mcstat_result`'s second anonymous union (`reserved` is 0.1.0's name).
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_result_per_test {
    pub reserved: [f64; 7],
    pub ks: mcstat_result_ks,
    pub tost: mcstat_result_tost,
    pub binom: mcstat_result_binom,
    pub chisq: mcstat_result_chisq,
    pub seq: mcstat_result_seq,
    pub eff: mcstat_result_eff,
}

/// `mcstat_result`: what every test fills.  The header's anonymous unions
/// are the fields `ints` and `per_test`; read only the member of `test`
/// (every member is plain data, so the accessors below are safe).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct mcstat_result {
    pub test: i32,
    pub method: i32,
    pub alternative: i32,
    pub reject: i32,
    pub decision: i32,
    pub ints: mcstat_result_ints,
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
    pub per_test: mcstat_result_per_test,
}

impl mcstat_result {
    pub fn ints(&self) -> mcstat_result_ints_named {
        unsafe { self.ints.s }
    }
    pub fn reserved(&self) -> [f64; 7] {
        unsafe { self.per_test.reserved }
    }
    pub fn ks(&self) -> mcstat_result_ks {
        unsafe { self.per_test.ks }
    }
    pub fn tost(&self) -> mcstat_result_tost {
        unsafe { self.per_test.tost }
    }
    pub fn binom(&self) -> mcstat_result_binom {
        unsafe { self.per_test.binom }
    }
    pub fn chisq(&self) -> mcstat_result_chisq {
        unsafe { self.per_test.chisq }
    }
    pub fn ints_seq(&self) -> mcstat_result_ints_seq {
        unsafe { self.ints.seq }
    }
    pub fn seq(&self) -> mcstat_result_seq {
        unsafe { self.per_test.seq }
    }
    pub fn eff(&self) -> mcstat_result_eff {
        unsafe { self.per_test.eff }
    }
    pub fn eff_ints(&self) -> mcstat_result_ints_eff {
        unsafe { self.ints.eff }
    }
}

impl std::fmt::Debug for mcstat_result {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("mcstat_result")
            .field("test", &self.test)
            .field("method", &self.method)
            .field("alternative", &self.alternative)
            .field("reject", &self.reject)
            .field("decision", &self.decision)
            .field("reserved_i", &unsafe { self.ints.reserved_i })
            .field("n", &self.n)
            .field("statistic", &self.statistic)
            .field("df", &self.df)
            .field("p_value", &self.p_value)
            .field("p_value_se", &self.p_value_se)
            .field("conf_int", &self.conf_int)
            .field("estimate", &self.estimate)
            .field("null_value", &self.null_value)
            .field("alpha", &self.alpha)
            .field("critical", &self.critical)
            .field("std_error", &self.std_error)
            .field("reserved", &self.reserved())
            .finish()
    }
}

pub const MCSTAT_KS_WEIGHT_NONE: i32 = 0;
pub const MCSTAT_KS_WEIGHT_CANNER: i32 = 1;
pub const MCSTAT_KS_EXACT_MAX_WORK: f64 = 2e11;
pub const MCSTAT_KS_AUTO_EXACT_WORK: f64 = 1.6e7;
pub const MCSTAT_KS_DEFAULT_N_SIM: i64 = 10000;

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

/// sizeof(mcstat_ks_options) in each release that changed it.
pub const MCSTAT_KS_OPTIONS_SIZE_0_1: usize = 48;

// ============================================================================
// Per-pixel rows.
// ============================================================================

pub const MCSTAT_ROWS_NO_INTERVALS: c_uint = 1;
pub const MCSTAT_ROWS_OMIT_NAN: c_uint = 2;
/// Welch's per-pixel test made valid on renders (mcstat.h): numerical floor, rule-of-three
/// floor for a constant or one-nonzero side, Hsu's df, deterministic differences.
pub const MCSTAT_PIXELS_RENDER: c_uint = 4;

// ============================================================================
// Multiple testing.
// ============================================================================

pub const MCSTAT_P_ADJUST_NONE: c_int = 0;
pub const MCSTAT_P_ADJUST_BONFERRONI: c_int = 1;
pub const MCSTAT_P_ADJUST_HOLM: c_int = 2;
pub const MCSTAT_P_ADJUST_HOCHBERG: c_int = 3;
pub const MCSTAT_P_ADJUST_HOMMEL: c_int = 4;
pub const MCSTAT_P_ADJUST_BH: c_int = 5;
pub const MCSTAT_P_ADJUST_BY: c_int = 6;
pub const MCSTAT_P_ADJUST_E_BH: c_int = 7;

/// `mcstat_escalation`: a two-stage design, written by
/// `mcstat_escalation_design` (plain data, no pointers).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct mcstat_escalation {
    pub alpha: f64,
    pub alpha1: f64,
    pub alpha0: f64,
    pub c: f64,
}

/// `enum mcstat_escalation_decision`, written by `mcstat_escalation_decide`.
pub const MCSTAT_ESCALATION_PASS: c_int = 0;
pub const MCSTAT_ESCALATION_REJECT: c_int = 1;
pub const MCSTAT_ESCALATION_CONTINUE: c_int = 2;

// ============================================================================
// Power and sample size (experimental).
// ============================================================================

pub const MCSTAT_POWER_T_1: i32 = 1;
pub const MCSTAT_POWER_T_2: i32 = 2;
pub const MCSTAT_POWER_WELCH: i32 = 3;
pub const MCSTAT_POWER_VAR_1: i32 = 4;
pub const MCSTAT_POWER_VAR_2: i32 = 5;

pub const MCSTAT_POWER_SOLVE_POWER: c_int = 0;
pub const MCSTAT_POWER_SOLVE_N: c_int = 1;
pub const MCSTAT_POWER_SOLVE_EFFECT: c_int = 2;
pub const MCSTAT_POWER_SOLVE_ALPHA: c_int = 3;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_power_options {
    pub size: u32,
    pub test: i32,
    pub alternative: i32,
    pub strict: i32,
    pub n: f64,
    pub n_ratio: f64,
    pub sd_ratio: f64,
    pub effect: f64,
    pub alpha: f64,
    pub power: f64,
    pub reserved: [f64; 4],
}

pub const MCSTAT_POWER_OPTIONS_SIZE_0_1: usize = 96;

// ============================================================================
// Estimator diagnostics (experimental).
// ============================================================================

pub const MCSTAT_DIAG_DEFAULT_M: u64 = 30;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_diag_options {
    pub size: u32,
    pub reserved_i: i32,
    pub k: u64,
    pub m: u64,
    pub tail_k: u64,
    pub alpha: f64,
    pub tolerance: f64,
    pub tail_threshold: f64,
    pub reserved: [f64; 4],
}

pub const MCSTAT_DIAG_OPTIONS_SIZE_0_1: usize = 88;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_diagnostics {
    pub n: u64,
    pub tail_k: u64,
    pub k: u64,
    pub m: u64,
    pub recommended_k: u64,
    pub heavy_tail: i32,
    pub reserved_i: i32,
    pub mean: f64,
    pub sd: f64,
    pub skewness: f64,
    pub skewness_se: f64,
    pub kurtosis: f64,
    pub kurtosis_se: f64,
    pub tail_index: [f64; 2],
    pub tail_index_se: [f64; 2],
    pub max_share: f64,
    pub t_size: [f64; 2],
    pub alpha: f64,
    pub tolerance: f64,
    pub reserved: [f64; 4],
}

// ============================================================================
// Goodness of fit (experimental).
// ============================================================================

pub const MCSTAT_GOF_PROBABILITIES: i32 = 0;
pub const MCSTAT_GOF_COUNTS: i32 = 1;
pub const MCSTAT_GOF_DEFAULT_MIN_EXPECTED: f64 = 5.0;

/// `mcstat_gof_options` (its C tag too since 0.3; 0.1.0 named it `mcstat_chisq_options`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_gof_options {
    pub size: u32,
    pub expected: i32,
    pub pool: i32,
    pub rescale: i32,
    pub min_expected: f64,
    pub n_estimated: i32,
    pub reserved: i32,
}

pub const MCSTAT_GOF_OPTIONS_SIZE_0_1: usize = 32;

// ============================================================================
// Renderer checks (mcstat/check.h).
// ============================================================================

pub const MCSTAT_CHECK_DOMAIN_SPHERE: i32 = 0;
pub const MCSTAT_CHECK_DOMAIN_HEMISPHERE: i32 = 1;
pub const MCSTAT_CHECK_DOMAIN_SQUARE: i32 = 2;
pub const MCSTAT_CHECK_DOMAIN_DISK: i32 = 3;
pub const MCSTAT_CHECK_DOMAIN_INTERVAL: i32 = 4;

pub const MCSTAT_CHECK_WEIGHT_OVER_PDF: i32 = 0;
pub const MCSTAT_CHECK_WEIGHT_VALUE: i32 = 1;

// the names before 0.3
#[deprecated(note = "use MCSTAT_CHECK_DOMAIN_SPHERE")]
pub const MCSTAT_DOMAIN_SPHERE: i32 = MCSTAT_CHECK_DOMAIN_SPHERE;
#[deprecated(note = "use MCSTAT_CHECK_DOMAIN_HEMISPHERE")]
pub const MCSTAT_DOMAIN_HEMISPHERE: i32 = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
#[deprecated(note = "use MCSTAT_CHECK_DOMAIN_SQUARE")]
pub const MCSTAT_DOMAIN_SQUARE: i32 = MCSTAT_CHECK_DOMAIN_SQUARE;
#[deprecated(note = "use MCSTAT_CHECK_DOMAIN_DISK")]
pub const MCSTAT_DOMAIN_DISK: i32 = MCSTAT_CHECK_DOMAIN_DISK;
#[deprecated(note = "use MCSTAT_CHECK_DOMAIN_INTERVAL")]
pub const MCSTAT_DOMAIN_INTERVAL: i32 = MCSTAT_CHECK_DOMAIN_INTERVAL;
#[deprecated(note = "use MCSTAT_CHECK_WEIGHT_OVER_PDF")]
pub const MCSTAT_WEIGHT_OVER_PDF: i32 = MCSTAT_CHECK_WEIGHT_OVER_PDF;
#[deprecated(note = "use MCSTAT_CHECK_WEIGHT_VALUE")]
pub const MCSTAT_WEIGHT_VALUE: i32 = MCSTAT_CHECK_WEIGHT_VALUE;

pub const MCSTAT_CHECK_MAX_UNIFORMS: i32 = 8;

/// `sample(user, wi, u, n, x, weight, pdf)`: 0 on success.
pub type mcstat_check_sample_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        wi: *const f64,
        u: *const f64,
        n: usize,
        x: *mut f64,
        weight: *mut f64,
        pdf: *mut f64,
    ) -> c_int,
>;
/// `pdf(user, wi, x, n, out)` and `eval(...)`: 0 on success.
pub type mcstat_check_density_fn =
    Option<unsafe extern "C" fn(user: *mut c_void, wi: *const f64, x: *const f64, n: usize, out: *mut f64) -> c_int>;

/// Discrete lobes per check at most (`lobes()` gives up to this many).
pub const MCSTAT_CHECK_MAX_LOBES: usize = 4;
/// A sample within this chord length of a lobe's direction is that lobe's.
pub const MCSTAT_CHECK_LOBE_TOLERANCE: f64 = 1e-4;

/// `lobes(user, wi, x, mass, value, count)`: 0 on success.  For the check's
/// wi, `*count <= MCSTAT_CHECK_MAX_LOBES` discrete (delta) lobes: lobe k's
/// direction `x[3k..3k + 3]`, the probability `mass[k]` in [0, 1] with which
/// sample() returns it (the pdf it reports there) and `value[k] >= 0`, its
/// albedo (the weight there is value/mass).  Called once per check
/// (`mcstat_check_bsdf` only).
pub type mcstat_check_lobes_fn = Option<
    unsafe extern "C" fn(
        user: *mut c_void,
        wi: *const f64,
        x: *mut f64,
        mass: *mut f64,
        value: *mut f64,
        count: *mut usize,
    ) -> c_int,
>;

/// The named storage of `mcstat_check_model`'s anonymous union.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_check_model_named {
    /// None: no discrete lobes (0.2.0's zeros).
    pub lobes: mcstat_check_lobes_fn,
    /// Zero.
    pub reserved_rest: [f64; 3],
}

/// `mcstat_check_model`'s anonymous union: `reserved` is 0.2.0's name of the
/// storage (zeros: no lobes).  `Default` is all zeros.
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_check_model_union {
    pub reserved: [f64; 4],
    pub s: mcstat_check_model_named,
}

impl Default for mcstat_check_model_union {
    fn default() -> Self {
        mcstat_check_model_union { reserved: [0.0; 4] }
    }
}

impl std::fmt::Debug for mcstat_check_model_union {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // both members are plain data of the same size: the named one is
        // always readable
        unsafe { self.s.fmt(f) }
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_check_model {
    pub domain: i32,
    pub n_uniforms: i32,
    pub weight: i32,
    pub sample_reports: i32,
    pub user: *mut c_void,
    pub sample: mcstat_check_sample_fn,
    pub pdf: mcstat_check_density_fn,
    pub eval: mcstat_check_density_fn,
    /// C's anonymous union of `reserved[4]` and `{ lobes, reserved_rest[3] }`.
    pub extra: mcstat_check_model_union,
}

impl mcstat_check_model {
    /// The discrete lobes' callback (`model->lobes` in C).
    pub fn lobes(&self) -> mcstat_check_lobes_fn {
        unsafe { self.extra.s.lobes }
    }
    pub fn set_lobes(&mut self, lobes: mcstat_check_lobes_fn) {
        // a write to the named member: reserved_rest is left as it was
        self.extra.s.lobes = lobes;
    }
}

pub const MCSTAT_CHECK_ROUTE_CELLS: i32 = 0;
pub const MCSTAT_CHECK_ROUTE_MASS: i32 = 1;
pub const MCSTAT_CHECK_ROUTE_PDF_VALUE: i32 = 2;
pub const MCSTAT_CHECK_ROUTE_WEIGHT: i32 = 3;
pub const MCSTAT_CHECK_ROUTE_SUPPORT: i32 = 4;
pub const MCSTAT_CHECK_ROUTE_INTEGRALS: i32 = 5;
pub const MCSTAT_CHECK_ROUTE_ENERGY: i32 = 6;
pub const MCSTAT_CHECK_ROUTE_RECIPROCITY: i32 = 7;
pub const MCSTAT_CHECK_ROUTE_KS: i32 = 8;
pub const MCSTAT_CHECK_ROUTE_COUNT: usize = 9;

pub const MCSTAT_CHECK_STATE_RAN: i32 = 0;
pub const MCSTAT_CHECK_STATE_SKIPPED: i32 = 1;
pub const MCSTAT_CHECK_STATE_INVALID: i32 = 2;
#[deprecated(note = "use MCSTAT_CHECK_STATE_RAN")]
pub const MCSTAT_ROUTE_RAN: i32 = MCSTAT_CHECK_STATE_RAN;
#[deprecated(note = "use MCSTAT_CHECK_STATE_SKIPPED")]
pub const MCSTAT_ROUTE_SKIPPED: i32 = MCSTAT_CHECK_STATE_SKIPPED;
#[deprecated(note = "use MCSTAT_CHECK_STATE_INVALID")]
pub const MCSTAT_ROUTE_INVALID: i32 = MCSTAT_CHECK_STATE_INVALID;

pub const MCSTAT_CHECK_ROUTE_ALL: u32 = (1u32 << MCSTAT_CHECK_ROUTE_COUNT) - 1;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_check_options {
    pub size: u32,
    pub routes: u32,
    pub stochastic: i32,
    pub reciprocal: i32,
    pub cells: i32,
    pub reserved_i: i32,
    pub n_pilot: u64,
    pub n_eval: u64,
    pub batch: u64,
    pub rtol: f64,
    pub tolerated: f64,
    pub reserved: [f64; 4],
    /// Since 0.3 (`MCSTAT_CHECK_OPTIONS_SIZE_0_3`).  `mcstat_check_medium`:
    /// < 0 (the initialiser's -1): a flight that passes the surface is a
    /// failed sample, which must weigh 0; in [0, 1]: T(tmax), the
    /// transmittance to the surface, and such a flight reports pdf 0 and the
    /// weight it carries on; MASS also tests that the mean over the n flights
    /// of the escapes' weights (0 for a scattering) equals T(tmax).  Needs
    /// `MCSTAT_CHECK_WEIGHT_OVER_PDF`; NaN, > 1, or >= 0 for another check:
    /// `MCSTAT_EINVAL`.
    pub escape_transmittance: f64,
    /// Since 0.3.  The relative resolution of the caller's arithmetic:
    /// differences of integrals at that scale are rounding, not evidence
    /// (the statistical routes add it as an error of what they compare).
    /// 0 (the initialiser's): derived from the values the callbacks return,
    /// `MCSTAT_RESOLUTION_FLOAT32` when every pdf, weight and eval
    /// value is a float32, else `MCSTAT_RESOLUTION_FLOAT64`; > 0: that
    /// value, below 0.01.
    pub resolution: f64,
}

/// sizeof(mcstat_check_options) in each release that changed it.
pub const MCSTAT_CHECK_OPTIONS_SIZE_0_2: usize = 96;
pub const MCSTAT_CHECK_OPTIONS_SIZE_0_3: usize = 112;

/// The derived resolutions: 64 units in the last place of float32 and float64.
pub const MCSTAT_RESOLUTION_FLOAT32: f64 = 3.814697265625e-06; // 2^-18
pub const MCSTAT_RESOLUTION_FLOAT64: f64 = 7.105427357601002e-15; // 2^-47

/// Why a route could not answer (`mcstat_check_route_result::why`).
pub const MCSTAT_CHECK_WHY_NONE: i32 = 0;
pub const MCSTAT_CHECK_WHY_HEAVY_TAIL: i32 = 1;
pub const MCSTAT_CHECK_WHY_TOO_FEW: i32 = 2;
pub const MCSTAT_CHECK_WHY_ENVELOPE: i32 = 3;
pub const MCSTAT_CHECK_WHY_NOTHING: i32 = 4;
pub const MCSTAT_CHECK_WHY_NUMERIC: i32 = 5;
pub const MCSTAT_CHECK_WHY_INTEGRATION: i32 = 6;

/// The verdicts of `mcstat_check_verdict`.
pub const MCSTAT_CHECK_CONSISTENT: c_int = 0;
pub const MCSTAT_CHECK_INCONSISTENT: c_int = 1;
pub const MCSTAT_CHECK_INCONCLUSIVE: c_int = 2;

#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_check_route_result {
    pub state: i32,
    pub deterministic: i32,
    pub reject: i32,
    /// State INVALID: `MCSTAT_CHECK_WHY_*` (C's union with 0.2.0's `reserved_i`).
    pub why: i32,
    pub statistic: f64,
    pub df: f64,
    pub p_value: f64,
    pub p_adjusted: f64,
    pub effect: f64,
    pub detectable: f64,
    pub n_for_1pct: f64,
    pub checked: u64,
    pub count: u64,
    pub r#where: [f64; 3],
    pub value: [f64; 2],
    /// Statistical routes: the relative numerical floor they applied (NaN
    /// for the deterministic ones); with `reserved_2`, C's union with
    /// 0.2.0's `reserved[3]`.
    pub resolution: f64,
    pub reserved_2: [f64; 2],
}

pub const MCSTAT_CHECK_KIND_BSDF: i32 = 0;
pub const MCSTAT_CHECK_KIND_EMITTER: i32 = 1;
pub const MCSTAT_CHECK_KIND_WARP: i32 = 2;
pub const MCSTAT_CHECK_KIND_PHASE: i32 = 3;
pub const MCSTAT_CHECK_KIND_MEDIUM: i32 = 4;

/// The discrete lobes' counts and a medium's escape weights: the named
/// storage of the anonymous union over `reserved_rest` in
/// `mcstat_check_report`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_check_report_lobes {
    /// Discrete lobes given by `lobes()` (0 without).
    pub lobes: u64,
    /// Samples that fell on a discrete lobe.
    pub n_lobe: u64,
    /// The sum of the lobes' masses (probabilities).
    pub lobe_mass: f64,
    /// The sum of the lobes' values: the discrete part of the albedo (the
    /// report's albedo fields are the smooth part's).
    pub lobe_albedo: f64,
    /// `mcstat_check_medium` with `escape_transmittance >= 0`: the mean over
    /// the n flights of the escapes' weights (0 for a scattering), which
    /// MASS tests against T(tmax); NaN otherwise.
    pub escape_weight: f64,
    /// Its standard error (NaN when not checked, or with fewer than 2
    /// escapes of weight > 0).
    pub escape_weight_se: f64,
}

/// The anonymous union over `reserved_rest` in `mcstat_check_report`:
/// `reserved_rest` is 0.2.0's name of the storage.
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_check_report_rest {
    pub reserved_rest: [f64; 6],
    pub s: mcstat_check_report_lobes,
}

impl Default for mcstat_check_report_rest {
    fn default() -> Self {
        mcstat_check_report_rest { reserved_rest: [0.0; 6] }
    }
}

impl std::fmt::Debug for mcstat_check_report_rest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        unsafe { self.s.fmt(f) }
    }
}

/// The named storage of `mcstat_check_report`'s anonymous union.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct mcstat_check_report_named {
    /// Samples with weight 0 where the reported pdf and eval() are > 0.
    pub zero_weight: u64,
    /// mcstat_check_medium: the sigma_ref of the map of distances (0 otherwise)
    pub sigma_ref: f64,
    /// C's anonymous union of `reserved_rest[6]` and the lobes' counts.
    pub rest: mcstat_check_report_rest,
}

/// `mcstat_check_report`'s anonymous union: `reserved` is 0.1.0's name of the storage.
#[repr(C)]
#[derive(Clone, Copy)]
pub union mcstat_check_report_union {
    pub reserved: [f64; 8],
    pub s: mcstat_check_report_named,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct mcstat_check_report {
    pub kind: i32,
    pub domain: i32,
    pub reject: i32,
    pub heavy_tailed: i32,
    pub alpha: f64,
    pub p_value: f64,
    pub wi: [f64; 3],
    pub n: u64,
    pub n_failed: u64,
    pub n_pilot: u64,
    pub n_eval: u64,
    pub cells: u64,
    pub calls: u64,
    pub pdf_without_eval: u64,
    pub mass: f64,
    pub mass_error: f64,
    pub mass_sampled: f64,
    pub mass_sampled_se: f64,
    pub albedo: f64,
    pub albedo_se: f64,
    pub albedo_eval: f64,
    pub albedo_eval_se: f64,
    pub tail_index: [f64; 2],
    pub extra: mcstat_check_report_union,
    pub route: [mcstat_check_route_result; MCSTAT_CHECK_ROUTE_COUNT],
    pub message: [c_char; 256],
}

impl mcstat_check_report {
    pub fn zero_weight(&self) -> u64 {
        unsafe { self.extra.s.zero_weight }
    }
    /// The discrete lobes' counts (`lobes`, `n_lobe`, `lobe_mass`,
    /// `lobe_albedo`), with a medium's `escape_weight`, `escape_weight_se`.
    pub fn lobe_counts(&self) -> mcstat_check_report_lobes {
        unsafe { self.extra.s.rest.s }
    }
    /// `mcstat_check_medium` with `escape_transmittance >= 0`: the escapes'
    /// mean weight and its standard error (NaN otherwise).
    pub fn escape_weight(&self) -> (f64, f64) {
        let s = self.lobe_counts();
        (s.escape_weight, s.escape_weight_se)
    }
}

impl std::fmt::Debug for mcstat_check_report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let len = self.message.iter().position(|&c| c == 0).unwrap_or(self.message.len());
        let msg: Vec<u8> = self.message[..len].iter().map(|&c| c as u8).collect();
        f.debug_struct("mcstat_check_report")
            .field("kind", &self.kind)
            .field("domain", &self.domain)
            .field("reject", &self.reject)
            .field("heavy_tailed", &self.heavy_tailed)
            .field("alpha", &self.alpha)
            .field("p_value", &self.p_value)
            .field("n", &self.n)
            .field("zero_weight", &self.zero_weight())
            .field("lobes", &self.lobe_counts())
            .field("route", &self.route)
            .field("message", &String::from_utf8_lossy(&msg))
            .finish()
    }
}

// ============================================================================
// Sequential, anytime-valid tests (experimental).
// ============================================================================

pub const MCSTAT_SEQ_MEAN_1: c_int = 1;
pub const MCSTAT_SEQ_MEAN_2: c_int = 2;
pub const MCSTAT_SEQ_VAR_1: c_int = 3;
pub const MCSTAT_SEQ_VAR_2: c_int = 4;

pub const MCSTAT_SEQ_CONTINUE: i32 = 0;
pub const MCSTAT_SEQ_DECIDED: i32 = 1;

pub const MCSTAT_SEQ_HOLD_FEW: u32 = 1;
pub const MCSTAT_SEQ_HOLD_DEGENERATE: u32 = 2;
pub const MCSTAT_SEQ_HOLD_KURTOSIS: u32 = 4;

/// `mcstat_seq_options`; start from `mcstat_seq_options_init_size(&mut o,
/// size_of::<mcstat_seq_options>())`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_seq_options {
    pub size: u32,
    pub alternative: i32,
    pub alpha: f64,
    pub eps: f64,
    pub t_opt: f64,
    pub kurtosis_gate: f64,
    pub var_ucb_z: f64,
    pub min_n: u64,
}

/// sizeof(mcstat_seq_options) in each release that changed it.
pub const MCSTAT_SEQ_OPTIONS_SIZE_0_2: usize = 56;

pub const MCSTAT_SEQ_VERSION: u32 = 1;

/// `mcstat_seq`: one sequential test's state, 448 bytes of plain data the
/// caller owns (no pointers), written only by the `mcstat_seq_*` functions.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct mcstat_seq {
    pub version: u32,
    pub kind: i32,
    pub alternative: i32,
    pub state: i32,
    pub decision: i32,
    pub hold: u32,
    pub x: mcstat_moments,
    pub y: mcstat_moments,
    pub null_value: f64,
    pub alpha: f64,
    pub eps: f64,
    pub t_opt: f64,
    pub kurtosis_gate: f64,
    pub var_ucb_z: f64,
    pub min_n: u64,
    pub looks: u64,
    pub n_decided: u64,
    pub log_e: f64,
    pub log_e_max: f64,
    pub cs: [f64; 2],
    pub reserved: [f64; 8],
}

// ============================================================================
// Versions.
// ============================================================================

pub const MCSTAT_VERSION_MAJOR: u32 = 0;
pub const MCSTAT_VERSION_MINOR: u32 = 2;
pub const MCSTAT_VERSION_PATCH: u32 = 0;
pub const MCSTAT_SOVERSION: u32 = 0;
pub const MCSTAT_VERSION_NUMBER: u32 =
    MCSTAT_VERSION_MAJOR * 10000 + MCSTAT_VERSION_MINOR * 100 + MCSTAT_VERSION_PATCH;

// ============================================================================
// Deprecated names (types and constants; the functions are below).
// ============================================================================

#[deprecated(note = "use mcstat_gof_options")]
pub type mcstat_chisq_options = mcstat_gof_options;
#[deprecated(note = "use MCSTAT_GOF_PROBABILITIES")]
pub const MCSTAT_CHISQ_PROBABILITIES: i32 = MCSTAT_GOF_PROBABILITIES;
#[deprecated(note = "use MCSTAT_GOF_COUNTS")]
pub const MCSTAT_CHISQ_COUNTS: i32 = MCSTAT_GOF_COUNTS;
#[deprecated(note = "use MCSTAT_GOF_DEFAULT_MIN_EXPECTED")]
pub const MCSTAT_CHISQ_DEFAULT_MIN_EXPECTED: f64 = MCSTAT_GOF_DEFAULT_MIN_EXPECTED;
#[deprecated(note = "use MCSTAT_GOF_OPTIONS_SIZE_0_1")]
pub const MCSTAT_CHISQ_OPTIONS_SIZE_0_1: usize = MCSTAT_GOF_OPTIONS_SIZE_0_1;

// The layout, at compile time, against the header's numbers (LP64: the
// pointers in mcstat_ks_options and mcstat_check_model are 8 bytes).
#[cfg(target_pointer_width = "64")]
const _: () = {
    use std::mem::size_of;
    assert!(size_of::<mcstat_moments>() == 128);
    assert!(size_of::<mcstat_stream>() == MCSTAT_STREAM_BYTES);
    assert!(size_of::<mcstat_result>() == 216);
    assert!(size_of::<mcstat_ks_options>() == MCSTAT_KS_OPTIONS_SIZE_0_1);
    assert!(size_of::<mcstat_power_options>() == MCSTAT_POWER_OPTIONS_SIZE_0_1);
    assert!(size_of::<mcstat_diag_options>() == MCSTAT_DIAG_OPTIONS_SIZE_0_1);
    assert!(size_of::<mcstat_gof_options>() == MCSTAT_GOF_OPTIONS_SIZE_0_1);
    assert!(size_of::<mcstat_check_options>() == MCSTAT_CHECK_OPTIONS_SIZE_0_3);
    assert!(size_of::<mcstat_seq_options>() == MCSTAT_SEQ_OPTIONS_SIZE_0_2);
    assert!(size_of::<mcstat_seq>() == 448);
    assert!(size_of::<mcstat_pixels_in>() == MCSTAT_PIXELS_IN_SIZE_0_2);
    assert!(size_of::<mcstat_pixels_options>() == MCSTAT_PIXELS_OPTIONS_SIZE_0_3);
    assert!(size_of::<mcstat_pixels_out>() == MCSTAT_PIXELS_OUT_SIZE_0_2);
    assert!(size_of::<mcstat_escalation>() == 32);
};

extern "C" {
    // ---- conventions ------------------------------------------------------
    pub fn mcstat_strerror(status: c_int) -> *const c_char;
    /// Why the last call on this thread refused its arguments ("" when it
    /// gave no reason): the renderer checks and `mcstat_check_work_size`
    /// clear it when they start and set it for every `MCSTAT_EINVAL` and
    /// `MCSTAT_ETOOBIG`.  Thread-local; read it on the calling thread right
    /// after the call.  Never NULL.  (Since 0.3.)
    pub fn mcstat_last_error() -> *const c_char;
    pub fn mcstat_alternative_parse(name: *const c_char, alternative: *mut c_int) -> c_int;
    pub fn mcstat_alternative_name(alternative: c_int) -> *const c_char;

    // ---- accumulators -----------------------------------------------------
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
    pub fn mcstat_moments_from_summary(n: u64, mean: f64, m2: f64, out: *mut mcstat_moments) -> c_int;

    pub fn mcstat_moments_init_rows(m: *mut mcstat_moments, rows: usize) -> c_int;
    pub fn mcstat_moments_add_rows(
        m: *mut mcstat_moments,
        rows: usize,
        x: *const f64,
        n: usize,
        x_stride: usize,
        flags: c_uint,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_moments_merge_rows(dst: *mut mcstat_moments, src: *const mcstat_moments, rows: usize) -> c_int;
    pub fn mcstat_moments_to_bytes_rows(m: *const mcstat_moments, rows: usize, buf: *mut u8, size: usize) -> c_int;
    pub fn mcstat_moments_from_bytes_rows(buf: *const u8, size: usize, rows: usize, m: *mut mcstat_moments) -> c_int;

    pub fn mcstat_stream_init(s: *mut mcstat_stream) -> c_int;
    pub fn mcstat_stream_flush(s: *mut mcstat_stream) -> c_int;
    pub fn mcstat_stream_merge(dst: *mut mcstat_stream, src: *const mcstat_stream) -> c_int;
    pub fn mcstat_stream_moments(s: *const mcstat_stream, out: *mut mcstat_moments) -> c_int;
    pub fn mcstat_stream_check_mean(
        s: *const mcstat_stream,
        reference: f64,
        tolerance: f64,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_stream_check_var(s: *const mcstat_stream, bound: f64, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_sizeof_stream() -> usize;

    // ---- the tests and their result -------------------------------------
    pub fn mcstat_result_format(
        r: *const mcstat_result,
        x_name: *const c_char,
        y_name: *const c_char,
        buf: *mut c_char,
        size: usize,
        length: *mut usize,
    ) -> c_int;
    pub fn mcstat_decision_name(decision: c_int) -> *const c_char;

    pub fn mcstat_t_test_1(x: *const f64, n: usize, mu0: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_t_test_1_moments(
        x: *const mcstat_moments,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
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
    pub fn mcstat_efficiency_test(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        time_x: *const mcstat_moments,
        time_y: *const mcstat_moments,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_t_test_2_pooled(
        x: *const f64,
        nx: usize,
        y: *const f64,
        ny: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_t_test_2_pooled_moments(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_t_test_paired(
        x: *const f64,
        y: *const f64,
        n: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_result_log_p_value(r: *const mcstat_result, log_p: *mut f64) -> c_int;
    pub fn mcstat_result_conf_int(r: *const mcstat_result, confidence_level: f64, conf_int: *mut f64) -> c_int;
    pub fn mcstat_var_test_1(
        x: *const f64,
        n: usize,
        sigma2: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_var_test_1_moments(
        x: *const mcstat_moments,
        sigma2: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
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
    pub fn mcstat_ks_cache_stats(
        cache: *const mcstat_ks_cache,
        hits: *mut u64,
        misses: *mut u64,
        entries: *mut u64,
    ) -> c_int;
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

    // ---- per-pixel rows ---------------------------------------------------
    pub fn mcstat_t_test_1_matrix(
        x: *const f64,
        n: usize,
        x_stride: usize,
        rows: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_t_test_2_matrix(
        x: *const f64,
        nx: usize,
        x_stride: usize,
        y: *const f64,
        ny: usize,
        y_stride: usize,
        rows: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_var_test_1_matrix(
        x: *const f64,
        n: usize,
        x_stride: usize,
        rows: usize,
        sigma2: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_var_test_2_matrix(
        x: *const f64,
        nx: usize,
        x_stride: usize,
        y: *const f64,
        ny: usize,
        y_stride: usize,
        rows: usize,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_t_test_2_pixels(
        x: *const f64,
        nx: usize,
        x_seed_stride: usize,
        y: *const f64,
        ny: usize,
        y_seed_stride: usize,
        channels: usize,
        weights: *const f64,
        begin: usize,
        end: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *const mcstat_pixels_out,
    ) -> c_int;
    pub fn mcstat_sizeof_pixels_in() -> usize;
    pub fn mcstat_sizeof_pixels_options() -> usize;
    pub fn mcstat_sizeof_pixels_out() -> usize;
    pub fn mcstat_pixels_in_init_size(x: *mut mcstat_pixels_in, size: usize) -> c_int;
    pub fn mcstat_pixels_options_init_size(opt: *mut mcstat_pixels_options, size: usize) -> c_int;
    pub fn mcstat_pixels_out_init_size(out: *mut mcstat_pixels_out, size: usize) -> c_int;
    pub fn mcstat_pixels_test(
        test: c_int,
        x: *const mcstat_pixels_in,
        y: *const mcstat_pixels_in,
        begin: usize,
        end: usize,
        null_value: f64,
        alternative: c_int,
        alpha: f64,
        opt: *const mcstat_pixels_options,
        out: *const mcstat_pixels_out,
    ) -> c_int;
    pub fn mcstat_t_test_2_pixels_f32(
        x: *const f32,
        nx: usize,
        x_seed_stride: usize,
        y: *const f32,
        ny: usize,
        y_seed_stride: usize,
        channels: usize,
        weights: *const f64,
        begin: usize,
        end: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *const mcstat_pixels_out,
    ) -> c_int;
    pub fn mcstat_t_test_1_moments_rows(
        x: *const mcstat_moments,
        rows: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_t_test_2_moments_rows(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        rows: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_var_test_1_moments_rows(
        x: *const mcstat_moments,
        rows: usize,
        sigma2: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    pub fn mcstat_var_test_2_moments_rows(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        rows: usize,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;

    // ---- multiple testing -------------------------------------------------
    pub fn mcstat_p_adjust_method_parse(name: *const c_char, method: *mut c_int) -> c_int;
    pub fn mcstat_p_adjust_method_name(method: c_int) -> *const c_char;
    pub fn mcstat_p_adjust_work_size(n: usize, method: c_int, bytes: *mut usize) -> c_int;
    pub fn mcstat_p_adjust(
        p: *const f64,
        n: usize,
        method: c_int,
        work: *mut c_void,
        work_bytes: usize,
        adjusted: *mut f64,
    ) -> c_int;
    pub fn mcstat_e_bh(e: *const f64, n: usize, work: *mut c_void, work_bytes: usize, adjusted: *mut f64) -> c_int;
    pub fn mcstat_escalation_design(alpha: f64, share1: f64, alpha0: f64, out: *mut mcstat_escalation) -> c_int;
    pub fn mcstat_escalation_decide(design: *const mcstat_escalation, p1: f64, p2: f64, decision: *mut c_int) -> c_int;

    // ---- equivalence ------------------------------------------------------
    pub fn mcstat_equivalence_test_1(
        x: *const f64,
        n: usize,
        mu0: f64,
        lower: f64,
        upper: f64,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_equivalence_test_1_moments(
        x: *const mcstat_moments,
        mu0: f64,
        lower: f64,
        upper: f64,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_equivalence_test_2(
        x: *const f64,
        nx: usize,
        y: *const f64,
        ny: usize,
        lower: f64,
        upper: f64,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_equivalence_test_2_moments(
        x: *const mcstat_moments,
        y: *const mcstat_moments,
        lower: f64,
        upper: f64,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;

    // ---- power (experimental) ---------------------------------------------
    pub fn mcstat_power_options_init_size(o: *mut mcstat_power_options, size: usize) -> c_int;
    /// 0.1.0's initialiser: writes `MCSTAT_POWER_OPTIONS_SIZE_0_1` bytes.
    pub fn mcstat_power_options_init(o: *mut mcstat_power_options) -> c_int;
    pub fn mcstat_sizeof_power_options() -> usize;
    pub fn mcstat_power_compute(o: *const mcstat_power_options, power: *mut f64) -> c_int;
    pub fn mcstat_power_solve(o: *const mcstat_power_options, unknown: c_int, out: *mut mcstat_power_options) -> c_int;
    pub fn mcstat_power_format(o: *const mcstat_power_options, buf: *mut c_char, size: usize, length: *mut usize) -> c_int;

    // ---- diagnostics (experimental) ---------------------------------------
    pub fn mcstat_diag_options_init_size(opt: *mut mcstat_diag_options, size: usize) -> c_int;
    /// 0.1.0's initialiser: writes `MCSTAT_DIAG_OPTIONS_SIZE_0_1` bytes.
    pub fn mcstat_diag_options_init(opt: *mut mcstat_diag_options) -> c_int;
    pub fn mcstat_sizeof_diag_options() -> usize;
    pub fn mcstat_sizeof_diagnostics() -> usize;
    pub fn mcstat_diag_compute(
        x: *const f64,
        n: usize,
        opt: *const mcstat_diag_options,
        out: *mut mcstat_diagnostics,
    ) -> c_int;
    pub fn mcstat_diag_tail_index(x: *const f64, n: usize, tail_k: usize, index: *mut f64) -> c_int;
    pub fn mcstat_diag_t_size(skewness: f64, kurtosis: f64, k: u64, m: u64, alpha: f64, size: *mut f64) -> c_int;
    pub fn mcstat_diag_batch_size(
        skewness: f64,
        kurtosis: f64,
        m: u64,
        alpha: f64,
        tolerance: f64,
        k: *mut u64,
    ) -> c_int;

    // ---- goodness of fit (experimental) -----------------------------------
    pub fn mcstat_gof_options_init_size(opt: *mut mcstat_gof_options, size: usize) -> c_int;
    pub fn mcstat_sizeof_gof_options() -> usize;
    pub fn mcstat_gof_default_min_expected() -> f64;
    pub fn mcstat_gof_chisq_test(
        observed: *const f64,
        expected: *const f64,
        k: usize,
        opt: *const mcstat_gof_options,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_binom_test(x: u64, n: u64, p: f64, alternative: c_int, alpha: f64, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_battery_test(
        rejections: u64,
        k: u64,
        level: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    pub fn mcstat_battery_test_pvalues(
        p_values: *const f64,
        k: usize,
        level: f64,
        alternative: c_int,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;

    // ---- renderer checks (experimental) ----------------------------------
    pub fn mcstat_check_domain_dims(domain: c_int) -> c_int;
    pub fn mcstat_check_domain_parse(name: *const c_char, domain: *mut c_int) -> c_int;
    pub fn mcstat_check_domain_name(domain: c_int) -> *const c_char;
    pub fn mcstat_check_route_name(route: c_int) -> *const c_char;
    pub fn mcstat_check_route_parse(name: *const c_char, route: *mut c_int) -> c_int;
    pub fn mcstat_check_options_init_size(opt: *mut mcstat_check_options, size: usize) -> c_int;
    pub fn mcstat_sizeof_check_options() -> usize;
    pub fn mcstat_sizeof_check_model() -> usize;
    pub fn mcstat_sizeof_check_report() -> usize;
    pub fn mcstat_check_work_size(
        model: *const mcstat_check_model,
        n: usize,
        opt: *const mcstat_check_options,
        bytes: *mut usize,
    ) -> c_int;
    pub fn mcstat_check_bsdf(
        model: *const mcstat_check_model,
        wi: *const f64,
        n: usize,
        seed: u64,
        alpha: f64,
        opt: *const mcstat_check_options,
        work: *mut c_void,
        work_bytes: usize,
        out: *mut mcstat_check_report,
    ) -> c_int;
    pub fn mcstat_check_emitter(
        model: *const mcstat_check_model,
        n: usize,
        seed: u64,
        alpha: f64,
        opt: *const mcstat_check_options,
        work: *mut c_void,
        work_bytes: usize,
        out: *mut mcstat_check_report,
    ) -> c_int;
    pub fn mcstat_check_warp(
        model: *const mcstat_check_model,
        n: usize,
        seed: u64,
        alpha: f64,
        opt: *const mcstat_check_options,
        work: *mut c_void,
        work_bytes: usize,
        out: *mut mcstat_check_report,
    ) -> c_int;
    pub fn mcstat_check_phase(
        model: *const mcstat_check_model,
        wi: *const f64,
        n: usize,
        seed: u64,
        alpha: f64,
        opt: *const mcstat_check_options,
        work: *mut c_void,
        work_bytes: usize,
        out: *mut mcstat_check_report,
    ) -> c_int;
    pub fn mcstat_check_medium(
        model: *const mcstat_check_model,
        sigma_ref: f64,
        n: usize,
        seed: u64,
        alpha: f64,
        opt: *const mcstat_check_options,
        work: *mut c_void,
        work_bytes: usize,
        out: *mut mcstat_check_report,
    ) -> c_int;
    pub fn mcstat_check_format(r: *const mcstat_check_report, buf: *mut c_char, size: usize, length: *mut usize) -> c_int;
    pub fn mcstat_check_route_meaning(route: c_int) -> *const c_char;
    pub fn mcstat_check_route_blind_spot(route: c_int) -> *const c_char;
    pub fn mcstat_check_verdict(report: *const mcstat_check_report, verdict: *mut c_int, unanswered: *mut u32) -> c_int;
    pub fn mcstat_check_verdict_name(verdict: c_int) -> *const c_char;
    pub fn mcstat_check_why_text(why: c_int) -> *const c_char;

    // ---- sequential tests (experimental) ---------------------------------
    pub fn mcstat_seq_options_init_size(opt: *mut mcstat_seq_options, size: usize) -> c_int;
    pub fn mcstat_sizeof_seq_options() -> usize;
    pub fn mcstat_seq_init(s: *mut mcstat_seq, kind: c_int, null_value: f64, opt: *const mcstat_seq_options) -> c_int;
    pub fn mcstat_seq_push_moments(s: *mut mcstat_seq, batch: *const mcstat_moments) -> c_int;
    pub fn mcstat_seq_push_array(s: *mut mcstat_seq, x: *const f64, n: usize) -> c_int;
    pub fn mcstat_seq_push_stream(s: *mut mcstat_seq, frame: *const mcstat_stream) -> c_int;
    pub fn mcstat_seq_push_2_moments(s: *mut mcstat_seq, bx: *const mcstat_moments, by: *const mcstat_moments) -> c_int;
    pub fn mcstat_seq_push_2_array(s: *mut mcstat_seq, x: *const f64, nx: usize, y: *const f64, ny: usize) -> c_int;
    pub fn mcstat_seq_result(s: *const mcstat_seq, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_seq_finish(s: *const mcstat_seq, out: *mut mcstat_result) -> c_int;
    pub fn mcstat_seq_kind_name(kind: c_int) -> *const c_char;
    pub fn mcstat_sizeof_seq() -> usize;

    // ---- distributions ---------------------------------------------------
    pub fn mcstat_t_cdf(x: f64, df: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_t_logcdf(x: f64, df: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_t_quantile(p: f64, df: f64, upper: c_int, x: *mut f64) -> c_int;
    pub fn mcstat_t_quantiles(p: f64, df: *const f64, n: usize, upper: c_int, x: *mut f64) -> c_int;
    pub fn mcstat_chisq_cdf(x: f64, df: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_chisq_logcdf(x: f64, df: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_chisq_quantile(p: f64, df: f64, upper: c_int, x: *mut f64) -> c_int;
    pub fn mcstat_f_cdf(x: f64, df1: f64, df2: f64, upper: c_int, p: *mut f64) -> c_int;
    pub fn mcstat_f_logcdf(x: f64, df1: f64, df2: f64, upper: c_int, logp: *mut f64) -> c_int;
    pub fn mcstat_f_quantile(p: f64, df1: f64, df2: f64, upper: c_int, x: *mut f64) -> c_int;

    // ---- sizes, versions, GSL's handler ----------------------------------
    pub fn mcstat_sizeof_moments() -> usize;
    pub fn mcstat_sizeof_result() -> usize;
    pub fn mcstat_sizeof_moments_bytes() -> usize;
    pub fn mcstat_version_number() -> c_uint;
    pub fn mcstat_version() -> *const c_char;
    pub fn mcstat_gsl_handler_off();
    pub fn mcstat_gsl_handler_off_if_default() -> c_int;

    // ---- deprecated names ------------------------------------------------
    #[deprecated(note = "use mcstat_sizeof_moments_bytes")]
    pub fn mcstat_moments_bytes() -> usize;
    #[deprecated(note = "use mcstat_sizeof_gof_options")]
    pub fn mcstat_sizeof_chisq_options() -> usize;
    #[deprecated(note = "use mcstat_diag_compute")]
    pub fn mcstat_diagnose(x: *const f64, n: usize, opt: *const mcstat_diag_options, out: *mut mcstat_diagnostics) -> c_int;
    #[deprecated(note = "use mcstat_diag_tail_index")]
    pub fn mcstat_tail_index(x: *const f64, n: usize, tail_k: usize, index: *mut f64) -> c_int;
    #[deprecated(note = "use mcstat_diag_t_size")]
    pub fn mcstat_t_size_edgeworth(skewness: f64, kurtosis: f64, k: u64, m: u64, alpha: f64, size: *mut f64) -> c_int;
    #[deprecated(note = "use mcstat_diag_batch_size")]
    pub fn mcstat_batch_size_recommend(
        skewness: f64,
        kurtosis: f64,
        m: u64,
        alpha: f64,
        tolerance: f64,
        k: *mut u64,
    ) -> c_int;
    #[deprecated(note = "use mcstat_gof_options_init_size")]
    pub fn mcstat_chisq_options_init_size(opt: *mut mcstat_gof_options, size: usize) -> c_int;
    /// 0.1.0's initialiser: writes `MCSTAT_GOF_OPTIONS_SIZE_0_1` bytes.
    #[deprecated(note = "use mcstat_gof_options_init_size")]
    pub fn mcstat_chisq_options_init(opt: *mut mcstat_gof_options) -> c_int;
    #[deprecated(note = "use mcstat_gof_default_min_expected")]
    pub fn mcstat_chisq_default_min_expected() -> f64;
    #[deprecated(note = "use mcstat_gof_chisq_test")]
    pub fn mcstat_chisq_gof(
        observed: *const f64,
        expected: *const f64,
        k: usize,
        opt: *const mcstat_gof_options,
        alpha: f64,
        out: *mut mcstat_result,
    ) -> c_int;
    #[deprecated(note = "use mcstat_seq_push_2_moments")]
    pub fn mcstat_seq_push_moments_2(s: *mut mcstat_seq, bx: *const mcstat_moments, by: *const mcstat_moments) -> c_int;
    #[deprecated(note = "use mcstat_seq_push_2_array")]
    pub fn mcstat_seq_push_array_2(s: *mut mcstat_seq, x: *const f64, nx: usize, y: *const f64, ny: usize) -> c_int;
    /// 0.1.0's order: `rows` before `n`.
    #[deprecated(note = "use mcstat_t_test_1_matrix (rows moves after x_stride)")]
    pub fn mcstat_t_test_1_rows(
        x: *const f64,
        rows: usize,
        n: usize,
        x_stride: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    #[deprecated(note = "use mcstat_t_test_2_matrix (same arguments)")]
    pub fn mcstat_t_test_2_rows(
        x: *const f64,
        nx: usize,
        x_stride: usize,
        y: *const f64,
        ny: usize,
        y_stride: usize,
        rows: usize,
        mu0: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    /// 0.1.0's order: `rows` before `n`.
    #[deprecated(note = "use mcstat_var_test_1_matrix (rows moves after x_stride)")]
    pub fn mcstat_var_test_1_rows(
        x: *const f64,
        rows: usize,
        n: usize,
        x_stride: usize,
        sigma2: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
    #[deprecated(note = "use mcstat_var_test_2_matrix (same arguments)")]
    pub fn mcstat_var_test_2_rows(
        x: *const f64,
        nx: usize,
        x_stride: usize,
        y: *const f64,
        ny: usize,
        y_stride: usize,
        rows: usize,
        ratio: f64,
        alternative: c_int,
        alpha: f64,
        flags: c_uint,
        out: *mut mcstat_result,
        status: *mut i32,
    ) -> c_int;
}

#[cfg(test)]
mod tests;
