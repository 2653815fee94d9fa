//! Multiple testing: adjusted p-values, as R's p.adjust.  NaN entries are
//! R's NA: they stay NaN and are not counted among the tests.
use crate::{c_name, check, static_str, sys, Error, Result};
use std::fmt;
use std::os::raw::c_int;

/// R's p.adjust methods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PAdjustMethod {
    /// Unchanged.
    None,
    /// min(1, n p) (family-wise error rate).
    Bonferroni,
    /// Step-down Bonferroni (FWER, any dependence).
    Holm,
    /// Step-up (FWER, independent or positively dependent tests).
    Hochberg,
    /// Simes closed testing (FWER, as Hochberg; more powerful).
    Hommel,
    /// Benjamini-Hochberg (false discovery rate).
    BH,
    /// Benjamini-Yekutieli (FDR, any dependence).
    BY,
    /// e-BH on the e-values p^(-9/10) / 10 (FDR, any dependence; less
    /// powerful than BY on the same p-values): see [`e_bh`].
    EBH,
}

impl PAdjustMethod {
    fn raw(self) -> c_int {
        match self {
            PAdjustMethod::None => sys::MCSTAT_P_ADJUST_NONE,
            PAdjustMethod::Bonferroni => sys::MCSTAT_P_ADJUST_BONFERRONI,
            PAdjustMethod::Holm => sys::MCSTAT_P_ADJUST_HOLM,
            PAdjustMethod::Hochberg => sys::MCSTAT_P_ADJUST_HOCHBERG,
            PAdjustMethod::Hommel => sys::MCSTAT_P_ADJUST_HOMMEL,
            PAdjustMethod::BH => sys::MCSTAT_P_ADJUST_BH,
            PAdjustMethod::BY => sys::MCSTAT_P_ADJUST_BY,
            PAdjustMethod::EBH => sys::MCSTAT_P_ADJUST_E_BH,
        }
    }
    pub const ALL: [PAdjustMethod; 8] = [
        PAdjustMethod::None,
        PAdjustMethod::Bonferroni,
        PAdjustMethod::Holm,
        PAdjustMethod::Hochberg,
        PAdjustMethod::Hommel,
        PAdjustMethod::BH,
        PAdjustMethod::BY,
        PAdjustMethod::EBH,
    ];
    /// Bytes of scratch the adjustment of n p-values needs (0 for none and
    /// bonferroni).  TooBig when it does not fit in a usize.
    pub fn work_size(self, n: usize) -> Result<usize> {
        let mut bytes = 0usize;
        check(unsafe { sys::mcstat_p_adjust_work_size(n, self.raw(), &mut bytes) })?;
        Ok(bytes)
    }
}

impl fmt::Display for PAdjustMethod {
    /// R's name: "none", "bonferroni", "holm", "hochberg", "hommel", "BH", "BY";
    /// and "e-BH".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(static_str(unsafe { sys::mcstat_p_adjust_method_name(self.raw()) }).unwrap_or("?"))
    }
}

impl std::str::FromStr for PAdjustMethod {
    type Err = Error;
    /// R's names (also "bh", "fdr", "by"), "e-BH" ("ebh", "e_bh").
    fn from_str(s: &str) -> Result<PAdjustMethod> {
        let c = c_name(s)?;
        let mut v: c_int = -1;
        if unsafe { sys::mcstat_p_adjust_method_parse(c.as_ptr(), &mut v) } != sys::MCSTAT_OK {
            return Err(Error::invalid(format!("unknown p.adjust method {s:?}")));
        }
        PAdjustMethod::ALL
            .iter()
            .copied()
            .find(|m| m.raw() == v)
            .ok_or_else(|| Error::invalid(format!("p.adjust method {s:?} parsed to unknown value {v}")))
    }
}

/// Reusable scratch for [`p_adjust_in_place`] (aligned for double).
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    buf: Vec<f64>,
}

impl Workspace {
    pub fn new() -> Workspace {
        Workspace::default()
    }
    fn reserve(&mut self, bytes: usize) -> (*mut std::os::raw::c_void, usize) {
        let words = (bytes + 7) / 8;
        if self.buf.len() < words {
            self.buf.resize(words, 0.0);
        }
        if self.buf.is_empty() {
            (std::ptr::null_mut(), 0)
        } else {
            (self.buf.as_mut_ptr().cast(), self.buf.len() * 8)
        }
    }
}

/// The adjusted p-values of `p` (each in [0, 1] or NaN; InvalidArgument otherwise).
pub fn p_adjust(p: &[f64], method: PAdjustMethod) -> Result<Vec<f64>> {
    let mut out = p.to_vec();
    p_adjust_in_place(&mut out, method, &mut Workspace::new())?;
    Ok(out)
}

/// Adjusts `p` in place with scratch from `work` (grown as needed, kept
/// for the next call: no allocation once it is large enough).  Nothing is
/// written on error.
pub fn p_adjust_in_place(p: &mut [f64], method: PAdjustMethod, work: &mut Workspace) -> Result<()> {
    let bytes = method.work_size(p.len())?;
    let (ptr, size) = work.reserve(bytes);
    let data = p.as_mut_ptr();
    // in place: libmcstat allows adjusted == p
    check(unsafe { sys::mcstat_p_adjust(data, p.len(), method.raw(), ptr, size, data) })
}

/// e-BH (Wang & Ramdas 2022) on e-values (each in [0, inf] or NaN;
/// InvalidArgument for a negative one): FDR control under any dependence.
/// Reject where the value returned is <= alpha; NaN entries stay NaN and
/// are not counted; a single e-value gives min(1, 1/e).
pub fn e_bh(e: &[f64]) -> Result<Vec<f64>> {
    let mut out = e.to_vec();
    let bytes = PAdjustMethod::EBH.work_size(e.len())?;
    let mut work = Workspace::new();
    let (ptr, size) = work.reserve(bytes);
    let data = out.as_mut_ptr();
    // in place: libmcstat allows adjusted == e
    check(unsafe { sys::mcstat_e_bh(data, out.len(), ptr, size, data) })?;
    Ok(out)
}
