//! Per-pixel rows: the tests once per row of a matrix of values or of an
//! array of accumulators.  Row i's result is bit for bit the single test on
//! row i; a row that fails does not stop the others, and its status is
//! kept with the results.
use crate::{sys, Alternative, Error, Moments, Result, TestResult};
use std::os::raw::{c_int, c_uint};

/// Rows of values in a slice: row i holds the `n` contiguous values at
/// `data[i * stride ..]`.  The constructor checks that every row lies
/// inside `data`.
#[derive(Clone, Copy, Debug)]
pub struct Matrix<'a> {
    data: &'a [f64],
    rows: usize,
    n: usize,
    stride: usize,
}

impl<'a> Matrix<'a> {
    /// `rows` rows of `n` values, one after the other (stride n).
    pub fn new(data: &'a [f64], rows: usize, n: usize) -> Result<Matrix<'a>> {
        Matrix::with_stride(data, rows, n, n)
    }
    /// `rows` rows of `n` values starting every `stride` values.
    pub fn with_stride(data: &'a [f64], rows: usize, n: usize, stride: usize) -> Result<Matrix<'a>> {
        let needed = if rows == 0 {
            Some(0)
        } else {
            (rows - 1).checked_mul(stride).and_then(|v| v.checked_add(n))
        };
        match needed {
            Some(k) if k <= data.len() => Ok(Matrix { data, rows, n, stride }),
            _ => Err(Error::invalid(format!(
                "a matrix of {rows} rows of {n} values with stride {stride} does not fit in {} values",
                data.len()
            ))),
        }
    }
    pub fn data(&self) -> &'a [f64] {
        self.data
    }
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Values per row.
    pub fn n(&self) -> usize {
        self.n
    }
    pub fn stride(&self) -> usize {
        self.stride
    }
}

/// How the rows are computed; `Default`: with intervals, NaN an error.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RowFlags {
    /// Skip critical values and confidence intervals (they are then
    /// `None`; p-value, reject and decision remain): the cheap path when
    /// only the decision map is wanted.
    pub no_intervals: bool,
    /// Skip NaN values in each row (infinities remain an error); matrices only.
    pub omit_nan: bool,
}

impl RowFlags {
    pub(crate) fn bits(self) -> c_uint {
        (if self.no_intervals { sys::MCSTAT_ROWS_NO_INTERVALS } else { 0 })
            | (if self.omit_nan { sys::MCSTAT_ROWS_OMIT_NAN } else { 0 })
    }
}

// A status the library never writes: marks rows it did not reach.
const PENDING: i32 = i32::MIN;

/// The status of every row: which succeeded, and why the others failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Statuses {
    codes: Vec<i32>,
}

impl Statuses {
    pub(crate) fn pending(rows: usize) -> Statuses {
        Statuses { codes: vec![PENDING; rows] }
    }
    pub(crate) fn as_mut_ptr(&mut self) -> *mut i32 {
        self.codes.as_mut_ptr()
    }
    /// The call's own status: Err when the rows were not reached (invalid
    /// arguments, nothing written), Ok when every row has its status.
    pub(crate) fn finish(&self, st: c_int) -> Result<()> {
        if st != sys::MCSTAT_OK && self.codes.first().map_or(true, |&c| c == PENDING) {
            return Err(Error::from_status(st));
        }
        if self.codes.contains(&PENDING) {
            return Err(Error::with_message(st.max(sys::MCSTAT_EINVAL), "libmcstat left rows without a status"));
        }
        Ok(())
    }
    pub fn len(&self) -> usize {
        self.codes.len()
    }
    pub fn is_empty(&self) -> bool {
        self.codes.is_empty()
    }
    /// Row i's status (panics if i is out of range).
    pub fn get(&self, i: usize) -> Result<()> {
        crate::check(self.codes[i])
    }
    pub fn all_ok(&self) -> bool {
        self.codes.iter().all(|&c| c == sys::MCSTAT_OK)
    }
    /// The rows that failed, with their errors.
    pub fn failed(&self) -> Vec<(usize, Error)> {
        self.codes
            .iter()
            .enumerate()
            .filter(|(_, &c)| c != sys::MCSTAT_OK)
            .map(|(i, &c)| (i, Error::from_status(c)))
            .collect()
    }
    /// The C status codes (0 for success).
    pub fn codes(&self) -> &[i32] {
        &self.codes
    }
}

/// One result per row, and each row's status.
#[derive(Clone, Debug)]
pub struct RowResults {
    raw: Vec<sys::mcstat_result>,
    status: Statuses,
}

impl RowResults {
    pub fn len(&self) -> usize {
        self.raw.len()
    }
    pub fn is_empty(&self) -> bool {
        self.raw.is_empty()
    }
    /// Row i's result, or the error that row met (panics if i is out of range).
    pub fn get(&self, i: usize) -> Result<TestResult> {
        self.status.get(i)?;
        Ok(TestResult::from_raw(self.raw[i]))
    }
    pub fn iter(&self) -> impl Iterator<Item = Result<TestResult>> + '_ {
        (0..self.len()).map(move |i| self.get(i))
    }
    pub fn statuses(&self) -> &Statuses {
        &self.status
    }
    /// The rows' p-values, in the form [`crate::p_adjust()`] takes: a failed
    /// row's is NaN, R's NA, which p_adjust leaves NaN and does not count.
    pub fn p_values(&self) -> Vec<f64> {
        self.raw
            .iter()
            .zip(self.status.codes())
            .map(|(r, &c)| if c == sys::MCSTAT_OK { r.p_value } else { f64::NAN })
            .collect()
    }
}

fn rows_call(rows: usize, f: impl FnOnce(*mut sys::mcstat_result, *mut i32) -> c_int) -> Result<RowResults> {
    let mut raw: Vec<sys::mcstat_result> = vec![unsafe { std::mem::zeroed() }; rows];
    let mut status = Statuses::pending(rows);
    let st = f(raw.as_mut_ptr(), status.as_mut_ptr());
    status.finish(st)?;
    Ok(RowResults { raw, status })
}

fn same_rows(x: usize, y: usize) -> Result<()> {
    if x == y {
        Ok(())
    } else {
        Err(Error::invalid(format!("x has {x} rows and y {y}: rows pair up")))
    }
}

fn moments_ptr(m: &[Moments]) -> *const sys::mcstat_moments {
    // Moments is repr(transparent) over mcstat_moments
    m.as_ptr() as *const sys::mcstat_moments
}

/// The one-sample t test of every row of `x` against `mu0`.
pub fn t_test_1_matrix(x: &Matrix, mu0: f64, alternative: Alternative, alpha: f64, flags: RowFlags) -> Result<RowResults> {
    rows_call(x.rows(), |out, status| unsafe {
        sys::mcstat_t_test_1_matrix(
            x.data().as_ptr(),
            x.n(),
            x.stride(),
            x.rows(),
            mu0,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

/// Welch's t test of row i of `x` against row i of `y`.
pub fn t_test_2_matrix(
    x: &Matrix,
    y: &Matrix,
    mu0: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<RowResults> {
    same_rows(x.rows(), y.rows())?;
    rows_call(x.rows(), |out, status| unsafe {
        sys::mcstat_t_test_2_matrix(
            x.data().as_ptr(),
            x.n(),
            x.stride(),
            y.data().as_ptr(),
            y.n(),
            y.stride(),
            x.rows(),
            mu0,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

/// The chi-squared test of every row's variance against `sigma2`.
pub fn var_test_1_matrix(x: &Matrix, sigma2: f64, alternative: Alternative, alpha: f64, flags: RowFlags) -> Result<RowResults> {
    rows_call(x.rows(), |out, status| unsafe {
        sys::mcstat_var_test_1_matrix(
            x.data().as_ptr(),
            x.n(),
            x.stride(),
            x.rows(),
            sigma2,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

/// The F test of row i of `x` against row i of `y`.
pub fn var_test_2_matrix(
    x: &Matrix,
    y: &Matrix,
    ratio: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<RowResults> {
    same_rows(x.rows(), y.rows())?;
    rows_call(x.rows(), |out, status| unsafe {
        sys::mcstat_var_test_2_matrix(
            x.data().as_ptr(),
            x.n(),
            x.stride(),
            y.data().as_ptr(),
            y.n(),
            y.stride(),
            x.rows(),
            ratio,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

/// The one-sample t test of every accumulator (`flags.omit_nan` has no
/// meaning here: InvalidArgument).
pub fn t_test_1_moments_rows(x: &[Moments], mu0: f64, alternative: Alternative, alpha: f64, flags: RowFlags) -> Result<RowResults> {
    rows_call(x.len(), |out, status| unsafe {
        sys::mcstat_t_test_1_moments_rows(moments_ptr(x), x.len(), mu0, alternative.raw(), alpha, flags.bits(), out, status)
    })
}

/// Welch's t test of `x[i]` against `y[i]`.
pub fn t_test_2_moments_rows(
    x: &[Moments],
    y: &[Moments],
    mu0: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<RowResults> {
    same_rows(x.len(), y.len())?;
    rows_call(x.len(), |out, status| unsafe {
        sys::mcstat_t_test_2_moments_rows(
            moments_ptr(x),
            moments_ptr(y),
            x.len(),
            mu0,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

/// The chi-squared test of every accumulator's variance against `sigma2`.
pub fn var_test_1_moments_rows(
    x: &[Moments],
    sigma2: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<RowResults> {
    rows_call(x.len(), |out, status| unsafe {
        sys::mcstat_var_test_1_moments_rows(moments_ptr(x), x.len(), sigma2, alternative.raw(), alpha, flags.bits(), out, status)
    })
}

/// The F test of `x[i]` against `y[i]`.
pub fn var_test_2_moments_rows(
    x: &[Moments],
    y: &[Moments],
    ratio: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<RowResults> {
    same_rows(x.len(), y.len())?;
    rows_call(x.len(), |out, status| unsafe {
        sys::mcstat_var_test_2_moments_rows(
            moments_ptr(x),
            moments_ptr(y),
            x.len(),
            ratio,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
            status,
        )
    })
}

// ---- Welch per pixel on seeds-major images ---------------------------------------

/// The outputs of [`t_test_2_pixels`], one entry per pixel.  A pixel that
/// could not be tested (too few values, NaN or Inf, constant in both
/// samples) has its status (a nonzero `mcstat_status`) in `status` and NaN
/// elsewhere; the intervals are `None` with `no_intervals`.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelResults {
    pub p_value: Vec<f64>,
    pub statistic: Vec<f64>,
    pub df: Vec<f64>,
    pub mean_x: Vec<f64>,
    pub mean_y: Vec<f64>,
    /// Welch's standard error of mean_x - mean_y.
    pub std_error: Vec<f64>,
    pub conf_lo: Option<Vec<f64>>,
    pub conf_hi: Option<Vec<f64>>,
    pub status: Vec<i32>,
}

/// Seeds-major images of `pixels` pixels of `channels` values: the sizes
/// must fit in the slice and the weights match the channels.
fn pixel_sizes(len: usize, seeds: usize, pixels: usize, channels: usize, weights: Option<&[f64]>) -> Result<()> {
    match weights {
        None if channels != 1 => return Err(Error::invalid(format!("{channels} channels need one weight each"))),
        Some(w) if w.len() != channels => {
            return Err(Error::invalid(format!("{} weights for {channels} channels", w.len())))
        }
        _ => {}
    }
    match pixels.checked_mul(channels).and_then(|p| p.checked_mul(seeds)) {
        Some(k) if k <= len => Ok(()),
        _ => Err(Error::invalid(format!(
            "{seeds} seeds of {pixels} pixels x {channels} channels do not fit in {len} values"
        ))),
    }
}

fn run_pixels(
    pixels: usize,
    flags: RowFlags,
    call: impl Fn(usize, usize, *const sys::mcstat_pixels_out) -> c_int,
) -> Result<PixelResults> {
    let null = std::ptr::null_mut();
    let none = sys::mcstat_pixels_out {
        p_value: null,
        statistic: null,
        df: null,
        mean_x: null,
        mean_y: null,
        conf_lo: null,
        conf_hi: null,
        status: std::ptr::null_mut(),
        std_error: null,
    };
    crate::check(call(0, 0, &none))?; // the arguments, on an empty range
    let intervals = !flags.no_intervals;
    let mut r = PixelResults {
        p_value: vec![f64::NAN; pixels],
        statistic: vec![f64::NAN; pixels],
        df: vec![f64::NAN; pixels],
        mean_x: vec![f64::NAN; pixels],
        mean_y: vec![f64::NAN; pixels],
        std_error: vec![f64::NAN; pixels],
        conf_lo: if intervals { Some(vec![f64::NAN; pixels]) } else { None },
        conf_hi: if intervals { Some(vec![f64::NAN; pixels]) } else { None },
        status: vec![PENDING; pixels],
    };
    let out = sys::mcstat_pixels_out {
        p_value: r.p_value.as_mut_ptr(),
        statistic: r.statistic.as_mut_ptr(),
        df: r.df.as_mut_ptr(),
        mean_x: r.mean_x.as_mut_ptr(),
        mean_y: r.mean_y.as_mut_ptr(),
        conf_lo: r.conf_lo.as_mut().map_or(null, |v| v.as_mut_ptr()),
        conf_hi: r.conf_hi.as_mut().map_or(null, |v| v.as_mut_ptr()),
        status: r.status.as_mut_ptr(),
        std_error: r.std_error.as_mut_ptr(),
    };
    call(0, pixels, &out); // per-pixel failures are in r.status
    Ok(r)
}

/// Welch's test per pixel of `x` against `y`, images written seeds-major
/// as renderers write them: seed s of pixel i, channel c is
/// `x[s * pixels * channels + i * channels + c]` (`nx` seeds of x, `ny` of
/// y).  With `weights` (one per channel) the tested value is
/// `sum_c weights[c] x[..]`, formed in double (luminance from RGB);
/// `None` with one channel tests the values themselves.  Each pixel agrees
/// with [`crate::t_test_2`] on its two samples (libmcstat's
/// `mcstat_t_test_2_pixels`).  `Err` only for bad arguments.
#[allow(clippy::too_many_arguments)]
pub fn t_test_2_pixels(
    x: &[f64],
    nx: usize,
    y: &[f64],
    ny: usize,
    pixels: usize,
    channels: usize,
    weights: Option<&[f64]>,
    mu0: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<PixelResults> {
    pixel_sizes(x.len(), nx, pixels, channels, weights)?;
    pixel_sizes(y.len(), ny, pixels, channels, weights)?;
    let w = weights.map_or(std::ptr::null(), |w| w.as_ptr());
    run_pixels(pixels, flags, |b, e, out| unsafe {
        sys::mcstat_t_test_2_pixels(
            x.as_ptr(),
            nx,
            pixels * channels,
            y.as_ptr(),
            ny,
            pixels * channels,
            channels,
            w,
            b,
            e,
            mu0,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
        )
    })
}

/// [`t_test_2_pixels`] on float32 images, read as they are.
#[allow(clippy::too_many_arguments)]
pub fn t_test_2_pixels_f32(
    x: &[f32],
    nx: usize,
    y: &[f32],
    ny: usize,
    pixels: usize,
    channels: usize,
    weights: Option<&[f64]>,
    mu0: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
) -> Result<PixelResults> {
    pixel_sizes(x.len(), nx, pixels, channels, weights)?;
    pixel_sizes(y.len(), ny, pixels, channels, weights)?;
    let w = weights.map_or(std::ptr::null(), |w| w.as_ptr());
    run_pixels(pixels, flags, |b, e, out| unsafe {
        sys::mcstat_t_test_2_pixels_f32(
            x.as_ptr(),
            nx,
            pixels * channels,
            y.as_ptr(),
            ny,
            pixels * channels,
            channels,
            w,
            b,
            e,
            mu0,
            alternative.raw(),
            alpha,
            flags.bits(),
            out,
        )
    })
}
