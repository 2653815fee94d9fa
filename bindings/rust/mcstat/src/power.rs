//! Power and sample size (experimental in libmcstat): given all but one of
//! n, effect, alpha and power, find the missing one (as R's power.t.test).
use crate::{check, format_with, sys, Alternative, Error, Result};
use std::fmt;
use std::mem::size_of;

/// The design whose power is computed (not the same numbering as [`crate::Test`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PowerTest {
    /// One-sample t: effect d = (mean - mu0)/sd.
    #[default]
    T1,
    /// Two-sample t with n per group and a common sd: d = (mean_x - mean_y)/sd.
    T2,
    /// Welch's t with nx = n, ny = n_ratio n, sd_y = sd_ratio sd_x.
    Welch,
    /// Chi-squared test of a variance: rho = sigma^2/sigma0^2.
    Var1,
    /// F test, nx = n, ny = n_ratio n: rho = (var_x/var_y)/ratio0.
    Var2,
}

impl PowerTest {
    fn raw(self) -> i32 {
        match self {
            PowerTest::T1 => sys::MCSTAT_POWER_T_1,
            PowerTest::T2 => sys::MCSTAT_POWER_T_2,
            PowerTest::Welch => sys::MCSTAT_POWER_WELCH,
            PowerTest::Var1 => sys::MCSTAT_POWER_VAR_1,
            PowerTest::Var2 => sys::MCSTAT_POWER_VAR_2,
        }
    }
}

/// A power calculation: exactly one of `n`, `effect`, `alpha`, `power` is
/// `None` for [`Power::solve`]; [`Power::compute`] needs n, effect and
/// alpha.  `Default` is libmcstat's: one-sample t, two-sided, strict,
/// alpha 0.05, ratios 1, n, effect and power unset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Power {
    pub test: PowerTest,
    pub alternative: Alternative,
    /// Two-sided: count rejections in both tails (R's strict = TRUE).
    pub strict: bool,
    /// Observations (per group for T2, of x for Welch and Var2), >= 2.
    pub n: Option<f64>,
    /// Welch, Var2: ny = n_ratio n.
    pub n_ratio: f64,
    /// Welch: sd_y / sd_x.
    pub sd_ratio: f64,
    /// d (t tests) or rho (variance tests, > 0).
    pub effect: Option<f64>,
    pub alpha: Option<f64>,
    pub power: Option<f64>,
}

fn c_defaults() -> sys::mcstat_power_options {
    let mut o = std::mem::MaybeUninit::<sys::mcstat_power_options>::zeroed();
    unsafe {
        let st = sys::mcstat_power_options_init_size(o.as_mut_ptr(), size_of::<sys::mcstat_power_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for Power {
    fn default() -> Self {
        let o = c_defaults();
        Power {
            test: PowerTest::T1,
            alternative: Alternative::from_raw(o.alternative),
            strict: o.strict != 0,
            n: None,
            n_ratio: o.n_ratio,
            sd_ratio: o.sd_ratio,
            effect: None,
            alpha: Some(o.alpha),
            power: None,
        }
    }
}

impl Power {
    fn raw(&self) -> sys::mcstat_power_options {
        let mut o = c_defaults();
        o.test = self.test.raw();
        o.alternative = self.alternative.raw();
        o.strict = self.strict as i32;
        // an unset field is 0, which libmcstat refuses wherever it is needed
        o.n = self.n.unwrap_or(0.0);
        o.n_ratio = self.n_ratio;
        o.sd_ratio = self.sd_ratio;
        o.effect = self.effect.unwrap_or(0.0);
        o.alpha = self.alpha.unwrap_or(0.0);
        o.power = self.power.unwrap_or(0.0);
        o
    }
    /// The power at n, effect and alpha.
    pub fn compute(&self) -> Result<f64> {
        for (name, v) in [("n", self.n), ("effect", self.effect), ("alpha", self.alpha)] {
            if v.is_none() {
                return Err(Error::invalid(format!("power: {name} is needed to compute the power")));
            }
        }
        let mut p = f64::NAN;
        check(unsafe { sys::mcstat_power_compute(&self.raw(), &mut p) })?;
        Ok(p)
    }
    /// Solves for the one field that is `None`.  Solving for n gives the
    /// smallest integer n reaching the power, and the power at that n.
    pub fn solve(&self) -> Result<PowerSolution> {
        let unset: Vec<(&str, i32)> = [
            ("n", self.n, sys::MCSTAT_POWER_SOLVE_N),
            ("effect", self.effect, sys::MCSTAT_POWER_SOLVE_EFFECT),
            ("alpha", self.alpha, sys::MCSTAT_POWER_SOLVE_ALPHA),
            ("power", self.power, sys::MCSTAT_POWER_SOLVE_POWER),
        ]
        .iter()
        .filter(|(_, v, _)| v.is_none())
        .map(|&(name, _, u)| (name, u))
        .collect();
        if unset.len() != 1 {
            let names: Vec<&str> = unset.iter().map(|u| u.0).collect();
            return Err(Error::invalid(format!(
                "power: exactly one of n, effect, alpha and power must be None to solve (unset: {names:?})"
            )));
        }
        let o = self.raw();
        let mut out = o;
        check(unsafe { sys::mcstat_power_solve(&o, unset[0].1, &mut out) })?;
        Ok(PowerSolution { raw: out })
    }
}

/// A solved power calculation; `Display` is R's print.power.htest block.
#[derive(Clone, Copy, Debug)]
pub struct PowerSolution {
    raw: sys::mcstat_power_options,
}

impl PowerSolution {
    pub fn n(&self) -> f64 {
        self.raw.n
    }
    pub fn effect(&self) -> f64 {
        self.raw.effect
    }
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    pub fn power(&self) -> f64 {
        self.raw.power
    }
    pub fn raw(&self) -> &sys::mcstat_power_options {
        &self.raw
    }
    pub fn try_format(&self) -> Result<String> {
        format_with(|buf, size, len| unsafe { sys::mcstat_power_format(&self.raw, buf, size, len) })
    }
}

impl fmt::Display for PowerSolution {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.try_format().map_err(|_| fmt::Error)?)
    }
}
