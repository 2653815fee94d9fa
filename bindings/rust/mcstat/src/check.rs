//! Renderer checks (experimental in libmcstat): do a BSDF's, an emitter's
//! or a warp's sample(), pdf(), eval() and sample weight agree?
//!
//! The renderer's routines are Rust closures.  libmcstat calls them from the
//! calling thread, a batch of points at a time; a closure that returns an
//! error or panics stops the check, which then fails with
//! [`Error::Callback`] naming the callback, the call and the closure's
//! error or panic message (panics are caught at the FFI boundary: they
//! never unwind into C).
//!
//! The ranges of the arguments and options are libmcstat's: a check that
//! refuses them fails with [`Error::InvalidArgument`] (or
//! [`Error::TooBig`]) whose message is libmcstat's reason, naming the field
//! as C spells it, the same as here (`"options.rtol must be in (0, 1), got
//! 0"`, `"n must be at least 1000, got 10"`); see [`Error`].
//!
//! A BSDF with specular (delta) parts gives them through
//! [`CheckModel::lobes`]; its `pdf` and `eval` are then the smooth part.
//! A medium whose escaping flights carry a weight on (analog or weighted
//! tracking) has it checked against T(tmax) by [`check_medium`] with
//! [`CheckOptions::escape_transmittance`].
//!
//! ```
//! use mcstat::check::{check_warp, CheckModel, CheckOptions, Domain, Samples};
//! // x = u^2 on [0, 1], whose density is 1 / (2 sqrt x)
//! let mut model = CheckModel::new(
//!     Domain::Interval,
//!     1,
//!     |s: Samples<'_>| {
//!         for (x, u) in s.x.iter_mut().zip(s.u) {
//!             *x = u * u;
//!         }
//!         Ok(())
//!     },
//!     |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
//!         for (o, &x) in out.iter_mut().zip(x) {
//!             *o = if x > 0.0 { 0.5 / x.sqrt() } else { 0.0 };
//!         }
//!         Ok(())
//!     },
//! )
//! .sample_reports(false);
//! let report = check_warp(&mut model, 20000, 3, 0.01, &CheckOptions::default())?;
//! assert!(!report.reject());
//! println!("{report}");
//! # Ok::<(), mcstat::Error>(())
//! ```
use crate::{c_name, format_with, refusal, static_str, sys, Error, Result};
use std::fmt;
use std::mem::{size_of, MaybeUninit};
use std::os::raw::{c_int, c_void};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::ptr;

/// What a callback returns: `Err` stops the check (its message is kept).
/// `T` is `()` for the batch callbacks, which write into slices, and
/// `Vec<Lobe>` for [`CheckModel::lobes`].
pub type CallbackResult<T = ()> = std::result::Result<T, Box<dyn std::error::Error + Send + Sync>>;

/// Discrete lobes a [`CheckModel::lobes`] callback may give, at most.
pub const MAX_LOBES: usize = sys::MCSTAT_CHECK_MAX_LOBES;
/// A sample within this distance (chord length) of a lobe's direction is
/// that lobe's sample; lobes must lie further apart than twice this.
pub const LOBE_TOLERANCE: f64 = sys::MCSTAT_CHECK_LOBE_TOLERANCE;

/// One discrete (delta) lobe of a BSDF at the check's incident direction:
/// a specular reflection or refraction, which sample() returns with a
/// probability rather than a density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// The lobe's direction (unit length, in the model's domain).
    pub direction: [f64; 3],
    /// The probability, in [0, 1], with which sample() returns this
    /// direction: the pdf sample() reports there.
    pub mass: f64,
    /// The integral of f |cos| over the lobe, >= 0 (its albedo: Fresnel's
    /// R for a mirror-like reflection); sample()'s weight there is
    /// value / mass (`WeightConvention::Value`: value).
    pub value: f64,
}

/// The points' domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Unit directions (x, y, z): BSDFs with transmission, emitters.
    Sphere,
    /// Unit directions with z >= 0: reflection-only BSDFs.
    Hemisphere,
    /// (x, y) in [0, 1]^2.
    Square,
    /// (x, y) with x^2 + y^2 <= 1.
    Disk,
    /// x in [0, 1].
    Interval,
}

impl Domain {
    pub const ALL: [Domain; 5] = [Domain::Sphere, Domain::Hemisphere, Domain::Square, Domain::Disk, Domain::Interval];
    fn raw(self) -> c_int {
        match self {
            Domain::Sphere => sys::MCSTAT_CHECK_DOMAIN_SPHERE,
            Domain::Hemisphere => sys::MCSTAT_CHECK_DOMAIN_HEMISPHERE,
            Domain::Square => sys::MCSTAT_CHECK_DOMAIN_SQUARE,
            Domain::Disk => sys::MCSTAT_CHECK_DOMAIN_DISK,
            Domain::Interval => sys::MCSTAT_CHECK_DOMAIN_INTERVAL,
        }
    }
    fn from_raw(v: c_int) -> Option<Domain> {
        Domain::ALL.iter().copied().find(|d| d.raw() == v)
    }
    /// Coordinates per point (3, 3, 2, 2, 1).
    pub fn dims(self) -> usize {
        unsafe { sys::mcstat_check_domain_dims(self.raw()) as usize }
    }
}

impl fmt::Display for Domain {
    /// "sphere", "hemisphere", "square", "disk", "interval".
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(static_str(unsafe { sys::mcstat_check_domain_name(self.raw()) }).unwrap_or("?"))
    }
}

impl std::str::FromStr for Domain {
    type Err = Error;
    fn from_str(s: &str) -> Result<Domain> {
        let c = c_name(s)?;
        let mut v: c_int = -1;
        if unsafe { sys::mcstat_check_domain_parse(c.as_ptr(), &mut v) } != sys::MCSTAT_OK {
            return Err(Error::invalid(format!("unknown domain {s:?}")));
        }
        Domain::from_raw(v).ok_or_else(|| Error::invalid(format!("domain {s:?} parsed to unknown value {v}")))
    }
}

/// What `weight` a sampler reports.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WeightConvention {
    /// weight = eval / pdf (Mitsuba, most path tracers).
    #[default]
    OverPdf,
    /// weight = eval (pbrt's Sample_f times |cos|).
    Value,
}

/// One check of the battery.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Route {
    Cells,
    Mass,
    PdfValue,
    Weight,
    Support,
    Integrals,
    Energy,
    Reciprocity,
    Ks,
}

impl Route {
    pub const ALL: [Route; sys::MCSTAT_CHECK_ROUTE_COUNT] = [
        Route::Cells,
        Route::Mass,
        Route::PdfValue,
        Route::Weight,
        Route::Support,
        Route::Integrals,
        Route::Energy,
        Route::Reciprocity,
        Route::Ks,
    ];
    fn raw(self) -> c_int {
        match self {
            Route::Cells => sys::MCSTAT_CHECK_ROUTE_CELLS,
            Route::Mass => sys::MCSTAT_CHECK_ROUTE_MASS,
            Route::PdfValue => sys::MCSTAT_CHECK_ROUTE_PDF_VALUE,
            Route::Weight => sys::MCSTAT_CHECK_ROUTE_WEIGHT,
            Route::Support => sys::MCSTAT_CHECK_ROUTE_SUPPORT,
            Route::Integrals => sys::MCSTAT_CHECK_ROUTE_INTEGRALS,
            Route::Energy => sys::MCSTAT_CHECK_ROUTE_ENERGY,
            Route::Reciprocity => sys::MCSTAT_CHECK_ROUTE_RECIPROCITY,
            Route::Ks => sys::MCSTAT_CHECK_ROUTE_KS,
        }
    }
    /// "cells", "mass", "pdf_value", ...
    pub fn name(self) -> &'static str {
        static_str(unsafe { sys::mcstat_check_route_name(self.raw()) }).unwrap_or("?")
    }
    /// What the route checks, in a sentence.
    pub fn meaning(self) -> &'static str {
        static_str(unsafe { sys::mcstat_check_route_meaning(self.raw()) }).unwrap_or("?")
    }
    /// What the route cannot see, in a sentence.
    pub fn blind_spot(self) -> &'static str {
        static_str(unsafe { sys::mcstat_check_route_blind_spot(self.raw()) }).unwrap_or("?")
    }
}

impl fmt::Display for Route {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Route {
    type Err = Error;
    fn from_str(s: &str) -> Result<Route> {
        let c = c_name(s)?;
        let mut v: c_int = -1;
        if unsafe { sys::mcstat_check_route_parse(c.as_ptr(), &mut v) } != sys::MCSTAT_OK {
            return Err(Error::invalid(format!("unknown route {s:?}")));
        }
        Route::ALL
            .iter()
            .copied()
            .find(|r| r.raw() == v)
            .ok_or_else(|| Error::invalid(format!("route {s:?} parsed to unknown value {v}")))
    }
}

/// A set of routes (`Default`: all; routes that do not apply are skipped).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RouteSet(u32);

impl RouteSet {
    pub fn all() -> RouteSet {
        RouteSet(sys::MCSTAT_CHECK_ROUTE_ALL)
    }
    pub fn of(routes: &[Route]) -> RouteSet {
        RouteSet(routes.iter().fold(0, |b, r| b | 1u32 << r.raw()))
    }
    pub fn with(self, r: Route) -> RouteSet {
        RouteSet(self.0 | 1u32 << r.raw())
    }
    pub fn without(self, r: Route) -> RouteSet {
        RouteSet(self.0 & !(1u32 << r.raw()))
    }
    pub fn contains(self, r: Route) -> bool {
        self.0 & (1u32 << r.raw()) != 0
    }
}

impl Default for RouteSet {
    fn default() -> Self {
        RouteSet::all()
    }
}

/// Options of the checks; `Default` is libmcstat's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckOptions {
    /// Routes to run (must not be empty).
    pub routes: RouteSet,
    /// Weight and pdf are estimates (layered BSDFs): PDF_VALUE and WEIGHT
    /// are skipped, INTEGRALS checks them.
    pub stochastic: bool,
    /// Run RECIPROCITY.
    pub reciprocal: bool,
    /// Target cells for CELLS, 2..=2^20 (`None`: 2 n^0.4 within [8, 8192]).
    pub cells: Option<u32>,
    /// Pilot samples for the cells, >= 64 (`None`: 32 per target cell).
    pub n_pilot: Option<u64>,
    /// Points of the eval-only estimator, >= 1000 (`None`: n).
    pub n_eval: Option<u64>,
    /// Points per callback call, 64..=2^32.
    pub batch: u64,
    /// Relative tolerance of the deterministic routes, in (0, 1).
    pub rtol: f64,
    /// Share of points a deterministic route lets differ beyond rtol, in [0, 1).
    pub tolerated: f64,
    /// [`check_medium`] only: `None` (the default), a flight that passes the
    /// surface is a failed sample (pdf 0), which must weigh 0.  `Some(T)`
    /// with T = T(tmax) in [0, 1], the transmittance to the surface: such a
    /// flight reports pdf 0 and the weight it carries on
    /// (1 for analog tracking, T(tmax) / P(escape) when the distances follow
    /// another density), and [`Route::Mass`] also tests, by a two-sided t
    /// test in the same Bonferroni as its other parts, that the mean over the
    /// n flights of the escapes' weights (0 for a scattering) equals T
    /// ([`CheckReport::escape_weight`]).  Needs [`WeightConvention::OverPdf`];
    /// the other checks refuse it.
    pub escape_transmittance: Option<f64>,
    /// The relative resolution of the renderer's arithmetic: differences of
    /// integrals at that scale are rounding, not evidence (the statistical
    /// routes add it as an error of what they compare; each reports it,
    /// [`RouteResult::resolution`]).  `None` (the default): derived from the
    /// values the callbacks return, 2^-18 (64 float32 ulps) when every pdf,
    /// weight and eval value is a float32, else 2^-47; `Some(r)`: r in (0, 0.01).
    pub resolution: Option<f64>,
}

fn c_options_defaults() -> sys::mcstat_check_options {
    let mut o = MaybeUninit::<sys::mcstat_check_options>::zeroed();
    unsafe {
        let st = sys::mcstat_check_options_init_size(o.as_mut_ptr(), size_of::<sys::mcstat_check_options>());
        debug_assert_eq!(st, sys::MCSTAT_OK);
        o.assume_init()
    }
}

impl Default for CheckOptions {
    fn default() -> Self {
        let o = c_options_defaults();
        CheckOptions {
            routes: RouteSet(o.routes),
            stochastic: o.stochastic != 0,
            reciprocal: o.reciprocal != 0,
            cells: None,
            n_pilot: None,
            n_eval: None,
            batch: o.batch,
            rtol: o.rtol,
            tolerated: o.tolerated,
            escape_transmittance: None,
            resolution: None,
        }
    }
}

impl CheckOptions {
    fn raw(&self) -> Result<sys::mcstat_check_options> {
        let mut o = c_options_defaults();
        o.routes = self.routes.0;
        o.stochastic = self.stochastic as i32;
        o.reciprocal = self.reciprocal as i32;
        // conversions only: the ranges are C's, and its reasons name them
        o.cells = match self.cells {
            None => 0,
            Some(c) => i32::try_from(c).map_err(|_| Error::invalid(format!("options.cells {c} does not fit C's int32_t")))?,
        };
        o.n_pilot = self.n_pilot.unwrap_or(0);
        o.n_eval = self.n_eval.unwrap_or(0);
        o.batch = self.batch;
        o.rtol = self.rtol;
        o.tolerated = self.tolerated;
        if let Some(t) = self.escape_transmittance {
            // C takes a negative value as "off" (None here), so Some(-0.5)
            // would pass it unseen; NaN fails the test too
            if !(0.0..=1.0).contains(&t) {
                return Err(Error::invalid(format!(
                    "escape_transmittance must be in [0, 1] (the transmittance to the surface), got {t}"
                )));
            }
            o.escape_transmittance = t;
        }
        o.resolution = self.resolution.unwrap_or(0.0);
        Ok(o)
    }
}

/// One call of the sampler: for k < n = `weight.len()`, from the uniforms
/// `u[k * n_uniforms ..]` in [0, 1), write the point `x[k * dims ..]`, and
/// (when the model's `sample_reports`) the weight and the density the
/// sampler reports; a failed sample has pdf 0 and weight 0.
pub struct Samples<'a> {
    /// The fixed incident direction of a BSDF check (`None` otherwise).
    pub wi: Option<&'a [f64; 3]>,
    pub u: &'a [f64],
    pub x: &'a mut [f64],
    pub weight: &'a mut [f64],
    pub pdf: &'a mut [f64],
}

impl Samples<'_> {
    /// Points in this call.
    pub fn len(&self) -> usize {
        self.weight.len()
    }
    pub fn is_empty(&self) -> bool {
        self.weight.is_empty()
    }
}

type SampleFn<'a> = dyn FnMut(Samples<'_>) -> CallbackResult + 'a;
/// (wi, points x (n * dims values), out (n values)).
type DensityFn<'a> = dyn FnMut(Option<&[f64; 3]>, &[f64], &mut [f64]) -> CallbackResult + 'a;
type LobesFn<'a> = dyn FnMut(&[f64; 3]) -> CallbackResult<Vec<Lobe>> + 'a;

/// The model a renderer hands over: its domain, how many uniforms a sample
/// takes, its sample, pdf and (BSDFs, emitters) eval routines, and (BSDFs
/// with specular parts) its discrete lobes.
pub struct CheckModel<'a> {
    domain: Domain,
    n_uniforms: usize,
    weight: WeightConvention,
    sample_reports: bool,
    sample: Box<SampleFn<'a>>,
    pdf: Box<DensityFn<'a>>,
    eval: Option<Box<DensityFn<'a>>>,
    lobes: Option<Box<LobesFn<'a>>>,
}

impl<'a> CheckModel<'a> {
    /// A model with weights eval/pdf and a sampler that reports them; add
    /// `eval` for BSDFs and emitters, or set `sample_reports(false)` for a
    /// warp.
    pub fn new<S, P>(domain: Domain, n_uniforms: usize, sample: S, pdf: P) -> CheckModel<'a>
    where
        S: FnMut(Samples<'_>) -> CallbackResult + 'a,
        P: FnMut(Option<&[f64; 3]>, &[f64], &mut [f64]) -> CallbackResult + 'a,
    {
        CheckModel {
            domain,
            n_uniforms,
            weight: WeightConvention::OverPdf,
            sample_reports: true,
            sample: Box::new(sample),
            pdf: Box::new(pdf),
            eval: None,
            lobes: None,
        }
    }
    /// The integrand the sampler is built for: f(wi, x) |cos x| for a BSDF,
    /// the radiance arriving along x for an emitter.
    pub fn eval<E>(mut self, eval: E) -> CheckModel<'a>
    where
        E: FnMut(Option<&[f64; 3]>, &[f64], &mut [f64]) -> CallbackResult + 'a,
    {
        self.eval = Some(Box::new(eval));
        self
    }
    /// The discrete (delta) lobes of a BSDF whose sample() returns
    /// specular directions ([`check_bsdf`] only): for the check's
    /// (normalised) wi, up to [`MAX_LOBES`] lobes, each with its direction,
    /// the probability sample() picks it and its albedo.  `pdf` and `eval`
    /// then describe the smooth part only (as Mitsuba's and pbrt's do).  A
    /// sample within [`LOBE_TOLERANCE`] of a lobe's direction is that
    /// lobe's: PDF_VALUE and WEIGHT check it against the lobe's mass and
    /// value / mass, MASS tests each lobe's count against n mass (exact
    /// binomial test), SUPPORT rejects a lobe with energy and mass 0,
    /// ENERGY includes the lobes; CELLS, INTEGRALS and KS see the smooth
    /// samples only.  Called once per check; an `Err`, a panic or more than
    /// [`MAX_LOBES`] lobes fail the check with [`Error::Callback`].
    pub fn lobes<L>(mut self, lobes: L) -> CheckModel<'a>
    where
        L: FnMut(&[f64; 3]) -> CallbackResult<Vec<Lobe>> + 'a,
    {
        self.lobes = Some(Box::new(lobes));
        self
    }
    pub fn weight(mut self, w: WeightConvention) -> CheckModel<'a> {
        self.weight = w;
        self
    }
    /// false: the sampler writes only x (warps: every sample succeeds).
    pub fn sample_reports(mut self, reports: bool) -> CheckModel<'a> {
        self.sample_reports = reports;
        self
    }
    pub fn domain(&self) -> Domain {
        self.domain
    }
}

/// What the trampolines see through `user`.
struct Ctx<'m, 'a> {
    model: &'m mut CheckModel<'a>,
    dims: usize,
    /// The first closure error or panic, in words.
    failure: Option<String>,
}

impl Ctx<'_, '_> {
    fn settle(&mut self, what: &str, r: std::thread::Result<CallbackResult>) -> c_int {
        let msg = match r {
            Ok(Ok(())) => return 0,
            Ok(Err(e)) => format!("{what}() returned an error: {e}"),
            Err(payload) => {
                let text = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "a non-string payload".to_string());
                format!("{what}() panicked: {text}")
            }
        };
        self.failure.get_or_insert(msg);
        1
    }
}

unsafe fn slice<'s>(p: *const f64, n: usize) -> &'s [f64] {
    if p.is_null() || n == 0 {
        &[]
    } else {
        std::slice::from_raw_parts(p, n)
    }
}

unsafe fn slice_mut<'s>(p: *mut f64, n: usize) -> &'s mut [f64] {
    if p.is_null() || n == 0 {
        &mut []
    } else {
        std::slice::from_raw_parts_mut(p, n)
    }
}

unsafe fn direction<'s>(p: *const f64) -> Option<&'s [f64; 3]> {
    if p.is_null() {
        None
    } else {
        Some(&*(p as *const [f64; 3]))
    }
}

unsafe extern "C" fn sample_trampoline(
    user: *mut c_void,
    wi: *const f64,
    u: *const f64,
    n: usize,
    x: *mut f64,
    weight: *mut f64,
    pdf: *mut f64,
) -> c_int {
    let ctx = &mut *(user as *mut Ctx);
    let (dims, nu) = (ctx.dims, ctx.model.n_uniforms);
    let model = &mut *ctx.model;
    let r = catch_unwind(AssertUnwindSafe(|| {
        (model.sample)(Samples {
            wi: direction(wi),
            u: slice(u, n * nu),
            x: slice_mut(x, n * dims),
            weight: slice_mut(weight, n),
            pdf: slice_mut(pdf, n),
        })
    }));
    ctx.settle("sample", r)
}

unsafe extern "C" fn pdf_trampoline(user: *mut c_void, wi: *const f64, x: *const f64, n: usize, out: *mut f64) -> c_int {
    let ctx = &mut *(user as *mut Ctx);
    let dims = ctx.dims;
    let model = &mut *ctx.model;
    let r = catch_unwind(AssertUnwindSafe(|| (model.pdf)(direction(wi), slice(x, n * dims), slice_mut(out, n))));
    ctx.settle("pdf", r)
}

unsafe extern "C" fn eval_trampoline(user: *mut c_void, wi: *const f64, x: *const f64, n: usize, out: *mut f64) -> c_int {
    let ctx = &mut *(user as *mut Ctx);
    let dims = ctx.dims;
    let model = &mut *ctx.model;
    let r = catch_unwind(AssertUnwindSafe(|| match model.eval.as_mut() {
        Some(eval) => eval(direction(wi), slice(x, n * dims), slice_mut(out, n)),
        None => Err("the model has no eval".into()),
    }));
    ctx.settle("eval", r)
}

unsafe extern "C" fn lobes_trampoline(
    user: *mut c_void,
    wi: *const f64,
    x: *mut f64,
    mass: *mut f64,
    value: *mut f64,
    count: *mut usize,
) -> c_int {
    let ctx = &mut *(user as *mut Ctx);
    let model = &mut *ctx.model;
    let r = catch_unwind(AssertUnwindSafe(|| match (model.lobes.as_mut(), direction(wi)) {
        (Some(lobes), Some(wi)) => lobes(wi),
        (None, _) => Err("the model has no lobes".into()),
        (Some(_), None) => Err("lobes() called without wi".into()),
    }));
    let lobes = match r {
        Ok(Ok(v)) => v,
        Ok(Err(e)) => return ctx.settle("lobes", Ok(Err(e))),
        Err(payload) => return ctx.settle("lobes", Err(payload)),
    };
    if x.is_null() || mass.is_null() || value.is_null() || count.is_null() {
        ctx.failure.get_or_insert("lobes() called with NULL outputs".to_string());
        return 1;
    }
    if lobes.len() > MAX_LOBES {
        let msg = format!("lobes() gave {} lobes: at most {MAX_LOBES}", lobes.len());
        ctx.failure.get_or_insert(msg);
        return 1;
    }
    // libmcstat's arrays hold MAX_LOBES lobes
    let x = slice_mut(x, 3 * MAX_LOBES);
    let (mass, value) = (slice_mut(mass, MAX_LOBES), slice_mut(value, MAX_LOBES));
    for (k, l) in lobes.iter().enumerate() {
        x[3 * k..3 * k + 3].copy_from_slice(&l.direction);
        mass[k] = l.mass;
        value[k] = l.value;
    }
    *count = lobes.len();
    0
}

fn raw_model(model: &CheckModel, user: *mut c_void) -> Result<sys::mcstat_check_model> {
    // a conversion only: the range is C's (its reason names model.n_uniforms)
    let n_uniforms = i32::try_from(model.n_uniforms)
        .map_err(|_| Error::invalid(format!("model.n_uniforms {} does not fit C's int32_t", model.n_uniforms)))?;
    Ok(sys::mcstat_check_model {
        domain: model.domain.raw(),
        n_uniforms,
        weight: match model.weight {
            WeightConvention::OverPdf => sys::MCSTAT_CHECK_WEIGHT_OVER_PDF,
            WeightConvention::Value => sys::MCSTAT_CHECK_WEIGHT_VALUE,
        },
        sample_reports: model.sample_reports as i32,
        user,
        sample: Some(sample_trampoline),
        pdf: Some(pdf_trampoline),
        eval: if model.eval.is_some() { Some(eval_trampoline) } else { None },
        extra: sys::mcstat_check_model_union {
            s: sys::mcstat_check_model_named {
                lobes: if model.lobes.is_some() { Some(lobes_trampoline) } else { None },
                reserved_rest: [0.0; 3],
            },
        },
    })
}

/// Bytes of scratch a check of `n` samples allocates (the checks here let
/// libmcstat allocate and free it): about 15 MB at n = 1e5 with the defaults.
pub fn check_work_size(model: &CheckModel, n: usize, opt: &CheckOptions) -> Result<usize> {
    let m = raw_model(model, ptr::null_mut())?;
    let o = opt.raw()?;
    let mut bytes = 0usize;
    let st = unsafe { sys::mcstat_check_work_size(&m, n, &o, &mut bytes) };
    if st != sys::MCSTAT_OK {
        return Err(refusal(st));
    }
    Ok(bytes)
}

fn run_check(
    model: &mut CheckModel,
    opt: &CheckOptions,
    call: impl FnOnce(&sys::mcstat_check_model, &sys::mcstat_check_options, *mut sys::mcstat_check_report) -> c_int,
) -> Result<CheckReport> {
    let o = opt.raw()?;
    let dims = model.domain.dims();
    let mut m = raw_model(model, ptr::null_mut())?;
    let mut ctx = Ctx { model, dims, failure: None };
    m.user = &mut ctx as *mut Ctx as *mut c_void;
    let mut out: Box<sys::mcstat_check_report> = Box::new(unsafe { MaybeUninit::zeroed().assume_init() });
    let st = call(&m, &o, &mut *out);
    if st == sys::MCSTAT_OK {
        return Ok(CheckReport { raw: out });
    }
    if st == sys::MCSTAT_ECALLBACK {
        let mut msg = message(&out);
        if let Some(f) = ctx.failure.take() {
            msg = if msg.is_empty() { f } else { format!("{msg}: {f}") };
        }
        return Err(Error::Callback(msg));
    }
    // C's reason, on this thread: nothing since the call has called libmcstat
    Err(refusal(st))
}

fn message(r: &sys::mcstat_check_report) -> String {
    let len = r.message.iter().position(|&c| c == 0).unwrap_or(r.message.len());
    let bytes: Vec<u8> = r.message[..len].iter().map(|&c| c as u8).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// Checks a BSDF at the incident direction `wi` with `n` samples (>= 1000)
/// at battery level `alpha`; the seed makes it reproducible.
pub fn check_bsdf(model: &mut CheckModel, wi: [f64; 3], n: usize, seed: u64, alpha: f64, opt: &CheckOptions) -> Result<CheckReport> {
    run_check(model, opt, |m, o, out| unsafe {
        sys::mcstat_check_bsdf(m, wi.as_ptr(), n, seed, alpha, o, ptr::null_mut(), 0, out)
    })
}

/// Checks an emitter's sampling of directions from a reference point (the
/// closures hold the point): domain sphere or hemisphere.
pub fn check_emitter(model: &mut CheckModel, n: usize, seed: u64, alpha: f64, opt: &CheckOptions) -> Result<CheckReport> {
    run_check(model, opt, |m, o, out| unsafe { sys::mcstat_check_emitter(m, n, seed, alpha, o, ptr::null_mut(), 0, out) })
}

/// Checks a warp (a sampler and its density, no integrand).
pub fn check_warp(model: &mut CheckModel, n: usize, seed: u64, alpha: f64, opt: &CheckOptions) -> Result<CheckReport> {
    run_check(model, opt, |m, o, out| unsafe { sys::mcstat_check_warp(m, n, seed, alpha, o, ptr::null_mut(), 0, out) })
}

/// Checks a phase function p(wi, wo) (domain sphere; eval is p, no cosine):
/// the routes of `check_bsdf`, with energy testing albedo == 1 (two-sided)
/// and reciprocity (when asked) p(wi, wo) == p(wo, wi).
pub fn check_phase(model: &mut CheckModel, wi: [f64; 3], n: usize, seed: u64, alpha: f64, opt: &CheckOptions) -> Result<CheckReport> {
    run_check(model, opt, |m, o, out| unsafe {
        sys::mcstat_check_phase(m, wi.as_ptr(), n, seed, alpha, o, ptr::null_mut(), 0, out)
    })
}

/// Checks distance sampling along a ray (domain interval): the closures'
/// points are distances t >= 0, mapped inside to x = 1 - exp(-sigma_ref t);
/// a flight that passes the surface is a failed sample (pdf 0, weight 0),
/// or with [`CheckOptions::escape_transmittance`] one that reports pdf 0 and
/// the weight it carries on; eval is sigma_s T(t).
pub fn check_medium(model: &mut CheckModel, sigma_ref: f64, n: usize, seed: u64, alpha: f64, opt: &CheckOptions) -> Result<CheckReport> {
    run_check(model, opt, |m, o, out| unsafe {
        sys::mcstat_check_medium(m, sigma_ref, n, seed, alpha, o, ptr::null_mut(), 0, out)
    })
}

/// Whether a route ran.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RouteState {
    Ran,
    /// Not asked for, or not applicable to this model.
    Skipped,
    /// An assumption failed (heavy tails, too few samples): no answer.
    Invalid,
}

/// One route's outcome.
#[derive(Clone, Copy, Debug)]
pub struct RouteResult {
    raw: sys::mcstat_check_route_result,
}

fn some(v: f64) -> Option<f64> {
    if v.is_nan() {
        None
    } else {
        Some(v)
    }
}

impl RouteResult {
    pub fn state(&self) -> RouteState {
        match self.raw.state {
            sys::MCSTAT_CHECK_STATE_RAN => RouteState::Ran,
            sys::MCSTAT_CHECK_STATE_SKIPPED => RouteState::Skipped,
            _ => RouteState::Invalid,
        }
    }
    /// A tolerance check, not a statistical test.
    pub fn deterministic(&self) -> bool {
        self.raw.deterministic != 0
    }
    pub fn reject(&self) -> bool {
        self.raw.reject != 0
    }
    /// Statistical routes only.
    pub fn statistic(&self) -> Option<f64> {
        some(self.raw.statistic)
    }
    pub fn df(&self) -> Option<f64> {
        some(self.raw.df)
    }
    pub fn p_value(&self) -> Option<f64> {
        some(self.raw.p_value)
    }
    /// The p-value adjusted across routes (Holm).
    pub fn p_adjusted(&self) -> Option<f64> {
        some(self.raw.p_adjusted)
    }
    /// The departure measured (Cohen's w, a relative difference, ...).
    pub fn effect(&self) -> Option<f64> {
        some(self.raw.effect)
    }
    /// The smallest departure this run detects with probability 0.8.
    pub fn detectable(&self) -> Option<f64> {
        some(self.raw.detectable)
    }
    /// Samples needed to detect a 1% departure with probability 0.8.
    pub fn n_for_1pct(&self) -> Option<f64> {
        some(self.raw.n_for_1pct)
    }
    /// Points checked, and points beyond tolerance (CELLS: samples and pooled cells).
    pub fn checked(&self) -> u64 {
        self.raw.checked
    }
    pub fn count(&self) -> u64 {
        self.raw.count
    }
    /// Deterministic routes: the point of the largest difference and the
    /// two values that differ there.
    pub fn worst(&self) -> Option<([f64; 3], f64, f64)> {
        if self.raw.value[0].is_nan() || self.raw.value[1].is_nan() {
            None
        } else {
            Some((self.raw.r#where, self.raw.value[0], self.raw.value[1]))
        }
    }
    /// State [`RouteState::Invalid`]: why the route could not answer and
    /// what would let it (libmcstat's sentence).
    pub fn why(&self) -> Option<&'static str> {
        if self.state() != RouteState::Invalid {
            return None;
        }
        static_str(unsafe { sys::mcstat_check_why_text(self.raw.why) })
    }
    /// Statistical routes: the relative numerical floor they applied.
    pub fn resolution(&self) -> Option<f64> {
        some(self.raw.resolution)
    }
    pub fn raw(&self) -> &sys::mcstat_check_route_result {
        &self.raw
    }
}

/// A check's verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// No route rejected, and every route the check needed answered.
    Consistent,
    /// Some route rejected ([`CheckReport::reject`]).
    Inconsistent,
    /// No route rejected, but a route the check needed could not answer
    /// ([`CheckReport::unanswered`]): "consistent" would claim an error rate
    /// the battery did not have.
    Inconclusive,
}

impl Verdict {
    /// "consistent", "inconsistent", "inconclusive".
    pub fn name(self) -> &'static str {
        let v = match self {
            Verdict::Consistent => sys::MCSTAT_CHECK_CONSISTENT,
            Verdict::Inconsistent => sys::MCSTAT_CHECK_INCONSISTENT,
            Verdict::Inconclusive => sys::MCSTAT_CHECK_INCONCLUSIVE,
        };
        static_str(unsafe { sys::mcstat_check_verdict_name(v) }).unwrap_or("?")
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A check's report; `Display` is libmcstat's text block (one line per
/// route, what a pass means, the budget a 1% error needs).
#[derive(Clone)]
pub struct CheckReport {
    raw: Box<sys::mcstat_check_report>,
}

impl fmt::Debug for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.raw.fmt(f)
    }
}

impl CheckReport {
    /// Some route rejected: the model is inconsistent.
    pub fn reject(&self) -> bool {
        self.raw.reject != 0
    }
    /// A tail index below 2 made routes invalid.
    pub fn heavy_tailed(&self) -> bool {
        self.raw.heavy_tailed != 0
    }
    pub fn domain(&self) -> Option<Domain> {
        Domain::from_raw(self.raw.domain)
    }
    pub fn alpha(&self) -> f64 {
        self.raw.alpha
    }
    /// The smallest adjusted p-value (0 when a deterministic route failed).
    pub fn p_value(&self) -> Option<f64> {
        some(self.raw.p_value)
    }
    /// BSDFs: the direction checked.
    pub fn wi(&self) -> Option<[f64; 3]> {
        if self.raw.wi.iter().any(|v| v.is_nan()) {
            None
        } else {
            Some(self.raw.wi)
        }
    }
    /// Samples drawn for the test.
    pub fn n(&self) -> u64 {
        self.raw.n
    }
    pub fn n_failed(&self) -> u64 {
        self.raw.n_failed
    }
    pub fn n_pilot(&self) -> u64 {
        self.raw.n_pilot
    }
    pub fn n_eval(&self) -> u64 {
        self.raw.n_eval
    }
    /// Cells of the tree (before pooling).
    pub fn cells(&self) -> u64 {
        self.raw.cells
    }
    /// Callback calls.
    pub fn calls(&self) -> u64 {
        self.raw.calls
    }
    /// Points where pdf() > 0 but eval() = 0 (wasted samples, not an error).
    pub fn pdf_without_eval(&self) -> u64 {
        self.raw.pdf_without_eval
    }
    /// Samples with weight 0 where the reported pdf and eval() are > 0, counted
    /// as successes: a sampler that marks a failed sample by its weight alone
    /// shows here (mark it by pdf 0 instead).
    pub fn zero_weight(&self) -> u64 {
        self.raw.zero_weight()
    }
    /// Discrete lobes given by the model's `lobes` (0 without).
    pub fn lobes(&self) -> u64 {
        self.raw.lobe_counts().lobes
    }
    /// Samples that fell on a discrete lobe.
    pub fn n_lobe(&self) -> u64 {
        self.raw.lobe_counts().n_lobe
    }
    /// The sum of the discrete lobes' masses (probabilities; 0 without).
    pub fn lobe_mass(&self) -> f64 {
        self.raw.lobe_counts().lobe_mass
    }
    /// The sum of the discrete lobes' values: the discrete part of the
    /// albedo ([`albedo`](Self::albedo) is the smooth part's; 0 without).
    pub fn lobe_albedo(&self) -> f64 {
        self.raw.lobe_counts().lobe_albedo
    }
    /// [`check_medium`] with [`CheckOptions::escape_transmittance`]: the mean
    /// over the n flights of the escapes' weights (0 for a scattering), which
    /// [`Route::Mass`] tests against T(tmax) (`None` otherwise).
    pub fn escape_weight(&self) -> Option<f64> {
        some(self.raw.escape_weight().0)
    }
    /// Its standard error (`None` when not checked, or with fewer than 2
    /// escapes of weight > 0).
    pub fn escape_weight_se(&self) -> Option<f64> {
        some(self.raw.escape_weight().1)
    }
    /// The integral of pdf() over the domain (cubature) and its error estimate.
    pub fn mass(&self) -> Option<(f64, f64)> {
        some(self.raw.mass).map(|m| (m, self.raw.mass_error))
    }
    /// The same by Monte Carlo, and its standard error.
    pub fn mass_sampled(&self) -> Option<(f64, f64)> {
        some(self.raw.mass_sampled).map(|m| (m, self.raw.mass_sampled_se))
    }
    fn is_warp(&self) -> bool {
        self.raw.kind == sys::MCSTAT_CHECK_KIND_WARP
    }
    /// The mean weight and its standard error (`None` for warps: no integrand).
    pub fn albedo(&self) -> Option<(f64, f64)> {
        if self.is_warp() {
            return None;
        }
        some(self.raw.albedo).map(|a| (a, self.raw.albedo_se))
    }
    /// The eval-only estimate of the same integral, and its standard error
    /// (`None` for warps).
    pub fn albedo_eval(&self) -> Option<(f64, f64)> {
        if self.is_warp() {
            return None;
        }
        some(self.raw.albedo_eval).map(|a| (a, self.raw.albedo_eval_se))
    }
    /// Hill's upper tail index of the weights and of the eval-only estimates.
    pub fn tail_index(&self) -> [Option<f64>; 2] {
        [some(self.raw.tail_index[0]), some(self.raw.tail_index[1])]
    }
    pub fn route(&self, r: Route) -> RouteResult {
        RouteResult { raw: self.raw.route[r.raw() as usize] }
    }
    /// Every route with its outcome.
    pub fn routes(&self) -> impl Iterator<Item = (Route, RouteResult)> + '_ {
        Route::ALL.iter().map(move |&r| (r, self.route(r)))
    }
    /// The verdict and the routes that could not answer (libmcstat's
    /// `mcstat_check_verdict`).
    fn verdict_raw(&self) -> (c_int, u32) {
        let (mut v, mut mask): (c_int, u32) = (sys::MCSTAT_CHECK_INCONSISTENT, 0);
        // a report the library wrote: never refused
        let st = unsafe { sys::mcstat_check_verdict(&*self.raw, &mut v, &mut mask) };
        debug_assert_eq!(st, sys::MCSTAT_OK);
        (v, mask)
    }
    /// Consistent, inconsistent, or inconclusive (a route the check needed
    /// could not answer).
    pub fn verdict(&self) -> Verdict {
        match self.verdict_raw().0 {
            sys::MCSTAT_CHECK_CONSISTENT => Verdict::Consistent,
            sys::MCSTAT_CHECK_INCONCLUSIVE => Verdict::Inconclusive,
            _ => Verdict::Inconsistent,
        }
    }
    /// The routes that could not answer and make the verdict inconclusive.
    pub fn unanswered(&self) -> Vec<Route> {
        let mask = self.verdict_raw().1;
        Route::ALL.iter().copied().filter(|r| mask & (1u32 << r.raw()) != 0).collect()
    }
    pub fn raw(&self) -> &sys::mcstat_check_report {
        &self.raw
    }
    pub fn try_format(&self) -> Result<String> {
        format_with(|buf, size, len| unsafe { sys::mcstat_check_format(&*self.raw, buf, size, len) })
    }
}

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.try_format().map_err(|_| fmt::Error)?)
    }
}
