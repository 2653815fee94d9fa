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
    let none = sys::mcstat_pixels_out::init();
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
        estimate: r.mean_x.as_mut_ptr(),
        estimate2: r.mean_y.as_mut_ptr(),
        conf_lo: r.conf_lo.as_mut().map_or(null, |v| v.as_mut_ptr()),
        conf_hi: r.conf_hi.as_mut().map_or(null, |v| v.as_mut_ptr()),
        status: r.status.as_mut_ptr(),
        std_error: r.std_error.as_mut_ptr(),
        ..sys::mcstat_pixels_out::init()
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

// ---- any test per pixel, any layout: mcstat_pixels_test --------------------------

/// The values of one side of [`pixels_test`], float64 or float32 (read as
/// they are, each converted to double exactly).
#[derive(Clone, Copy, Debug)]
pub enum PixelData<'a> {
    F64(&'a [f64]),
    F32(&'a [f32]),
}

impl PixelData<'_> {
    fn len(&self) -> usize {
        match self {
            PixelData::F64(v) => v.len(),
            PixelData::F32(v) => v.len(),
        }
    }
}

/// Where the values of each pixel are: value `s` of pixel `i` starts at
/// element `s * value_stride + i * pixel_stride` of `data` and is the
/// weighted sum of `channels` consecutive elements there (`weights`, one
/// per channel; `None` with one channel: the element itself).
#[derive(Clone, Copy, Debug)]
pub struct Pixels<'a> {
    pub data: PixelData<'a>,
    /// Values per pixel.
    pub n: usize,
    pub value_stride: usize,
    pub pixel_stride: usize,
    pub channels: usize,
    pub weights: Option<&'a [f64]>,
}

impl<'a> Pixels<'a> {
    /// A seeds-major stack `(n, pixels)` as renderers write it: value s of
    /// pixel i at `s * pixels + i`.
    pub fn seeds_major(data: PixelData<'a>, n: usize, pixels: usize) -> Self {
        Pixels { data, n, value_stride: pixels, pixel_stride: 1, channels: 1, weights: None }
    }

    /// Rows of `n` values per pixel `(pixels, n)`: value s of pixel i at `i * n + s`.
    pub fn rows(data: PixelData<'a>, n: usize) -> Self {
        Pixels { data, n, value_stride: 1, pixel_stride: n, channels: 1, weights: None }
    }

    /// Every element `pixels` pixels address lies in the slice.
    fn check(&self, pixels: usize) -> Result<()> {
        match self.weights {
            None if self.channels != 1 => {
                return Err(Error::invalid(format!("{} channels need one weight each", self.channels)))
            }
            Some(w) if w.len() != self.channels => {
                return Err(Error::invalid(format!("{} weights for {} channels", w.len(), self.channels)))
            }
            _ => {}
        }
        if self.channels == 0 {
            return Err(Error::invalid("channels must be at least 1"));
        }
        if pixels == 0 || self.n == 0 {
            return Ok(());
        }
        let last = (self.n - 1)
            .checked_mul(self.value_stride)
            .and_then(|a| (pixels - 1).checked_mul(self.pixel_stride).and_then(|b| a.checked_add(b)))
            .and_then(|a| a.checked_add(self.channels - 1));
        match last {
            Some(l) if l < self.data.len() => Ok(()),
            _ => Err(Error::invalid(format!(
                "{} values of {} pixels (strides {} and {}, {} channels) do not fit in {} elements",
                self.n,
                pixels,
                self.value_stride,
                self.pixel_stride,
                self.channels,
                self.data.len()
            ))),
        }
    }

    fn raw(&self) -> sys::mcstat_pixels_in {
        let (type_, data) = match self.data {
            PixelData::F64(v) => (sys::MCSTAT_VALUE_FLOAT64, v.as_ptr() as *const std::os::raw::c_void),
            PixelData::F32(v) => (sys::MCSTAT_VALUE_FLOAT32, v.as_ptr() as *const std::os::raw::c_void),
        };
        sys::mcstat_pixels_in {
            type_,
            data,
            n: self.n,
            value_stride: self.value_stride,
            pixel_stride: self.pixel_stride,
            channels: self.channels,
            weights: self.weights.map_or(std::ptr::null(), |w| w.as_ptr()),
            ..sys::mcstat_pixels_in::init()
        }
    }
}

/// The tests of [`pixels_test`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelTest {
    /// One-sample t of x's mean against the null value.
    T1,
    /// Welch's t of mean(x) - mean(y).
    T2,
    /// Student's pooled t.
    T2Pooled,
    /// Paired t of mean(x - y) (equal n).
    TPaired,
    /// Chi-squared test of x's variance.
    Var1,
    /// F test of var(x) / var(y).
    Var2,
}

impl PixelTest {
    fn raw(self) -> c_int {
        match self {
            PixelTest::T1 => sys::MCSTAT_TEST_T_1,
            PixelTest::T2 => sys::MCSTAT_TEST_T_2,
            PixelTest::T2Pooled => sys::MCSTAT_TEST_T_2_POOLED,
            PixelTest::TPaired => sys::MCSTAT_TEST_T_PAIRED,
            PixelTest::Var1 => sys::MCSTAT_TEST_VAR_1,
            PixelTest::Var2 => sys::MCSTAT_TEST_VAR_2,
        }
    }

    fn two_sample(self) -> bool {
        !matches!(self, PixelTest::T1 | PixelTest::Var1)
    }
}

/// The outputs of [`pixels_test`], one entry per pixel (mcstat.h's
/// `mcstat_pixels_out`).  A pixel that failed has its status in `status`,
/// NaN elsewhere, decision 0 and sizes 0.  With `no_intervals` the
/// intervals and critical values are NaN.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTestResults {
    pub p_value: Vec<f64>,
    pub statistic: Vec<f64>,
    /// The degrees of freedom (F: the numerator's).
    pub df: Vec<f64>,
    /// F: the denominator's degrees of freedom (NaN for the others).
    pub df2: Vec<f64>,
    /// The single call's `estimate[0]`: x's mean (t tests; paired: of the
    /// differences), x's variance (chi-squared), the ratio (F).
    pub estimate: Vec<f64>,
    /// `estimate[1]`: y's mean (two-sample t; NaN for the others).
    pub estimate2: Vec<f64>,
    pub std_error: Vec<f64>,
    pub conf_lo: Vec<f64>,
    pub conf_hi: Vec<f64>,
    pub critical_lo: Vec<f64>,
    pub critical_hi: Vec<f64>,
    pub status: Vec<i32>,
    /// -1, 0, +1 (`Decision`'s less, equal, greater).
    pub decision: Vec<i8>,
    pub n_x: Vec<u64>,
    pub n_y: Vec<u64>,
}

/// `test` once per pixel `0..pixels` of `x` (and `y` for the two-sample
/// tests; `None` for `T1` and `Var1`), libmcstat's `mcstat_pixels_test`:
/// each pixel's results are the single call's on its values (bit for bit
/// but for Welch's and the variance tests, within the bounds of mcstat.h).
/// `threads` (1..64) threads take the pixels by chunks in turn; results do
/// not depend on it.  `Err` only for bad arguments
/// (slices too short for the strides, weights that do not match the
/// channels, the arguments mcstat_pixels_test refuses); a pixel's failure
/// is its `status`.
#[allow(clippy::too_many_arguments)]
pub fn pixels_test(
    test: PixelTest,
    x: &Pixels<'_>,
    y: Option<&Pixels<'_>>,
    pixels: usize,
    null_value: f64,
    alternative: Alternative,
    alpha: f64,
    flags: RowFlags,
    threads: usize,
) -> Result<PixelTestResults> {
    if test.two_sample() != y.is_some() {
        return Err(Error::invalid(if test.two_sample() {
            "this test needs y"
        } else {
            "a one-sample test takes no y"
        }));
    }
    x.check(pixels)?;
    if let Some(y) = y {
        y.check(pixels)?;
    }
    if threads == 0 || threads > 64 {
        return Err(Error::invalid(format!("threads must be in 1..64, got {threads}")));
    }
    let rx = x.raw();
    let ry = y.map(|y| y.raw());
    let py = ry.as_ref().map_or(std::ptr::null(), |r| r as *const sys::mcstat_pixels_in);
    let mut opt = sys::mcstat_pixels_options::init();
    opt.flags = flags.bits();
    opt.threads = threads as i32;
    let call = |begin: usize, end: usize, out: &sys::mcstat_pixels_out| unsafe {
        sys::mcstat_pixels_test(test.raw(), &rx, py, begin, end, null_value, alternative.raw(), alpha, &opt, out)
    };
    crate::check(call(0, 0, &sys::mcstat_pixels_out::init()))?; // the arguments, on an empty range
    let nan = || vec![f64::NAN; pixels];
    let mut r = PixelTestResults {
        p_value: nan(),
        statistic: nan(),
        df: nan(),
        df2: nan(),
        estimate: nan(),
        estimate2: nan(),
        std_error: nan(),
        conf_lo: nan(),
        conf_hi: nan(),
        critical_lo: nan(),
        critical_hi: nan(),
        status: vec![PENDING; pixels],
        decision: vec![0; pixels],
        n_x: vec![0; pixels],
        n_y: vec![0; pixels],
    };
    let out = sys::mcstat_pixels_out {
        p_value: r.p_value.as_mut_ptr(),
        statistic: r.statistic.as_mut_ptr(),
        df: r.df.as_mut_ptr(),
        df2: r.df2.as_mut_ptr(),
        estimate: r.estimate.as_mut_ptr(),
        estimate2: r.estimate2.as_mut_ptr(),
        std_error: r.std_error.as_mut_ptr(),
        conf_lo: r.conf_lo.as_mut_ptr(),
        conf_hi: r.conf_hi.as_mut_ptr(),
        critical_lo: r.critical_lo.as_mut_ptr(),
        critical_hi: r.critical_hi.as_mut_ptr(),
        status: r.status.as_mut_ptr(),
        decision: r.decision.as_mut_ptr(),
        n_x: r.n_x.as_mut_ptr(),
        n_y: r.n_y.as_mut_ptr(),
        ..sys::mcstat_pixels_out::init()
    };
    call(0, pixels, &out); // per-pixel failures are in r.status
    Ok(r)
}

/// `sizeof` of the per-pixel structs as this libmcstat was built
/// (`mcstat_sizeof_pixels_{in,options,out}`): (in, options, out).
pub fn pixels_struct_sizes() -> (usize, usize, usize) {
    unsafe { (sys::mcstat_sizeof_pixels_in(), sys::mcstat_sizeof_pixels_options(), sys::mcstat_sizeof_pixels_out()) }
}

/// The per-pixel structs' initialisers for a given size (the first `size`
/// bytes of each, as an older caller would have them): libmcstat's
/// `mcstat_pixels_{in,options,out}_init_size`.  `Err` for a size no
/// release had.
pub fn pixels_structs_init_size(
    in_size: usize,
    options_size: usize,
    out_size: usize,
) -> Result<(sys::mcstat_pixels_in, sys::mcstat_pixels_options, sys::mcstat_pixels_out)> {
    let mut a = sys::mcstat_pixels_in::init();
    let mut b = sys::mcstat_pixels_options::init();
    let mut c = sys::mcstat_pixels_out::init();
    unsafe {
        crate::check(sys::mcstat_pixels_in_init_size(&mut a, in_size))?;
        crate::check(sys::mcstat_pixels_options_init_size(&mut b, options_size))?;
        crate::check(sys::mcstat_pixels_out_init_size(&mut c, out_size))?;
    }
    Ok((a, b, c))
}
