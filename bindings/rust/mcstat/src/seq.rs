//! Sequential, anytime-valid tests (`mcstat/sequential.h`).
use std::fmt;
use std::mem::{size_of, MaybeUninit};

use crate::{check, run, static_str, sys, Alternative, Decision, Error, Moments, Result, Stream, TestResult};

/// What a [`SequentialTest`] tests; `Display` gives libmcstat's name
/// ("mean", "mean2", "var", "var2").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeqKind {
    /// The mean of x against `null_value` (mu0).
    Mean,
    /// mean(x) - mean(y) against `null_value` (a difference).
    Mean2,
    /// The variance of x against `null_value` (sigma0^2 > 0).
    Var,
    /// var(x) / var(y) against `null_value` (a ratio > 0).
    Var2,
}

impl SeqKind {
    fn raw(self) -> i32 {
        match self {
            SeqKind::Mean => sys::MCSTAT_SEQ_MEAN_1,
            SeqKind::Mean2 => sys::MCSTAT_SEQ_MEAN_2,
            SeqKind::Var => sys::MCSTAT_SEQ_VAR_1,
            SeqKind::Var2 => sys::MCSTAT_SEQ_VAR_2,
        }
    }
    fn from_raw(v: i32) -> SeqKind {
        match v {
            sys::MCSTAT_SEQ_MEAN_2 => SeqKind::Mean2,
            sys::MCSTAT_SEQ_VAR_1 => SeqKind::Var,
            sys::MCSTAT_SEQ_VAR_2 => SeqKind::Var2,
            _ => SeqKind::Mean,
        }
    }
    /// Two samples (x and y): `Mean2` and `Var2`.
    pub fn two_sample(self) -> bool {
        matches!(self, SeqKind::Mean2 | SeqKind::Var2)
    }
}

impl fmt::Display for SeqKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(static_str(unsafe { sys::mcstat_seq_kind_name(self.raw()) }).unwrap_or("?"))
    }
}

/// Where a sequential test stands: still continuing, or its first decision,
/// which is final.  `Display` gives "continue", "less", "equal", "greater".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeqOutcome {
    /// Not decided yet (held, or not enough evidence).
    Continue,
    /// Rejected H0: the parameter is below the null value.
    Less,
    /// Equivalence shown: the confidence sequence lies within null +- eps.
    Equal,
    /// Rejected H0: the parameter is above the null value.
    Greater,
}

impl SeqOutcome {
    pub(crate) fn from_raw(state: i32, decision: i32) -> SeqOutcome {
        if state != sys::MCSTAT_SEQ_DECIDED {
            return SeqOutcome::Continue;
        }
        match decision {
            d if d < 0 => SeqOutcome::Less,
            0 => SeqOutcome::Equal,
            _ => SeqOutcome::Greater,
        }
    }
    /// The decision, `None` while continuing.
    pub fn decision(self) -> Option<Decision> {
        match self {
            SeqOutcome::Continue => None,
            SeqOutcome::Less => Some(Decision::Less),
            SeqOutcome::Equal => Some(Decision::Equal),
            SeqOutcome::Greater => Some(Decision::Greater),
        }
    }
}

impl fmt::Display for SeqOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.decision() {
            None => f.write_str("continue"),
            Some(d) => d.fmt(f),
        }
    }
}

/// Why a sequential test may not decide at its last look (the
/// `MCSTAT_SEQ_HOLD_*` bits); empty when it may.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SeqHold(pub(crate) u32);

impl SeqHold {
    /// A sample has fewer than `min_n` values.
    pub fn few(self) -> bool {
        self.0 & sys::MCSTAT_SEQ_HOLD_FEW != 0
    }
    /// A sample has no spread yet.
    pub fn degenerate(self) -> bool {
        self.0 & sys::MCSTAT_SEQ_HOLD_DEGENERATE != 0
    }
    /// A sample's n is below `kurtosis_gate` times its kurtosis (rare
    /// large values not yet seen often enough).
    pub fn kurtosis(self) -> bool {
        self.0 & sys::MCSTAT_SEQ_HOLD_KURTOSIS != 0
    }
    /// No reason: the test may decide.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }
    /// The C bits.
    pub fn bits(self) -> u32 {
        self.0
    }
}

/// Options of a [`SequentialTest`]; `Default` is libmcstat's
/// (`MCSTAT_SEQ_OPTIONS_INIT`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeqOptions {
    pub alternative: Alternative,
    /// In (0, 1); the error rate over every look.
    pub alpha: f64,
    /// Equivalence margin >= 0 on a mean (two-sided `Mean`/`Mean2` only):
    /// the test also stops with "equal" once the sequence lies within
    /// null +- eps; 0: none.
    pub eps: f64,
    /// Observations (per sample) where the sequence is tightest, > 0.
    pub t_opt: f64,
    /// Hold while n < kurtosis_gate * kurtosis, >= 0 (0: off).
    pub kurtosis_gate: f64,
    /// The variance's upper-bound factor, >= 0 (0: plain s^2).
    pub var_ucb_z: f64,
    /// Hold while a sample has fewer values, >= 2.
    pub min_n: u64,
}

fn c_options_defaults() -> sys::mcstat_seq_options {
    let mut o = MaybeUninit::<sys::mcstat_seq_options>::zeroed();
    unsafe {
        let st = sys::mcstat_seq_options_init_size(o.as_mut_ptr(), size_of::<sys::mcstat_seq_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for SeqOptions {
    fn default() -> Self {
        let o = c_options_defaults();
        SeqOptions {
            alternative: Alternative::from_raw(o.alternative),
            alpha: o.alpha,
            eps: o.eps,
            t_opt: o.t_opt,
            kurtosis_gate: o.kurtosis_gate,
            var_ucb_z: o.var_ucb_z,
            min_n: o.min_n,
        }
    }
}

impl SeqOptions {
    fn to_c(self) -> sys::mcstat_seq_options {
        let mut o = c_options_defaults();
        o.alternative = self.alternative.raw();
        o.alpha = self.alpha;
        o.eps = self.eps;
        o.t_opt = self.t_opt;
        o.kurtosis_gate = self.kurtosis_gate;
        o.var_ucb_z = self.var_ucb_z;
        o.min_n = self.min_n;
        o
    }
    /// The first argument libmcstat refuses, named (for the error message).
    fn diagnose(&self, kind: SeqKind, null_value: f64) -> String {
        let var = matches!(kind, SeqKind::Var | SeqKind::Var2);
        if !(self.alpha > 0.0 && self.alpha < 1.0) {
            format!("alpha = {} is not in (0, 1)", self.alpha)
        } else if !(self.eps >= 0.0 && self.eps.is_finite()) {
            format!("eps = {} is not finite and >= 0", self.eps)
        } else if self.eps > 0.0 && (var || self.alternative != Alternative::TwoSided) {
            format!("eps = {} needs a two-sided test of a mean (kind {kind}, {})", self.eps, self.alternative)
        } else if !(self.t_opt > 0.0 && self.t_opt.is_finite()) {
            format!("t_opt = {} is not finite and > 0", self.t_opt)
        } else if !(self.kurtosis_gate >= 0.0 && self.kurtosis_gate.is_finite()) {
            format!("kurtosis_gate = {} is not finite and >= 0", self.kurtosis_gate)
        } else if !(self.var_ucb_z >= 0.0 && self.var_ucb_z.is_finite()) {
            format!("var_ucb_z = {} is not finite and >= 0", self.var_ucb_z)
        } else if self.min_n < 2 {
            format!("min_n = {} is below 2", self.min_n)
        } else if !null_value.is_finite() || (var && null_value <= 0.0) {
            format!("null_value = {null_value} is not finite{}", if var { " and > 0" } else { "" })
        } else {
            "invalid sequential test options".to_string()
        }
    }
}

/// A sequential, anytime-valid test (`mcstat_seq`, 448 bytes of plain data,
/// owned by value): push a batch after each frame and look at it every
/// time; it stops ([`SequentialTest::outcome`]) with "less"/"greater" once
/// H0 is rejected, or "equal" once the bias is shown below eps, and its
/// error rate over all the looks stays at most alpha.
///
/// While a sample is too small, without spread, or its kurtosis says its
/// rare large values have not been seen often enough, the test holds
/// ([`SequentialTest::hold`]); [`SequentialTest::finish`] says
/// [`Error::HeavyTail`] when the kurtosis gate was still closed at the end.
/// `Display` prints libmcstat's R-style block.
///
/// ```
/// use mcstat::{SeqOptions, SeqOutcome, SequentialTest};
/// let mut t = SequentialTest::mean(0.0, &SeqOptions::default())?;
/// let mut u: u64 = 42;
/// while t.outcome() == SeqOutcome::Continue && t.n() < 100_000 {
///     // a frame of 100 uniform values on [0, 1): the mean is 0.5, not 0
///     let frame: Vec<f64> = (0..100)
///         .map(|_| {
///             u ^= u << 13;
///             u ^= u >> 7;
///             u ^= u << 17;
///             (u >> 11) as f64 / (1u64 << 53) as f64
///         })
///         .collect();
///     t.push(&frame)?;
/// }
/// assert_eq!(t.outcome(), SeqOutcome::Greater);
/// println!("{t}");
/// # Ok::<(), mcstat::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct SequentialTest {
    raw: sys::mcstat_seq,
}

impl SequentialTest {
    /// An empty test of `kind` against `null_value` (a mean, a difference,
    /// a variance or a ratio).  InvalidArgument names the bad argument.
    pub fn new(kind: SeqKind, null_value: f64, options: &SeqOptions) -> Result<SequentialTest> {
        let mut raw = MaybeUninit::<sys::mcstat_seq>::zeroed();
        let o = options.to_c();
        let st = unsafe { sys::mcstat_seq_init(raw.as_mut_ptr(), kind.raw(), null_value, &o) };
        if st == sys::MCSTAT_EINVAL {
            return Err(Error::invalid(options.diagnose(kind, null_value)));
        }
        check(st)?;
        Ok(SequentialTest { raw: unsafe { raw.assume_init() } })
    }
    /// The mean of x against `mu0`.
    pub fn mean(mu0: f64, options: &SeqOptions) -> Result<SequentialTest> {
        SequentialTest::new(SeqKind::Mean, mu0, options)
    }
    /// mean(x) - mean(y) against `difference`.
    pub fn mean2(difference: f64, options: &SeqOptions) -> Result<SequentialTest> {
        SequentialTest::new(SeqKind::Mean2, difference, options)
    }
    /// The variance of x against `sigma2` > 0.
    pub fn var(sigma2: f64, options: &SeqOptions) -> Result<SequentialTest> {
        SequentialTest::new(SeqKind::Var, sigma2, options)
    }
    /// var(x) / var(y) against `ratio` > 0.
    pub fn var2(ratio: f64, options: &SeqOptions) -> Result<SequentialTest> {
        SequentialTest::new(SeqKind::Var2, ratio, options)
    }

    fn one_sample(&self, call: &str) -> Result<()> {
        if self.kind().two_sample() {
            return Err(Error::invalid(format!("{call} needs a one-sample test (mean, var); this one is {}", self.kind())));
        }
        Ok(())
    }
    fn two_samples(&self, call: &str) -> Result<()> {
        if !self.kind().two_sample() {
            return Err(Error::invalid(format!("{call} needs a two-sample test (mean2, var2); this one is {}", self.kind())));
        }
        Ok(())
    }

    /// One look after adding a batch of x (one-sample tests).  NonFinite
    /// for NaN or infinity in the batch; the test is unchanged on an error.
    pub fn push(&mut self, x: &[f64]) -> Result<()> {
        self.one_sample("push")?;
        check(unsafe { sys::mcstat_seq_push_array(&mut self.raw, x.as_ptr(), x.len()) })
    }
    /// One look after adding a batch given as an accumulator (e.g. the
    /// per-thread accumulators of a frame, merged).
    pub fn push_moments(&mut self, batch: &Moments) -> Result<()> {
        self.one_sample("push_moments")?;
        check(unsafe { sys::mcstat_seq_push_moments(&mut self.raw, batch.raw()) })
    }
    /// One look after adding a stream's values (a frame's merged
    /// [`Stream`]); NonFinite if the stream has seen NaN or infinity.
    pub fn push_stream(&mut self, frame: &Stream) -> Result<()> {
        self.one_sample("push_stream")?;
        check(unsafe { sys::mcstat_seq_push_stream(&mut self.raw, frame.raw()) })
    }
    /// One look after adding a batch of each sample (two-sample tests;
    /// either may be empty).
    pub fn push2(&mut self, x: &[f64], y: &[f64]) -> Result<()> {
        self.two_samples("push2")?;
        check(unsafe { sys::mcstat_seq_push_2_array(&mut self.raw, x.as_ptr(), x.len(), y.as_ptr(), y.len()) })
    }
    /// [`SequentialTest::push2`] on accumulators.
    pub fn push_moments2(&mut self, x: &Moments, y: &Moments) -> Result<()> {
        self.two_samples("push_moments2")?;
        check(unsafe { sys::mcstat_seq_push_2_moments(&mut self.raw, x.raw(), y.raw()) })
    }

    /// The test at the last look: the anytime p-value, the confidence
    /// sequence as `conf_int()`, `reject()` once decided "less"/"greater",
    /// and [`crate::Details::Sequential`].
    pub fn result(&self) -> TestResult {
        // mcstat_seq_result fails only on an uninitialised test, which
        // this type cannot hold
        run(|out| unsafe { sys::mcstat_seq_result(&self.raw, out) }).expect("an initialised mcstat_seq")
    }
    /// The test at the end of the caller's budget: the result when decided,
    /// or undecided with data that allowed a decision (more samples may
    /// decide); [`Error::HeavyTail`] when the kurtosis gate was closed at
    /// the last look (the result is still [`SequentialTest::result`]).
    pub fn finish(&self) -> Result<TestResult> {
        let mut slot = None;
        let st = run(|out| {
            let st = unsafe { sys::mcstat_seq_finish(&self.raw, out) };
            if st == sys::MCSTAT_EHEAVYTAIL {
                slot = Some(unsafe { *out });
                return sys::MCSTAT_OK;
            }
            st
        })?;
        match slot {
            None => Ok(st),
            Some(r) => {
                let gate = unsafe { r.per_test.seq.seq_n_gate };
                Err(Error::HeavyTail(format!(
                    "the tails never allowed a decision: {} values, the kurtosis gate asks for {gate:.0}",
                    r.n[0] + r.n[1]
                )))
            }
        }
    }

    pub fn kind(&self) -> SeqKind {
        SeqKind::from_raw(self.raw.kind)
    }
    /// Continuing, or the first decision (final).
    pub fn outcome(&self) -> SeqOutcome {
        SeqOutcome::from_raw(self.raw.state, self.raw.decision)
    }
    pub fn is_decided(&self) -> bool {
        self.raw.state == sys::MCSTAT_SEQ_DECIDED
    }
    /// Why no decision was allowed at the last look.
    pub fn hold(&self) -> SeqHold {
        SeqHold(self.raw.hold)
    }
    /// Pushes so far.
    pub fn looks(&self) -> u64 {
        self.raw.looks
    }
    /// Values of x pushed so far.
    pub fn n(&self) -> u64 {
        self.raw.x.n
    }
    /// Values of y pushed so far (0 for one-sample tests).
    pub fn n_y(&self) -> u64 {
        self.raw.y.n
    }
    /// n of x at the deciding look; `None` while continuing.
    pub fn n_decided(&self) -> Option<u64> {
        if self.is_decided() {
            Some(self.raw.n_decided)
        } else {
            None
        }
    }
    pub fn null_value(&self) -> f64 {
        self.raw.null_value
    }
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    /// The C struct (plain data; a copy keeps the state).
    pub fn raw(&self) -> &sys::mcstat_seq {
        &self.raw
    }
}

impl fmt::Display for SequentialTest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.result().fmt(f)
    }
}
