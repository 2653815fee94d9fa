//! Accumulators: one sample ([`Moments`]), one per pixel ([`MomentsArray`]),
//! and the per-thread buffer of a renderer ([`Stream`]).
use crate::rows::{Matrix, RowFlags, Statuses};
use crate::{check, run, run_reasons, sys, Alternative, Error, Result, TestResult};
use std::mem::MaybeUninit;
use std::ops::{Deref, DerefMut};

/// Streaming, mergeable moments (`mcstat_moments`, 128 bytes, no
/// allocation): count, mean (double-double), central sums, min and max.
/// The derived quantities are NaN where undefined (the mean of nothing,
/// the variance of one value), as libmcstat returns them.
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub struct Moments {
    raw: sys::mcstat_moments,
}

impl Default for Moments {
    fn default() -> Self {
        Moments::new()
    }
}

impl Moments {
    pub fn new() -> Moments {
        let mut raw = MaybeUninit::<sys::mcstat_moments>::zeroed();
        unsafe {
            sys::mcstat_moments_init(raw.as_mut_ptr());
            Moments { raw: raw.assume_init() }
        }
    }
    /// The accumulator of a summary: n values of mean `mean` whose sum of
    /// squared deviations is `m2` ((n-1) var).  Only n, the mean and M2 are
    /// known: the t and variance tests on it give exactly the summary's
    /// results; skewness, kurtosis, min and max describe a symmetric
    /// two-point stand-in.
    pub fn from_summary(n: u64, mean: f64, m2: f64) -> Result<Moments> {
        let mut m = Moments::new();
        check(unsafe { sys::mcstat_moments_from_summary(n, mean, m2, &mut m.raw) })?;
        Ok(m)
    }
    /// Adds one value (NonFinite for NaN or infinity; `self` unchanged).
    pub fn add(&mut self, x: f64) -> Result<()> {
        check(unsafe { sys::mcstat_moments_add(&mut self.raw, x) })
    }
    /// Adds a slice (NonFinite if any value is NaN or infinite; `self` unchanged).
    pub fn add_slice(&mut self, x: &[f64]) -> Result<()> {
        check(unsafe { sys::mcstat_moments_add_array(&mut self.raw, x.as_ptr(), x.len()) })
    }
    /// Adds a slice skipping NaN values (infinities are still an error);
    /// returns the number skipped.
    pub fn add_slice_omit_nan(&mut self, x: &[f64]) -> Result<usize> {
        let mut omitted = 0usize;
        check(unsafe { sys::mcstat_moments_add_array_omit_nan(&mut self.raw, x.as_ptr(), x.len(), &mut omitted) })?;
        Ok(omitted)
    }
    /// Merges `other` into `self` exactly.
    pub fn merge(&mut self, other: &Moments) -> Result<()> {
        check(unsafe { sys::mcstat_moments_merge(&mut self.raw, &other.raw) })
    }
    pub fn n(&self) -> u64 {
        self.raw.n
    }
    pub fn mean(&self) -> f64 {
        unsafe { sys::mcstat_moments_mean(&self.raw) }
    }
    /// Sample variance M2/(n-1).
    pub fn var(&self) -> f64 {
        unsafe { sys::mcstat_moments_var(&self.raw) }
    }
    pub fn sd(&self) -> f64 {
        unsafe { sys::mcstat_moments_sd(&self.raw) }
    }
    /// g1 = sqrt(n) M3 / M2^1.5.
    pub fn skewness(&self) -> f64 {
        unsafe { sys::mcstat_moments_skewness(&self.raw) }
    }
    /// Excess kurtosis g2 = n M4 / M2^2 - 3.
    pub fn kurtosis(&self) -> f64 {
        unsafe { sys::mcstat_moments_kurtosis(&self.raw) }
    }
    /// The smallest value added (+Inf when empty).
    pub fn min(&self) -> f64 {
        self.raw.min
    }
    /// The largest value added (-Inf when empty).
    pub fn max(&self) -> f64 {
        self.raw.max
    }
    /// The portable, versioned, checksummed serialization (96 bytes).
    pub fn to_bytes(&self) -> [u8; sys::MCSTAT_MOMENTS_BYTES] {
        let mut b = [0u8; sys::MCSTAT_MOMENTS_BYTES];
        // cannot fail: an initialised accumulator, the right size
        let st = unsafe { sys::mcstat_moments_to_bytes(&self.raw, b.as_mut_ptr(), b.len()) };
        debug_assert_eq!(st, sys::MCSTAT_OK);
        b
    }
    /// Corrupt for bytes that are truncated, damaged or of another version.
    pub fn from_bytes(b: &[u8]) -> Result<Moments> {
        let mut m = Moments::new();
        check(unsafe { sys::mcstat_moments_from_bytes(b.as_ptr(), b.len(), &mut m.raw) })?;
        Ok(m)
    }
    pub fn raw(&self) -> &sys::mcstat_moments {
        &self.raw
    }
}

/// One-sample t test on an accumulator.
pub fn t_test_1_moments(x: &Moments, mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_t_test_1_moments(&x.raw, mu0, alternative.raw(), alpha, out) })
}

/// Welch's t test on accumulators.
pub fn t_test_2_moments(x: &Moments, y: &Moments, mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_t_test_2_moments(&x.raw, &y.raw, mu0, alternative.raw(), alpha, out) })
}

/// The efficiency-ratio test: rho = eff(x) / eff(y) = (var_y tau_y) /
/// (var_x tau_x) against `ratio`, from the estimators' samples `x`, `y` and
/// the time per sample of k >= 2 timed batches each (`time_x`, `time_y`);
/// delta-method standard error of log rho without assuming normal data, a
/// t on Satterthwaite's df.  `Greater` means x is the more efficient.
pub fn efficiency_test(
    x: &Moments,
    y: &Moments,
    time_x: &Moments,
    time_y: &Moments,
    ratio: f64,
    alternative: Alternative,
    alpha: f64,
) -> Result<TestResult> {
    run(|out| unsafe {
        sys::mcstat_efficiency_test(&x.raw, &y.raw, &time_x.raw, &time_y.raw, ratio, alternative.raw(), alpha, out)
    })
}

/// Student's pooled-variance t test on accumulators.
pub fn t_test_2_pooled_moments(x: &Moments, y: &Moments, mu0: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_t_test_2_pooled_moments(&x.raw, &y.raw, mu0, alternative.raw(), alpha, out) })
}

/// One-sample chi-squared test on an accumulator.
pub fn var_test_1_moments(x: &Moments, sigma2: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_var_test_1_moments(&x.raw, sigma2, alternative.raw(), alpha, out) })
}

/// F test on accumulators.
pub fn var_test_2_moments(x: &Moments, y: &Moments, ratio: f64, alternative: Alternative, alpha: f64) -> Result<TestResult> {
    run_reasons(|out| unsafe { sys::mcstat_var_test_2_moments(&x.raw, &y.raw, ratio, alternative.raw(), alpha, out) })
}

// ---- arrays of accumulators --------------------------------------------------------

/// One accumulator per pixel: add images (or stacks of images) row-wise,
/// ship them as bytes, merge element-wise, then test every pixel with the
/// `*_moments_rows` functions of [`crate::rows`].  Derefs to `[Moments]`.
#[derive(Clone, Debug, Default)]
pub struct MomentsArray {
    rows: Vec<Moments>,
}

impl MomentsArray {
    /// `rows` empty accumulators.
    pub fn new(rows: usize) -> MomentsArray {
        let mut v: Vec<Moments> = Vec::with_capacity(rows);
        unsafe {
            // Moments is repr(transparent): the C call initialises every element
            let st = sys::mcstat_moments_init_rows(v.as_mut_ptr() as *mut sys::mcstat_moments, rows);
            assert_eq!(st, sys::MCSTAT_OK);
            v.set_len(rows);
        }
        MomentsArray { rows: v }
    }
    /// Adds row i of `x` (its `x.n()` values) to accumulator i; `x` must
    /// have one row per accumulator.  One image with one value per pixel is
    /// a matrix with n = 1; a pixel-major stack of k images, n = k.
    /// `omit_nan` skips NaN values.  A row that fails (NonFinite, TooBig) is
    /// left unchanged and the others are still added: its status is in the
    /// returned [`Statuses`].  Err (nothing changed) for a shape mismatch.
    pub fn add(&mut self, x: &Matrix, omit_nan: bool) -> Result<Statuses> {
        if x.rows() != self.rows.len() {
            return Err(Error::invalid(format!("x has {} rows for {} accumulators", x.rows(), self.rows.len())));
        }
        let flags = RowFlags { omit_nan, ..RowFlags::default() }.bits();
        let mut status = Statuses::pending(self.rows.len());
        let st = unsafe {
            sys::mcstat_moments_add_rows(
                self.rows.as_mut_ptr() as *mut sys::mcstat_moments,
                self.rows.len(),
                x.data().as_ptr(),
                x.n(),
                x.stride(),
                flags,
                status.as_mut_ptr(),
            )
        };
        status.finish(st)?;
        Ok(status)
    }
    /// `self[i]` <- `self[i]` merged with `other[i]`.  Err (nothing changed) for
    /// arrays of different lengths or a count past 2^64 - 1.
    pub fn merge(&mut self, other: &[Moments]) -> Result<()> {
        if other.len() != self.rows.len() {
            return Err(Error::invalid(format!("merging {} accumulators into {}", other.len(), self.rows.len())));
        }
        check(unsafe {
            sys::mcstat_moments_merge_rows(
                self.rows.as_mut_ptr() as *mut sys::mcstat_moments,
                other.as_ptr() as *const sys::mcstat_moments,
                self.rows.len(),
            )
        })
    }
    /// The array as len() * 96 bytes (each record with its own magic,
    /// version and checksum; no header).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = vec![0u8; self.rows.len() * sys::MCSTAT_MOMENTS_BYTES];
        let st = unsafe {
            sys::mcstat_moments_to_bytes_rows(
                self.rows.as_ptr() as *const sys::mcstat_moments,
                self.rows.len(),
                b.as_mut_ptr(),
                b.len(),
            )
        };
        // cannot fail: initialised accumulators, the exact size
        debug_assert_eq!(st, sys::MCSTAT_OK);
        b
    }
    /// Reads the accumulators of [`MomentsArray::to_bytes`]; Corrupt when
    /// the length is not a multiple of 96 or any record is damaged.
    pub fn from_bytes(b: &[u8]) -> Result<MomentsArray> {
        let rows = b.len() / sys::MCSTAT_MOMENTS_BYTES;
        let mut m = MomentsArray::new(rows);
        check(unsafe {
            sys::mcstat_moments_from_bytes_rows(b.as_ptr(), b.len(), rows, m.rows.as_mut_ptr() as *mut sys::mcstat_moments)
        })?;
        Ok(m)
    }
    pub fn into_vec(self) -> Vec<Moments> {
        self.rows
    }
}

impl From<Vec<Moments>> for MomentsArray {
    fn from(rows: Vec<Moments>) -> Self {
        MomentsArray { rows }
    }
}

impl Deref for MomentsArray {
    type Target = [Moments];
    fn deref(&self) -> &[Moments] {
        &self.rows
    }
}

impl DerefMut for MomentsArray {
    fn deref_mut(&mut self) -> &mut [Moments] {
        &mut self.rows
    }
}

// ---- the per-thread stream ------------------------------------------------------

/// A renderer thread's buffered accumulator (`mcstat_stream`, 4096 bytes,
/// boxed here so that moving it is cheap): [`Stream::add`] stores a value
/// and bumps a counter, flushing into the moments every 492 values, so the
/// moments are exactly what [`Moments::add_slice`] gives on the same
/// values.  NaN and infinities are counted, not added, and make the checks
/// fail with NonFinite.  One stream per thread, merged at the end of a frame.
#[derive(Clone)]
pub struct Stream {
    raw: Box<sys::mcstat_stream>,
}

impl Default for Stream {
    fn default() -> Self {
        Stream::new()
    }
}

impl std::fmt::Debug for Stream {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stream")
            .field("n", &self.n())
            .field("n_nonfinite", &self.n_nonfinite())
            .field("n_overflow", &self.n_overflow())
            .finish()
    }
}

impl Stream {
    pub fn new() -> Stream {
        let mut raw: Box<sys::mcstat_stream> = Box::new(unsafe { MaybeUninit::zeroed().assume_init() });
        let st = unsafe { sys::mcstat_stream_init(&mut *raw) };
        assert_eq!(st, sys::MCSTAT_OK);
        Stream { raw }
    }
    /// Adds one value: the header's inline `mcstat_stream_add`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        // the stream was initialised by new(), so count < capacity
        unsafe { sys::mcstat_stream_add(&mut *self.raw, x) }
    }
    pub fn add_slice(&mut self, x: &[f64]) {
        for &v in x {
            self.add(v);
        }
    }
    /// Moves the buffered values into the moments.  TooBig when the count
    /// would pass 2^64 - 1 (the values are then left out, counted in
    /// [`Stream::n_overflow`], and every check fails with TooBig).
    pub fn flush(&mut self) -> Result<()> {
        check(unsafe { sys::mcstat_stream_flush(&mut *self.raw) })
    }
    /// self <- self merged with other (moments, buffered values, counts).
    pub fn merge(&mut self, other: &Stream) -> Result<()> {
        check(unsafe { sys::mcstat_stream_merge(&mut *self.raw, &*other.raw) })
    }
    /// The moments of every value seen (flushed or buffered).
    pub fn moments(&self) -> Moments {
        let mut m = Moments::new();
        let st = unsafe { sys::mcstat_stream_moments(&*self.raw, &mut m.raw) };
        debug_assert_eq!(st, sys::MCSTAT_OK);
        m
    }
    /// Values seen and added (flushed or buffered).
    pub fn n(&self) -> u64 {
        self.raw.moments.n + self.raw.count as u64
    }
    /// NaN and infinite values seen (and left out).
    pub fn n_nonfinite(&self) -> u64 {
        self.raw.n_nonfinite
    }
    /// Values left out because the count would pass 2^64 - 1.
    pub fn n_overflow(&self) -> u64 {
        self.raw.n_overflow()
    }
    /// Empties the stream.
    pub fn clear(&mut self) {
        let st = unsafe { sys::mcstat_stream_init(&mut *self.raw) };
        debug_assert_eq!(st, sys::MCSTAT_OK);
    }
    /// Is the mean `reference` to within `tolerance` (>= 0) at level alpha?
    /// `reject()` means the check failed.  Tolerance 0 is the two-sided t
    /// test; above 0, two one-sided tests at alpha/2 against the bounds.
    pub fn check_mean(&self, reference: f64, tolerance: f64, alpha: f64) -> Result<TestResult> {
        run(|out| unsafe { sys::mcstat_stream_check_mean(&*self.raw, reference, tolerance, alpha, out) })
    }
    /// Is the variance below `bound`?  The chi-squared test of var ==
    /// bound against var > bound; `reject()` means the check failed.
    pub fn check_var(&self, bound: f64, alpha: f64) -> Result<TestResult> {
        run(|out| unsafe { sys::mcstat_stream_check_var(&*self.raw, bound, alpha, out) })
    }
    pub fn raw(&self) -> &sys::mcstat_stream {
        &self.raw
    }
}
