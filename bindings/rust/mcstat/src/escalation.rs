//! Escalation instead of reruns (`mcstat/adjust.h`): the two-stage test
//! of Bauer & Koehne (1994), for a test suite that would otherwise rerun a
//! failed statistical test until it passes and so lose its error rate.
use std::os::raw::c_int;

use crate::{check, sys, Error, Result};

/// What an [`Escalation`] design says about the p-values it was given.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EscalationDecision {
    /// No evidence against H0 at the design's level.
    Pass,
    /// H0 rejected at the design's level.
    Reject,
    /// Stage 1 was inconclusive: run stage 2 on fresh samples and call
    /// [`Escalation::decide2`] with both p-values.
    Continue,
}

impl EscalationDecision {
    fn from_raw(v: c_int) -> Result<EscalationDecision> {
        match v {
            sys::MCSTAT_ESCALATION_PASS => Ok(EscalationDecision::Pass),
            sys::MCSTAT_ESCALATION_REJECT => Ok(EscalationDecision::Reject),
            sys::MCSTAT_ESCALATION_CONTINUE => Ok(EscalationDecision::Continue),
            v => Err(Error::invalid(format!("libmcstat returned an unknown escalation decision {v}"))),
        }
    }
}

/// A two-stage design of level `alpha`, made by [`Escalation::new`].
///
/// Stage 1 tests n1 samples and gives p1: p1 <= `alpha1` rejects, p1 >
/// `alpha0` passes, and in between the test continues on fresh samples (an
/// independent stage 2 of any size, chosen after seeing stage 1) that give
/// p2; stage 2 rejects when Fisher's product p1 p2 <= `c`.  `c` spends what
/// stage 1 left of `alpha` over the escalation band, so the whole test has
/// level `alpha` for uniform p-values and at most `alpha` for valid
/// (super-uniform) ones, discrete tests' included, provided the two stages
/// use independent random numbers.  A correct test escalates with
/// probability `alpha0 - alpha1`; a borderline error is judged on the
/// samples of both stages.  mcstat.h derives the numbers.
///
/// The fields are read through the accessors: a design is only ever one
/// libmcstat made, so [`decide`](Escalation::decide) cannot be handed a
/// forged one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Escalation {
    raw: sys::mcstat_escalation,
}

impl Escalation {
    /// The design of level `alpha` in (0, 1) that spends `alpha1 = share1
    /// alpha` at stage 1 (`share1` in (0, 1)) and escalates up to `alpha0`
    /// in (alpha1, 1].  `InvalidArgument` for arguments outside those
    /// ranges, NaN included, and where `alpha0` is so close to `alpha1` that
    /// stage 2 could not spend the rest (`c` would exceed `alpha1`).
    pub fn new(alpha: f64, share1: f64, alpha0: f64) -> Result<Escalation> {
        let mut raw = sys::mcstat_escalation::default();
        check(unsafe { sys::mcstat_escalation_design(alpha, share1, alpha0, &mut raw) })?;
        Ok(Escalation { raw })
    }

    /// The level of the whole two-stage test.
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    /// Stage 1 rejects when p1 <= alpha1.
    pub fn alpha1(&self) -> f64 {
        self.raw.alpha1
    }
    /// Stage 1 passes when p1 > alpha0, and continues when alpha1 < p1 <= alpha0.
    pub fn alpha0(&self) -> f64 {
        self.raw.alpha0
    }
    /// Stage 2 rejects when p1 p2 <= c (c <= alpha1).
    pub fn c(&self) -> f64 {
        self.raw.c
    }
    /// The C struct, for calls through [`sys`].
    pub fn raw(&self) -> &sys::mcstat_escalation {
        &self.raw
    }

    fn decide_raw(&self, p1: f64, p2: f64) -> Result<EscalationDecision> {
        let mut d: c_int = -1;
        check(unsafe { sys::mcstat_escalation_decide(&self.raw, p1, p2, &mut d) })?;
        EscalationDecision::from_raw(d)
    }

    /// Stage 1's decision on its p-value `p1` in [0, 1]: `Reject`, `Pass`,
    /// or `Continue` to stage 2.  `InvalidArgument` for `p1` outside [0, 1],
    /// NaN included.
    pub fn decide(&self, p1: f64) -> Result<EscalationDecision> {
        self.decide_raw(p1, f64::NAN)
    }

    /// The final decision, `Reject` or `Pass`, on stage 1's `p1` and stage
    /// 2's `p2` (both in [0, 1]; stage 2 on fresh samples).  Valid only when
    /// stage 1 said `Continue`: `InvalidArgument` when [`decide`](Escalation::decide)
    /// on `p1` rejects or passes, and for either p-value outside [0, 1], NaN
    /// included.
    pub fn decide2(&self, p1: f64, p2: f64) -> Result<EscalationDecision> {
        // libmcstat reads a NaN p2 as "stage 1 only"; here that is decide's
        if p2.is_nan() {
            return Err(Error::invalid("escalation: stage 2's p-value is NaN"));
        }
        self.decide_raw(p1, p2)
    }
}
