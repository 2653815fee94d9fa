//! Tail probabilities and quantiles of the t, chi-squared and F
//! distributions.  `upper` selects the tail: false gives `P[X <= x]`, true
//! gives `P[X > x]`; a quantile solves that tail's probability = p.  Log
//! versions stay finite where the probability underflows.
use crate::{check, sys, Result};

fn call(f: impl FnOnce(*mut f64) -> i32) -> Result<f64> {
    let mut v = f64::NAN;
    check(f(&mut v))?;
    Ok(v)
}
pub fn t_cdf(x: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_t_cdf(x, df, upper as i32, o) })
}
pub fn t_logcdf(x: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_t_logcdf(x, df, upper as i32, o) })
}
pub fn t_quantile(p: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_t_quantile(p, df, upper as i32, o) })
}
/// `t_quantile(p, df[i], upper)` for every `df[i]` at one level, to the same
/// accuracy, fast where many df differ (per-pixel critical values).  An
/// error if one fails (NaN or non-positive df): the first one's.
pub fn t_quantiles(p: f64, df: &[f64], upper: bool) -> Result<Vec<f64>> {
    let mut x = vec![f64::NAN; df.len()];
    check(unsafe { sys::mcstat_t_quantiles(p, df.as_ptr(), df.len(), upper as i32, x.as_mut_ptr()) })?;
    Ok(x)
}
pub fn chisq_cdf(x: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_chisq_cdf(x, df, upper as i32, o) })
}
pub fn chisq_logcdf(x: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_chisq_logcdf(x, df, upper as i32, o) })
}
pub fn chisq_quantile(p: f64, df: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_chisq_quantile(p, df, upper as i32, o) })
}
pub fn f_cdf(x: f64, df1: f64, df2: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_f_cdf(x, df1, df2, upper as i32, o) })
}
pub fn f_logcdf(x: f64, df1: f64, df2: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_f_logcdf(x, df1, df2, upper as i32, o) })
}
pub fn f_quantile(p: f64, df1: f64, df2: f64, upper: bool) -> Result<f64> {
    call(|o| unsafe { sys::mcstat_f_quantile(p, df1, df2, upper as i32, o) })
}
