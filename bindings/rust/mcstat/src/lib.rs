//! Statistical hypothesis tests for Monte Carlo estimators: safe Rust
//! bindings to libmcstat.
//!
//! Slices in, `Result<TestResult, Error>` out.  The numbers, the decisions
//! and the R-style text are computed by libmcstat; this crate converts
//! types and errors, and never hands out a NaN standing for "does not
//! apply": such fields are `Option`s or shorter slices.
//!
//! ```
//! use mcstat::{t_test_2, Alternative, Decision};
//! let new = [1.0, 1.2, 0.9, 1.1, 1.3, 0.8];
//! let trusted = [1.0, 1.05, 0.95, 1.02, 0.97, 1.01];
//! let r = t_test_2(&new, &trusted, 0.0, Alternative::TwoSided, 0.05)?;
//! assert_eq!(r.df().len(), 1);           // Welch: one degree of freedom
//! assert!(!r.reject() && r.decision() == Decision::Equal);
//! println!("{r}");                       // R's print.htest block + the decision
//! println!("{}", r.format("new", "trusted"));
//! # Ok::<(), mcstat::Error>(())
//! ```
//!
//! The families, each in its module and re-exported here: the tests on
//! slices and on accumulators ([`Moments`]), per-pixel rows ([`rows`]),
//! accumulator arrays and the per-thread [`Stream`], Kolmogorov-Smirnov
//! ([`ks_test_2`]), equivalence (TOST), multiple testing ([`p_adjust()`])
//! and escalation instead of reruns ([`Escalation`]), power ([`power`]),
//! estimator diagnostics ([`diag`]), goodness of fit and the binomial
//! battery test ([`gof`]), renderer checks ([`check`]), sequential
//! anytime-valid tests ([`SequentialTest`]) and the distributions
//! ([`dist`]).
use std::ffi::{CStr, CString};
use std::fmt;
use std::os::raw::{c_char, c_int};
use std::ptr;

pub use mcstat_sys as sys;

pub mod check;
pub mod diag;
pub mod dist;
pub mod escalation;
pub mod gof;
mod ks;
mod moments;
pub mod p_adjust;
pub mod power;
pub mod rows;
mod seq;

pub use check::{check_bsdf, check_emitter, check_medium, check_phase, check_warp, CheckModel, CheckOptions, CheckReport, Domain, Route, Verdict};
pub use diag::{diagnose, DiagOptions, Diagnostics};
pub use escalation::{Escalation, EscalationDecision};
pub use gof::{battery_test, battery_test_p_values, binom_test, gof_chisq_test, GofOptions};
pub use ks::{ks_test_2, KsCache, KsOptions};
pub use moments::{efficiency_test, t_test_1_moments, t_test_2_moments, t_test_2_pooled_moments, var_test_1_moments, var_test_2_moments, Moments, MomentsArray, Stream};
pub use p_adjust::{e_bh, p_adjust, PAdjustMethod};
pub use power::{Power, PowerSolution, PowerTest};
pub use rows::{Matrix, RowFlags, RowResults, Statuses};
pub use seq::{SeqHold, SeqKind, SeqOptions, SeqOutcome, SequentialTest};

// ---- errors --------------------------------------------------------------------

/// What went wrong: one variant per libmcstat status code, each with a
/// message: libmcstat's sentence for the status, or what the binding found
/// wrong with an argument, or what a renderer check's callback did, or why
/// a renderer check refused its arguments.
///
/// The renderer checks ([`check_bsdf`], [`check_emitter`], [`check_warp`],
/// [`check_phase`], [`check_medium`], [`check::check_work_size`]) and the
/// t and variance tests ([`t_test_1`], [`var_test_2`], their `_moments`
/// forms, ...) give libmcstat's reason for each
/// [`InvalidArgument`](Error::InvalidArgument) and [`TooBig`](Error::TooBig)
/// they return, verbatim (C's
/// `mcstat_last_error()`, read on the calling thread right after the call):
/// it names the field as C spells it, which is the Rust name too
/// (`"options.cells must be 0 (automatic) or 2..1048576, got 1"` for
/// [`CheckOptions::cells`], `"model.n_uniforms must be in 1..8, got 9"` for
/// [`CheckModel::new`]'s `n_uniforms`, `"alpha must be in (0, 1), got 1.5"`);
/// where C says 0 means automatic, `None` is the Rust spelling.
/// [`message`](Error::message) is that text; `Display` adds the status, as
/// for every error.  The ranges are checked once, in libmcstat.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Error {
    /// MCSTAT_EINVAL: an invalid argument.
    InvalidArgument(String),
    /// MCSTAT_ETOOFEW: too few observations.
    TooFewObservations(String),
    /// MCSTAT_ENONFINITE: NaN or infinity in the data.
    NonFinite(String),
    /// MCSTAT_EDEGENERATE: the data have (essentially) zero spread.
    DegenerateData(String),
    /// MCSTAT_ENOMEM.
    OutOfMemory(String),
    /// MCSTAT_ENUMERIC: a numerical method failed to converge.
    Numerical(String),
    /// MCSTAT_EBUFSIZE.
    BufferSize(String),
    /// MCSTAT_ECORRUPT: serialized bytes are corrupt, truncated or of another version.
    Corrupt(String),
    /// MCSTAT_ETOOBIG: sizes too large for the method, or a count past 2^64 - 1.
    TooBig(String),
    /// MCSTAT_ECALLBACK: a renderer check's callback failed, panicked or
    /// returned invalid values; the message says which and where.
    Callback(String),
    /// MCSTAT_EHEAVYTAIL: a sequential test ended with its kurtosis gate
    /// closed: the tails never allowed a decision in this budget
    /// ([`SequentialTest::finish`]).
    HeavyTail(String),
    /// A status this crate does not know (a newer library).
    Other { status: i32, message: String },
}

/// The kind of an [`Error`], without its message: for comparisons.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    InvalidArgument,
    TooFewObservations,
    NonFinite,
    DegenerateData,
    OutOfMemory,
    Numerical,
    BufferSize,
    Corrupt,
    TooBig,
    Callback,
    HeavyTail,
    Other(i32),
}

fn strerror(status: c_int) -> String {
    unsafe { CStr::from_ptr(sys::mcstat_strerror(status)) }.to_string_lossy().into_owned()
}

impl Error {
    /// The error of a C status, with libmcstat's sentence for it.
    pub fn from_status(status: i32) -> Error {
        Error::with_message(status, strerror(status))
    }
    /// The error of a C status with a message of the caller's.
    pub fn with_message(status: i32, message: impl Into<String>) -> Error {
        let m = message.into();
        match status {
            sys::MCSTAT_EINVAL => Error::InvalidArgument(m),
            sys::MCSTAT_ETOOFEW => Error::TooFewObservations(m),
            sys::MCSTAT_ENONFINITE => Error::NonFinite(m),
            sys::MCSTAT_EDEGENERATE => Error::DegenerateData(m),
            sys::MCSTAT_ENOMEM => Error::OutOfMemory(m),
            sys::MCSTAT_ENUMERIC => Error::Numerical(m),
            sys::MCSTAT_EBUFSIZE => Error::BufferSize(m),
            sys::MCSTAT_ECORRUPT => Error::Corrupt(m),
            sys::MCSTAT_ETOOBIG => Error::TooBig(m),
            sys::MCSTAT_ECALLBACK => Error::Callback(m),
            sys::MCSTAT_EHEAVYTAIL => Error::HeavyTail(m),
            status => Error::Other { status, message: m },
        }
    }
    /// An invalid argument found by the binding (e.g. slices of different
    /// lengths), with a message naming it.
    pub(crate) fn invalid(message: impl Into<String>) -> Error {
        Error::InvalidArgument(message.into())
    }
    /// The C status code (`MCSTAT_E*`).
    pub fn status(&self) -> i32 {
        match self {
            Error::InvalidArgument(_) => sys::MCSTAT_EINVAL,
            Error::TooFewObservations(_) => sys::MCSTAT_ETOOFEW,
            Error::NonFinite(_) => sys::MCSTAT_ENONFINITE,
            Error::DegenerateData(_) => sys::MCSTAT_EDEGENERATE,
            Error::OutOfMemory(_) => sys::MCSTAT_ENOMEM,
            Error::Numerical(_) => sys::MCSTAT_ENUMERIC,
            Error::BufferSize(_) => sys::MCSTAT_EBUFSIZE,
            Error::Corrupt(_) => sys::MCSTAT_ECORRUPT,
            Error::TooBig(_) => sys::MCSTAT_ETOOBIG,
            Error::Callback(_) => sys::MCSTAT_ECALLBACK,
            Error::HeavyTail(_) => sys::MCSTAT_EHEAVYTAIL,
            Error::Other { status, .. } => *status,
        }
    }
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::InvalidArgument(_) => ErrorKind::InvalidArgument,
            Error::TooFewObservations(_) => ErrorKind::TooFewObservations,
            Error::NonFinite(_) => ErrorKind::NonFinite,
            Error::DegenerateData(_) => ErrorKind::DegenerateData,
            Error::OutOfMemory(_) => ErrorKind::OutOfMemory,
            Error::Numerical(_) => ErrorKind::Numerical,
            Error::BufferSize(_) => ErrorKind::BufferSize,
            Error::Corrupt(_) => ErrorKind::Corrupt,
            Error::TooBig(_) => ErrorKind::TooBig,
            Error::Callback(_) => ErrorKind::Callback,
            Error::HeavyTail(_) => ErrorKind::HeavyTail,
            Error::Other { status, .. } => ErrorKind::Other(*status),
        }
    }
    /// The message: libmcstat's sentence for the status, or a more precise
    /// one (a renderer check's refusal: libmcstat's reason, naming the
    /// argument and its value).
    pub fn message(&self) -> &str {
        match self {
            Error::InvalidArgument(m)
            | Error::TooFewObservations(m)
            | Error::NonFinite(m)
            | Error::DegenerateData(m)
            | Error::OutOfMemory(m)
            | Error::Numerical(m)
            | Error::BufferSize(m)
            | Error::Corrupt(m)
            | Error::TooBig(m)
            | Error::Callback(m)
            | Error::HeavyTail(m) => m,
            Error::Other { message, .. } => message,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (mcstat status {})", self.message(), self.status())
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;

pub(crate) fn check(status: c_int) -> Result<()> {
    if status == sys::MCSTAT_OK {
        Ok(())
    } else {
        Err(Error::from_status(status))
    }
}

/// The error of a failing status of a function that gives reasons (the
/// renderer checks): libmcstat's reason (`mcstat_last_error`, thread-local:
/// call this on the thread of the call, before any other call that gives
/// reasons), or the status's sentence when it gave none.
pub(crate) fn refusal(status: c_int) -> Error {
    let why = unsafe { CStr::from_ptr(sys::mcstat_last_error()) }.to_string_lossy();
    if why.is_empty() {
        Error::from_status(status)
    } else {
        Error::with_message(status, why.into_owned())
    }
}

/// A NUL-free C string of a name (the C side refuses what it does not know).
pub(crate) fn c_name(s: &str) -> Result<CString> {
    CString::new(s).map_err(|_| Error::invalid(format!("{s:?} contains a NUL byte")))
}

pub(crate) fn static_str(p: *const c_char) -> Option<&'static str> {
    if p.is_null() {
        None
    } else {
        unsafe { CStr::from_ptr(p) }.to_str().ok()
    }
}

/// Runs one of libmcstat's formatters twice: for the length, then the text.
pub(crate) fn format_with(f: impl Fn(*mut c_char, usize, *mut usize) -> c_int) -> Result<String> {
    let mut len: usize = 0;
    let st = f(ptr::null_mut(), 0, &mut len);
    if st != sys::MCSTAT_OK && st != sys::MCSTAT_EBUFSIZE {
        return Err(Error::from_status(st));
    }
    let mut buf = vec![0u8; len + 1];
    check(f(buf.as_mut_ptr().cast(), buf.len(), ptr::null_mut()))?;
    buf.truncate(len);
    Ok(String::from_utf8_lossy(&buf).into_owned())
}

// ---- versions, GSL, layout -------------------------------------------------------

/// The version of the linked library, "MAJOR.MINOR.PATCH".
pub fn version() -> &'static str {
    static_str(unsafe { sys::mcstat_version() }).unwrap_or("?")
}

/// MAJOR * 10000 + MINOR * 100 + PATCH of the linked library.
pub fn version_number() -> u32 {
    unsafe { sys::mcstat_version_number() }
}

/// Turns GSL's process-wide error handler off (GSL's own calls then return
/// error codes instead of aborting).  mcstat never needs this: it validates
/// before calling GSL.
pub fn gsl_handler_off() {
    unsafe { sys::mcstat_gsl_handler_off() }
}

/// Turns GSL's handler off only if no handler was installed; true if it did.
pub fn gsl_handler_off_if_default() -> bool {
    unsafe { sys::mcstat_gsl_handler_off_if_default() != 0 }
}

/// Checks that the structs this crate passes to libmcstat have the sizes
/// the linked library expects (a mismatched mcstat-sys and library would
/// otherwise corrupt memory): a cheap test a program may run at start-up.
/// `InvalidArgument` names the first struct that differs.
pub fn check_layout() -> Result<()> {
    use std::mem::size_of;
    let sizes: [(&str, usize, usize); 14] = unsafe {
        [
            ("mcstat_moments", size_of::<sys::mcstat_moments>(), sys::mcstat_sizeof_moments()),
            ("mcstat_result", size_of::<sys::mcstat_result>(), sys::mcstat_sizeof_result()),
            ("mcstat_stream", size_of::<sys::mcstat_stream>(), sys::mcstat_sizeof_stream()),
            ("mcstat_ks_options", size_of::<sys::mcstat_ks_options>(), sys::mcstat_sizeof_ks_options()),
            ("mcstat_power_options", size_of::<sys::mcstat_power_options>(), sys::mcstat_sizeof_power_options()),
            ("mcstat_diag_options", size_of::<sys::mcstat_diag_options>(), sys::mcstat_sizeof_diag_options()),
            ("mcstat_diagnostics", size_of::<sys::mcstat_diagnostics>(), sys::mcstat_sizeof_diagnostics()),
            ("mcstat_gof_options", size_of::<sys::mcstat_gof_options>(), sys::mcstat_sizeof_gof_options()),
            ("mcstat_check_options", size_of::<sys::mcstat_check_options>(), sys::mcstat_sizeof_check_options()),
            ("mcstat_check_model", size_of::<sys::mcstat_check_model>(), sys::mcstat_sizeof_check_model()),
            ("mcstat_check_report", size_of::<sys::mcstat_check_report>(), sys::mcstat_sizeof_check_report()),
            ("mcstat_seq_options", size_of::<sys::mcstat_seq_options>(), sys::mcstat_sizeof_seq_options()),
            ("mcstat_seq", size_of::<sys::mcstat_seq>(), sys::mcstat_sizeof_seq()),
            ("serialized mcstat_moments", sys::MCSTAT_MOMENTS_BYTES, sys::mcstat_sizeof_moments_bytes()),
        ]
    };
    for (name, ours, theirs) in sizes {
        if ours != theirs {
            return Err(Error::invalid(format!(
                "{name} is {ours} bytes in mcstat-sys but {theirs} in the linked libmcstat {}",
                version()
            )));
        }
    }
    Ok(())
}

// ---- enums ---------------------------------------------------------------------

/// A claim about the first sample: `Less` means mean(x) < mu0 (or var(x) <
/// sigma2, mean(x) < mean(y), ...); for K-S, x tends to be smaller than y.
/// `Display` gives libmcstat's name ("two-sided", "less", "greater"),
/// `FromStr` parses them (also R's "two.sided").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Alternative {
    #[default]
    TwoSided,
    Less,
    Greater,
}

impl Alternative {
    pub(crate) fn raw(self) -> c_int {
        match self {
            Alternative::TwoSided => sys::MCSTAT_TWO_SIDED,
            Alternative::Less => sys::MCSTAT_LESS,
            Alternative::Greater => sys::MCSTAT_GREATER,
        }
    }
    pub(crate) fn from_raw(v: i32) -> Alternative {
        match v {
            sys::MCSTAT_LESS => Alternative::Less,
            sys::MCSTAT_GREATER => Alternative::Greater,
            _ => Alternative::TwoSided,
        }
    }
}

impl fmt::Display for Alternative {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(static_str(unsafe { sys::mcstat_alternative_name(self.raw()) }).unwrap_or("?"))
    }
}

impl std::str::FromStr for Alternative {
    type Err = Error;
    fn from_str(s: &str) -> Result<Alternative> {
        let c = c_name(s)?;
        let mut v: c_int = -1;
        if unsafe { sys::mcstat_alternative_parse(c.as_ptr(), &mut v) } != sys::MCSTAT_OK {
            return Err(Error::invalid(format!("unknown alternative {s:?} (two-sided, less, greater)")));
        }
        Ok(Alternative::from_raw(v))
    }
}

/// The paper's three-way outcome; `Display` gives "less", "equal", "greater".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Decision {
    Less,
    Equal,
    Greater,
}

impl Decision {
    fn raw(self) -> c_int {
        match self {
            Decision::Less => sys::MCSTAT_DECISION_LESS,
            Decision::Equal => sys::MCSTAT_DECISION_EQUAL,
            Decision::Greater => sys::MCSTAT_DECISION_GREATER,
        }
    }
}

impl fmt::Display for Decision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(static_str(unsafe { sys::mcstat_decision_name(self.raw()) }).unwrap_or("?"))
    }
}

/// Which test produced a result.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Test {
    /// One-sample t.
    T1,
    /// Welch's two-sample t.
    T2,
    /// One-sample chi-squared test of the variance.
    Var1,
    /// Two-sample F test of the ratio of variances.
    Var2,
    /// Two-sample Kolmogorov-Smirnov.
    Ks2,
    /// One-sample equivalence (TOST).
    Equiv1,
    /// Welch two-sample equivalence (TOST).
    Equiv2,
    /// Exact binomial test (also the battery meta-test).
    Binom,
    /// Pearson's chi-squared goodness of fit.
    ChisqGof,
    /// Student's pooled-variance two-sample t.
    T2Pooled,
    /// The paired t (one-sample t on the differences).
    TPaired,
    /// Sequential (anytime-valid) test of a mean ([`SequentialTest`]).
    SeqMean1,
    /// Sequential test of a difference of means.
    SeqMean2,
    /// Sequential test of a variance.
    SeqVar1,
    /// Sequential test of a ratio of variances.
    SeqVar2,
    /// The ratio of two estimators' efficiencies, 1 / (variance x time).
    Efficiency,
    /// A test this crate does not know (a newer library).
    Other(i32),
}

impl Test {
    fn from_raw(v: i32) -> Test {
        match v {
            sys::MCSTAT_TEST_T_1 => Test::T1,
            sys::MCSTAT_TEST_T_2 => Test::T2,
            sys::MCSTAT_TEST_VAR_1 => Test::Var1,
            sys::MCSTAT_TEST_VAR_2 => Test::Var2,
            sys::MCSTAT_TEST_KS_2 => Test::Ks2,
            sys::MCSTAT_TEST_EQUIV_1 => Test::Equiv1,
            sys::MCSTAT_TEST_EQUIV_2 => Test::Equiv2,
            sys::MCSTAT_TEST_BINOM => Test::Binom,
            sys::MCSTAT_TEST_CHISQ_GOF => Test::ChisqGof,
            sys::MCSTAT_TEST_T_2_POOLED => Test::T2Pooled,
            sys::MCSTAT_TEST_T_PAIRED => Test::TPaired,
            sys::MCSTAT_TEST_SEQ_MEAN_1 => Test::SeqMean1,
            sys::MCSTAT_TEST_SEQ_MEAN_2 => Test::SeqMean2,
            sys::MCSTAT_TEST_SEQ_VAR_1 => Test::SeqVar1,
            sys::MCSTAT_TEST_SEQ_VAR_2 => Test::SeqVar2,
            sys::MCSTAT_TEST_EFFICIENCY => Test::Efficiency,
            v => Test::Other(v),
        }
    }
}

/// How the p-value was obtained (`Auto` is a K-S option only: results
/// never carry it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Analytic,
    Auto,
    Exact,
    Simulate,
    Asymptotic,
}

impl Method {
    pub(crate) fn raw(self) -> i32 {
        match self {
            Method::Analytic => sys::MCSTAT_METHOD_ANALYTIC,
            Method::Auto => sys::MCSTAT_METHOD_AUTO,
            Method::Exact => sys::MCSTAT_METHOD_EXACT,
            Method::Simulate => sys::MCSTAT_METHOD_SIMULATE,
            Method::Asymptotic => sys::MCSTAT_METHOD_ASYMPTOTIC,
        }
    }
    fn from_raw(v: i32) -> Method {
        match v {
            sys::MCSTAT_METHOD_EXACT => Method::Exact,
            sys::MCSTAT_METHOD_SIMULATE => Method::Simulate,
            sys::MCSTAT_METHOD_ASYMPTOTIC => Method::Asymptotic,
            sys::MCSTAT_METHOD_AUTO => Method::Auto,
            _ => Method::Analytic,
        }
    }
}

/// The K-S statistic's weight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KsWeight {
    /// Smirnov's D = sup |F - G| (as R and SciPy).
    None,
    /// Canner's [z(1-z)]^(-1/2), the paper's D2.
    Canner,
}

// ---- results -------------------------------------------------------------------

/// The outputs particular to one test (the named unions of `mcstat_result`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Details {
    /// The t, chi-squared and F tests have none.
    None,
    Ks {
        weight: KsWeight,
        /// Monte Carlo standard error of the critical value (0 unless simulated).
        critical_se: f64,
        /// Replicates simulated (0 unless simulated).
        n_sim: u64,
    },
    Tost {
        /// t for H1: mean > lower bound, and its one-sided p-value.
        t_lower: f64,
        p_lower: f64,
        /// t for H1: mean < upper bound, and its one-sided p-value.
        t_upper: f64,
        p_upper: f64,
        /// The bounds tested (mu0 + lower, mu0 + upper for one sample).
        lower: f64,
        upper: f64,
    },
    Binom {
        /// log(p-value), finite where the p-value underflows to 0.
        log_p_value: f64,
    },
    ChisqGof {
        /// Cells after pooling.
        cells: u32,
        /// Parameters estimated from the counts.
        n_estimated: u32,
        /// Cells given.
        cells_given: u64,
        /// Smallest expected count after pooling.
        min_expected: f64,
        /// The pooling threshold, `None` when pooling was off.
        pool_below: Option<f64>,
    },
    /// A sequential test at its last look ([`SequentialTest`]).
    Sequential {
        /// Continuing, or the first (final) decision.
        outcome: SeqOutcome,
        /// Why no decision is allowed at the last look (empty when none).
        hold: SeqHold,
        /// Pushes so far.
        looks: u64,
        /// n (of x) at the look that decided; `None` while continuing.
        n_decided: Option<u64>,
        /// The z of the last look; `None` while held (`statistic()` is then NaN).
        z: Option<f64>,
        /// Log of the e-value at the last look; `None` while held.
        log_e: Option<f64>,
        /// Its running maximum over the looks (p-value = min(1,
        /// exp(-log_e_max))); `None` before the first look that was not held.
        log_e_max: Option<f64>,
        /// The equivalence margin; `None` when none.
        eps: Option<f64>,
        /// The n where the confidence sequence is tightest.
        t_opt: f64,
        /// The n the kurtosis gate asks for; `None` when it is open.
        n_gate: Option<f64>,
    },
    /// The ratio of two estimators' efficiencies (`efficiency_test`).
    Efficiency {
        /// s_y^2 / s_x^2: x's advantage in variance.
        var_ratio: f64,
        /// Mean time per sample of y / of x: x's advantage in time.
        time_ratio: f64,
        /// Delta-method standard errors of log s_x^2, log s_y^2, log tau_x, log tau_y.
        se_log_var_x: f64,
        se_log_var_y: f64,
        se_log_time_x: f64,
        se_log_time_y: f64,
        /// Timed batches of x and of y.
        batches_x: u32,
        batches_y: u32,
    },
}

/// A test's result: a copy of libmcstat's `mcstat_result`.  Fields that do
/// not apply to the test are `None` or left out of the slices (a t test has
/// one degree of freedom, a K-S test none); infinities are meaningful (the
/// open end of a one-sided interval).  `Display` prints the R-style block
/// with the data named "x" and "y"; [`TestResult::format`] names them.
#[derive(Clone, Copy, Debug)]
pub struct TestResult {
    raw: sys::mcstat_result,
}

fn some(v: f64) -> Option<f64> {
    if v.is_nan() {
        None
    } else {
        Some(v)
    }
}

fn pair(v: [f64; 2]) -> Option<(f64, f64)> {
    if v[0].is_nan() || v[1].is_nan() {
        None
    } else {
        Some((v[0], v[1]))
    }
}

/// The leading values that are not NaN.
fn leading(v: &[f64]) -> &[f64] {
    &v[..v.iter().position(|x| x.is_nan()).unwrap_or(v.len())]
}

impl TestResult {
    pub(crate) fn from_raw(raw: sys::mcstat_result) -> TestResult {
        TestResult { raw }
    }
    /// The C struct, NaN placeholders and all.
    pub fn raw(&self) -> &sys::mcstat_result {
        &self.raw
    }
    pub fn test(&self) -> Test {
        Test::from_raw(self.raw.test)
    }
    pub fn method(&self) -> Method {
        Method::from_raw(self.raw.method)
    }
    pub fn alternative(&self) -> Alternative {
        Alternative::from_raw(self.raw.alternative)
    }
    /// t, X-squared, F, the K-S statistic (D or Canner's D2), the count of
    /// a binomial test, the z of a sequential test's last look (NaN while
    /// the test holds: read [`Details::Sequential`]'s `z` instead).
    pub fn statistic(&self) -> f64 {
        self.raw.statistic
    }
    /// Degrees of freedom: one (t, Welch, chi-squared, TOST, GOF), two (F)
    /// or none (K-S, binomial).
    pub fn df(&self) -> &[f64] {
        leading(&self.raw.df)
    }
    pub fn p_value(&self) -> f64 {
        self.raw.p_value
    }
    /// Monte Carlo standard error of a simulated p-value; 0 when exact.
    pub fn p_value_se(&self) -> f64 {
        self.raw.p_value_se
    }
    /// The (1 - alpha) confidence interval (1 - 2 alpha for TOST); `None`
    /// for K-S and goodness of fit, and for rows computed without intervals.
    pub fn conf_int(&self) -> Option<(f64, f64)> {
        pair(self.raw.conf_int)
    }
    /// mean of x (and of y); variance of x; ratio of variances; x/n.
    /// Empty for K-S and goodness of fit.
    pub fn estimate(&self) -> &[f64] {
        leading(&self.raw.estimate)
    }
    /// mu0, sigma0^2, the ratio or p under H0; `None` for K-S and GOF.
    pub fn null_value(&self) -> Option<f64> {
        some(self.raw.null_value)
    }
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    /// Reject when the statistic is below `.0` or above `.1` (an infinite
    /// bound for a one-sided test); `None` when not computed (K-S with
    /// `critical: false`, rows without intervals).
    pub fn critical(&self) -> Option<(f64, f64)> {
        pair(self.raw.critical)
    }
    /// The estimate's standard error (t tests and TOST); `None` otherwise.
    pub fn std_error(&self) -> Option<f64> {
        some(self.raw.std_error)
    }
    /// Sample sizes: one for one-sample tests, two for two-sample tests.
    pub fn n(&self) -> &[u64] {
        let k = if self.raw.n[1] == 0 { 1 } else { 2 };
        &self.raw.n[..k]
    }
    pub fn reject(&self) -> bool {
        self.raw.reject != 0
    }
    pub fn decision(&self) -> Decision {
        match self.raw.decision {
            d if d < 0 => Decision::Less,
            0 => Decision::Equal,
            _ => Decision::Greater,
        }
    }
    /// The per-test outputs of K-S, TOST, binomial, GOF and sequential results.
    pub fn details(&self) -> Details {
        let r = &self.raw;
        match self.test() {
            Test::Ks2 => Details::Ks {
                weight: if r.ints().ks_weight == sys::MCSTAT_KS_WEIGHT_NONE { KsWeight::None } else { KsWeight::Canner },
                critical_se: r.ks().ks_critical_se,
                n_sim: r.ks().ks_n_sim as u64,
            },
            Test::Equiv1 | Test::Equiv2 => {
                let t = r.tost();
                Details::Tost {
                    t_lower: t.tost_t_lower,
                    p_lower: t.tost_p_lower,
                    t_upper: t.tost_t_upper,
                    p_upper: t.tost_p_upper,
                    lower: t.tost_lower,
                    upper: t.tost_upper,
                }
            }
            Test::Binom => Details::Binom { log_p_value: r.binom().binom_log_p_value },
            Test::ChisqGof => {
                let c = r.chisq();
                Details::ChisqGof {
                    cells: r.ints().chisq_cells as u32,
                    n_estimated: r.ints().chisq_n_estimated as u32,
                    cells_given: c.chisq_cells_given as u64,
                    min_expected: c.chisq_min_expected,
                    pool_below: if c.chisq_pool_below > 0.0 { Some(c.chisq_pool_below) } else { None },
                }
            }
            Test::SeqMean1 | Test::SeqMean2 | Test::SeqVar1 | Test::SeqVar2 => {
                let (i, q) = (r.ints_seq(), r.seq());
                let finite = |v: f64| if v.is_finite() { Some(v) } else { None };
                Details::Sequential {
                    outcome: SeqOutcome::from_raw(i.seq_state, r.decision),
                    hold: SeqHold(i.seq_hold as u32),
                    looks: q.seq_looks as u64,
                    n_decided: if i.seq_state == sys::MCSTAT_SEQ_DECIDED { Some(q.seq_n_decided as u64) } else { None },
                    z: some(r.statistic),
                    log_e: finite(q.seq_log_e),
                    log_e_max: finite(q.seq_log_e_max),
                    eps: if q.seq_eps > 0.0 { Some(q.seq_eps) } else { None },
                    t_opt: q.seq_t_opt,
                    n_gate: if q.seq_n_gate > 0.0 { Some(q.seq_n_gate) } else { None },
                }
            }
            Test::Efficiency => {
                let e = r.eff();
                let k = r.eff_ints();
                Details::Efficiency {
                    var_ratio: e.eff_var_ratio,
                    time_ratio: e.eff_time_ratio,
                    se_log_var_x: e.eff_se_log_var_x,
                    se_log_var_y: e.eff_se_log_var_y,
                    se_log_time_x: e.eff_se_log_time_x,
                    se_log_time_y: e.eff_se_log_time_y,
                    batches_x: k.eff_batches_x as u32,
                    batches_y: k.eff_batches_y as u32,
                }
            }
            _ => Details::None,
        }
    }
    /// The natural logarithm of the p-value, finite wherever the tail is
    /// representable in log, also where `p_value()` underflows to 0.
    pub fn log_p_value(&self) -> Result<f64> {
        let mut v = 0.0;
        check(unsafe { sys::mcstat_result_log_p_value(&self.raw, &mut v) })?;
        Ok(v)
    }
    /// The confidence interval at `confidence_level` in (0, 1) instead of
    /// 1 - alpha (one-sided alternatives keep their infinite end).  An error
    /// for tests without a parameter interval (K-S, goodness of fit).
    pub fn conf_int_at(&self, confidence_level: f64) -> Result<(f64, f64)> {
        let mut ci = [0.0f64; 2];
        check(unsafe { sys::mcstat_result_conf_int(&self.raw, confidence_level, ci.as_mut_ptr()) })?;
        Ok((ci[0], ci[1]))
    }

    /// The R-style block (R's print.htest plus a "decision at alpha" line),
    /// with the data named `x_name` and `y_name`.
    pub fn try_format(&self, x_name: &str, y_name: &str) -> Result<String> {
        let xn = c_name(x_name)?;
        let yn = c_name(y_name)?;
        format_with(|buf, size, len| unsafe { sys::mcstat_result_format(&self.raw, xn.as_ptr(), yn.as_ptr(), buf, size, len) })
    }
    /// As [`TestResult::try_format`]; NUL bytes in the names are dropped.
    pub fn format(&self, x_name: &str, y_name: &str) -> String {
        self.try_format(&x_name.replace('\0', ""), &y_name.replace('\0', ""))
            .unwrap_or_else(|e| format!("<mcstat result: {e}>"))
    }
}

impl fmt::Display for TestResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.try_format("x", "y").map_err(|_| fmt::Error)?)
    }
}

pub(crate) fn run(f: impl FnOnce(*mut sys::mcstat_result) -> c_int) -> Result<TestResult> {
    let mut raw = std::mem::MaybeUninit::<sys::mcstat_result>::zeroed();
    check(f(raw.as_mut_ptr()))?;
    Ok(TestResult { raw: unsafe { raw.assume_init() } })
}

/// [`run`] for the calls that give reasons (the t and variance tests): a
/// refusal carries libmcstat's reason ([`refusal`]).
pub(crate) fn run_reasons(f: impl FnOnce(*mut sys::mcstat_result) -> c_int) -> Result<TestResult> {
    let mut raw = std::mem::MaybeUninit::<sys::mcstat_result>::zeroed();
    let status = f(raw.as_mut_ptr());
    if status != 0 {
        return Err(refusal(status));
    }
    Ok(TestResult { raw: unsafe { raw.assume_init() } })
}

// ---- the tests on slices -------------------------------------------------------

/// One-sample t test of mean(x) against `mu0`.
pub fn t_test_1(x: &[f64], mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_t_test_1(x.as_ptr(), x.len(), mu0, alternative.raw(), alpha, out) })
}

/// Welch's two-sample t test of mean(x) - mean(y) against `mu0`.
pub fn t_test_2(x: &[f64], y: &[f64], mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_t_test_2(x.as_ptr(), x.len(), y.as_ptr(), y.len(), mu0, alternative.raw(), alpha, out) })
}

/// Student's pooled-variance two-sample t test of mean(x) - mean(y) against
/// `mu0` (R's `t.test(var.equal = TRUE)`, SciPy's `ttest_ind` default).
pub fn t_test_2_pooled(x: &[f64], y: &[f64], mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe {
        sys::mcstat_t_test_2_pooled(x.as_ptr(), x.len(), y.as_ptr(), y.len(), mu0, alternative.raw(), alpha, out)
    })
}

/// The paired t test of mean(x - y) against `mu0` (R's `t.test(paired =
/// TRUE)`, SciPy's `ttest_rel`); x and y must have the same length.
pub fn t_test_paired(x: &[f64], y: &[f64], mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    if x.len() != y.len() {
        return Err(Error::with_message(
            sys::MCSTAT_EINVAL,
            format!("paired samples differ in length: x has {}, y has {}", x.len(), y.len()),
        ));
    }
    run_reasons(|out| unsafe { sys::mcstat_t_test_paired(x.as_ptr(), y.as_ptr(), x.len(), mu0, alternative.raw(), alpha, out) })
}

/// One-sample chi-squared test of var(x) against `sigma2`.
pub fn var_test_1(x: &[f64], sigma2: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_var_test_1(x.as_ptr(), x.len(), sigma2, alternative.raw(), alpha, out) })
}

/// Two-sample F test of var(x)/var(y) against `ratio`.
pub fn var_test_2(x: &[f64], y: &[f64], ratio: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_var_test_2(x.as_ptr(), x.len(), y.as_ptr(), y.len(), ratio, alternative.raw(), alpha, out) })
}

// ---- equivalence (TOST) ---------------------------------------------------------

/// Is mean(x) within [mu0 + lower, mu0 + upper]?  Two one-sided t tests at
/// `alpha` each (alpha in (0, 0.5)); `reject()` means EQUIVALENT, and
/// [`Details::Tost`] holds both one-sided tests.
pub fn equivalence_test_1(x: &[f64], mu0: f64, lower: f64, upper: f64, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_equivalence_test_1(x.as_ptr(), x.len(), mu0, lower, upper, alpha, out) })
}

/// [`equivalence_test_1`] on an accumulator.
pub fn equivalence_test_1_moments(x: &Moments, mu0: f64, lower: f64, upper: f64, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_equivalence_test_1_moments(x.raw(), mu0, lower, upper, alpha, out) })
}

/// Is mean(x) - mean(y) within [lower, upper]?  (Welch: unequal variances.)
pub fn equivalence_test_2(x: &[f64], y: &[f64], lower: f64, upper: f64, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_equivalence_test_2(x.as_ptr(), x.len(), y.as_ptr(), y.len(), lower, upper, alpha, out) })
}

/// [`equivalence_test_2`] on accumulators.
pub fn equivalence_test_2_moments(x: &Moments, y: &Moments, lower: f64, upper: f64, alpha: f64) -> Result<TestResult> {
    run(|out| unsafe { sys::mcstat_equivalence_test_2_moments(x.raw(), y.raw(), lower, upper, alpha, out) })
}

// The README's Rust blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;
