package mcstat

// #include <stdint.h>
// #include <stdlib.h>
// #include <mcstat.h>
//
// /* The Go trampolines (check_export.go) take non-const pointers; these
//    adapters give libmcstat functions of its callback types. */
// extern int gomcstatSample(void *, double *, double *, size_t, double *, double *, double *);
// extern int gomcstatPDF(void *, double *, double *, size_t, double *);
// extern int gomcstatEval(void *, double *, double *, size_t, double *);
// extern int gomcstatLobes(void *, double *, double *, double *, double *, size_t *);
// static int gomcstat_sample(void *user, const double *wi, const double *u, size_t n, double *x,
//                            double *weight, double *pdf) {
//     return gomcstatSample(user, (double *)wi, (double *)u, n, x, weight, pdf);
// }
// static int gomcstat_pdf(void *user, const double *wi, const double *x, size_t n, double *out) {
//     return gomcstatPDF(user, (double *)wi, (double *)x, n, out);
// }
// static int gomcstat_eval(void *user, const double *wi, const double *x, size_t n, double *out) {
//     return gomcstatEval(user, (double *)wi, (double *)x, n, out);
// }
// static int gomcstat_lobes(void *user, const double *wi, double *x, double *mass, double *value,
//                           size_t *count) {
//     return gomcstatLobes(user, (double *)wi, x, mass, value, count);
// }
// /* the anonymous unions of the report and the model, which cgo cannot name */
// static uint64_t gomcstat_zero_weight(const mcstat_check_report *r) { return r->zero_weight; }
// static uint64_t gomcstat_lobes_count(const mcstat_check_report *r) { return r->lobes; }
// static uint64_t gomcstat_n_lobe(const mcstat_check_report *r) { return r->n_lobe; }
// static double gomcstat_lobe_mass(const mcstat_check_report *r) { return r->lobe_mass; }
// static double gomcstat_lobe_albedo(const mcstat_check_report *r) { return r->lobe_albedo; }
// static double gomcstat_escape_weight(const mcstat_check_report *r) { return r->escape_weight; }
// static double gomcstat_escape_weight_se(const mcstat_check_report *r) { return r->escape_weight_se; }
// static int gomcstat_route_why(const mcstat_check_route_result *q) { return q->why; }
// static double gomcstat_route_resolution(const mcstat_check_route_result *q) { return q->resolution; }
// static void gomcstat_model_callbacks(mcstat_check_model *m, void *user, int with_eval, int with_lobes) {
//     m->user = user;
//     m->sample = gomcstat_sample;
//     m->pdf = gomcstat_pdf;
//     m->eval = with_eval ? gomcstat_eval : NULL;
//     m->lobes = with_lobes ? gomcstat_lobes : NULL;
// }
import "C"

import (
	"fmt"
	"math"
	"runtime"
	"runtime/cgo"
	"unsafe"
)

// ---- renderer checks (experimental) ---------------------------------------------

// Domain is where a model's points live.
type Domain int

const (
	DomainSphere     Domain = C.MCSTAT_CHECK_DOMAIN_SPHERE     // unit directions: BSDFs with transmission, emitters
	DomainHemisphere Domain = C.MCSTAT_CHECK_DOMAIN_HEMISPHERE // unit directions with z >= 0
	DomainSquare     Domain = C.MCSTAT_CHECK_DOMAIN_SQUARE     // (x, y) in [0, 1]^2
	DomainDisk       Domain = C.MCSTAT_CHECK_DOMAIN_DISK       // x^2 + y^2 <= 1
	DomainInterval   Domain = C.MCSTAT_CHECK_DOMAIN_INTERVAL   // x in [0, 1]
)

// Dims is the number of coordinates of a point (0 for an invalid domain).
func (d Domain) Dims() int { return int(C.mcstat_check_domain_dims(C.int(d))) }

func (d Domain) String() string {
	if s := C.mcstat_check_domain_name(C.int(d)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("Domain(%d)", int(d))
}

// ParseDomain accepts "sphere", "hemisphere", "square", "disk", "interval".
func ParseDomain(name string) (Domain, error) {
	cs := C.CString(name)
	defer C.free(unsafe.Pointer(cs))
	var v C.int
	if err := check(C.mcstat_check_domain_parse(cs, &v)); err != nil {
		return 0, err
	}
	return Domain(v), nil
}

// SampleWeight is the convention of the weight a sampler reports.
type SampleWeight int

const (
	WeightOverPDF SampleWeight = C.MCSTAT_CHECK_WEIGHT_OVER_PDF // weight = eval / pdf (Mitsuba, most path tracers)
	WeightValue   SampleWeight = C.MCSTAT_CHECK_WEIGHT_VALUE    // weight = eval (pbrt's Sample_f times |cos|)
)

// Route is one of the checks a renderer check runs.
type Route int

const (
	RouteCells       Route = C.MCSTAT_CHECK_ROUTE_CELLS       // sample() draws from pdf(): chi-squared on cells
	RouteMass        Route = C.MCSTAT_CHECK_ROUTE_MASS        // the fraction of successful samples is pdf()'s integral
	RoutePDFValue    Route = C.MCSTAT_CHECK_ROUTE_PDF_VALUE   // the pdf sample() reports is pdf()'s
	RouteWeight      Route = C.MCSTAT_CHECK_ROUTE_WEIGHT      // the weight is eval/pdf
	RouteSupport     Route = C.MCSTAT_CHECK_ROUTE_SUPPORT     // eval > 0 only where pdf > 0
	RouteIntegrals   Route = C.MCSTAT_CHECK_ROUTE_INTEGRALS   // eval's integrals by the sampler and by eval alone agree
	RouteEnergy      Route = C.MCSTAT_CHECK_ROUTE_ENERGY      // albedo <= 1 (BSDFs)
	RouteReciprocity Route = C.MCSTAT_CHECK_ROUTE_RECIPROCITY // eval is reciprocal (only when asked)
	RouteKS          Route = C.MCSTAT_CHECK_ROUTE_KS          // the weighted samples against eval, point by point
	NumRoutes              = int(C.MCSTAT_CHECK_ROUTE_COUNT)
)

func (r Route) String() string {
	if s := C.mcstat_check_route_name(C.int(r)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("Route(%d)", int(r))
}

// ParseRoute accepts the routes' names ("cells", "mass", "pdf_value", ...).
func ParseRoute(name string) (Route, error) {
	cs := C.CString(name)
	defer C.free(unsafe.Pointer(cs))
	var v C.int
	if err := check(C.mcstat_check_route_parse(cs, &v)); err != nil {
		return 0, err
	}
	return Route(v), nil
}

// Meaning is a sentence saying what the route checks ("" if invalid).
func (r Route) Meaning() string { return goStringOrEmpty(C.mcstat_check_route_meaning(C.int(r))) }

// BlindSpot is a sentence saying what the route cannot see ("" if invalid).
func (r Route) BlindSpot() string { return goStringOrEmpty(C.mcstat_check_route_blind_spot(C.int(r))) }

func goStringOrEmpty(s *C.char) string {
	if s == nil {
		return ""
	}
	return C.GoString(s)
}

// RouteSet is a set of routes (bit 1<<route).
type RouteSet uint32

// AllRoutes runs every route that applies to the model.
const AllRoutes RouteSet = (1 << C.MCSTAT_CHECK_ROUTE_COUNT) - 1

// Routes is the set of the routes given.
func Routes(rs ...Route) RouteSet {
	var s RouteSet
	for _, r := range rs {
		s |= 1 << uint(r)
	}
	return s
}

// RouteState says whether a route ran.
type RouteState int

const (
	RouteRan     RouteState = C.MCSTAT_CHECK_STATE_RAN
	RouteSkipped RouteState = C.MCSTAT_CHECK_STATE_SKIPPED // not asked for, or not applicable
	RouteInvalid RouteState = C.MCSTAT_CHECK_STATE_INVALID // an assumption failed (heavy tails, too few samples)
)

func (s RouteState) String() string {
	switch s {
	case RouteRan:
		return "ran"
	case RouteSkipped:
		return "skipped"
	case RouteInvalid:
		return "invalid"
	}
	return fmt.Sprintf("RouteState(%d)", int(s))
}

// CheckKind is what a report checked.
type CheckKind int

const (
	KindBSDF    CheckKind = C.MCSTAT_CHECK_KIND_BSDF
	KindEmitter CheckKind = C.MCSTAT_CHECK_KIND_EMITTER
	KindWarp    CheckKind = C.MCSTAT_CHECK_KIND_WARP
	KindPhase   CheckKind = C.MCSTAT_CHECK_KIND_PHASE
	KindMedium  CheckKind = C.MCSTAT_CHECK_KIND_MEDIUM
)

// SampleFunc draws n = len(weight) points: for k < n, from the uniforms
// u[k*NUniforms:(k+1)*NUniforms] in [0, 1), it writes the point
// x[k*dims:(k+1)*dims], the sample weight weight[k] and the density pdf[k]
// the sampler reports (a failed sample: pdf and weight 0).  wi is the BSDF's
// fixed direction (nil for emitters and warps).  For a model with
// SampleReports false, weight and pdf may be nil and only x is written
// (n = len(x)/dims).  The slices are libmcstat's memory, valid only during
// the call: do not keep them.
type SampleFunc func(wi, u, x, weight, pdf []float64) error

// DensityFunc writes, for each of the n = len(out) points x[k*dims:], the
// density (pdf) or the integrand (eval) into out[k].
type DensityFunc func(wi, x, out []float64) error

// MaxLobes is the most discrete lobes a LobesFunc may return.
const MaxLobes = int(C.MCSTAT_CHECK_MAX_LOBES)

// LobeTolerance is the distance (chord length) within which a sample is a
// lobe's; lobes must lie further apart than twice this.
const LobeTolerance = float64(C.MCSTAT_CHECK_LOBE_TOLERANCE)

// Lobe is one discrete (delta) lobe of a BSDF at the check's wi: a
// specular reflection or refraction, which the sampler returns with a
// probability rather than a density.
type Lobe struct {
	Dir  [3]float64 // the direction (unit length, in the model's domain)
	Mass float64    // the probability in [0, 1] that Sample returns Dir: the pdf it reports there
	// Value is the integral of f |cos| over the lobe, >= 0 (its albedo:
	// Fresnel's R for a mirror-like reflection); Sample's weight there is
	// Value/Mass (WeightValue: Value).
	Value float64
}

// LobesFunc returns, for the check's wi (normalised), at most MaxLobes
// discrete lobes.  It is called once per check.
type LobesFunc func(wi []float64) ([]Lobe, error)

// Model is what a renderer hands over to be checked.  A callback that
// returns an error or panics stops the check, which then fails with an
// error matching ErrCallback (a *CallbackError carrying the callback's
// error or panic).  Callbacks run on the calling goroutine.
type Model struct {
	Domain        Domain
	NUniforms     int          // uniforms per sample, 1..8 (Mitsuba's BSDFs: 3)
	Weight        SampleWeight // the weight convention
	SampleReports bool         // Sample writes weight and pdf (BSDFs, emitters); false for warps
	Sample        SampleFunc
	PDF           DensityFunc
	Eval          DensityFunc // the integrand; nil for warps
	// Lobes gives a BSDF's discrete (delta) lobes (CheckBSDF only; nil:
	// none).  PDF and Eval then describe the smooth part only (as
	// Mitsuba's and pbrt's do).  A sample within LobeTolerance of a lobe's
	// direction is that lobe's: RoutePDFValue and RouteWeight check it
	// against the lobe's Mass and Value/Mass, RouteMass tests each lobe's
	// count against n Mass (exact binomial test), RouteSupport rejects a
	// lobe with Value > 0 and Mass 0, RouteEnergy includes the lobes;
	// RouteCells, RouteIntegrals and RouteKS see the smooth samples only.
	// An error, a panic or more than MaxLobes lobes stop the check with a
	// *CallbackError whose Callback is "lobes".
	Lobes LobesFunc
}

// CheckOptions are the checks' options; start from DefaultCheckOptions.
// Their ranges are libmcstat's: a check refuses a value outside them with
// an *Error matching ErrInvalidArgument whose Message is C's reason, which
// names the field as C spells it ("options.n_pilot must be 0 (automatic) or
// at least 64, got 10" for NPilot; options.rtol for RTol, options.cells for
// Cells, and so on).
type CheckOptions struct {
	Routes     RouteSet
	Stochastic bool    // weight and pdf are estimates (layered BSDFs)
	Reciprocal bool    // run RouteReciprocity
	Cells      int     // target cells (0: from n)
	NPilot     uint64  // pilot samples (0: 32 per cell)
	NEval      uint64  // points of the eval-only estimator (0: n)
	Batch      uint64  // points per callback call
	RTol       float64 // relative tolerance of the deterministic routes
	Tolerated  float64 // share of points a deterministic route lets differ beyond RTol
	// EscapeTransmittance is CheckMedium's only (the other checks refuse
	// it).  nil (the default): a flight that passes the surface is a
	// failed sample (pdf 0), which must weigh 0.  A value T in [0, 1],
	// T(tmax), the transmittance to the surface: such a flight reports pdf 0 and the weight it carries on (1 for analog
	// tracking, T(tmax)/P(escape) when the distances follow another
	// density), and RouteMass also tests, by a two-sided t test in the
	// same Bonferroni as its other parts, that the mean over the n flights
	// of the escapes' weights (0 for a scattering) equals T
	// (CheckReport.EscapeWeight).  Needs WeightOverPDF.
	EscapeTransmittance *float64
	// Resolution is the relative resolution of the renderer's arithmetic:
	// differences of integrals at that scale are rounding, not evidence
	// (the statistical routes add it as an error of what they compare;
	// each reports it in RouteReport.Resolution).  0 (the default):
	// derived from the values the callbacks return, 2^-18 (64 float32
	// ulps) when every pdf, weight and eval value is a float32, else
	// 2^-47; otherwise a value in (0, 0.01).
	Resolution float64
}

func checkOptionsInit() C.struct_mcstat_check_options {
	var o C.struct_mcstat_check_options
	C.mcstat_check_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// DefaultCheckOptions returns libmcstat's defaults (every route, batch
// 65536, rtol 1e-3, tolerated 1e-4, sizes chosen from n).
func DefaultCheckOptions() CheckOptions {
	o := checkOptionsInit()
	return CheckOptions{Routes: RouteSet(o.routes), Stochastic: o.stochastic != 0, Reciprocal: o.reciprocal != 0,
		Cells: int(o.cells), NPilot: uint64(o.n_pilot), NEval: uint64(o.n_eval), Batch: uint64(o.batch),
		RTol: float64(o.rtol), Tolerated: float64(o.tolerated)}
}

func (opt *CheckOptions) toC() C.struct_mcstat_check_options {
	o := checkOptionsInit()
	if opt != nil {
		o.routes = C.uint32_t(opt.Routes)
		o.stochastic = C.int32_t(b2i(opt.Stochastic))
		o.reciprocal = C.int32_t(b2i(opt.Reciprocal))
		o.cells = C.int32_t(opt.Cells)
		o.n_pilot = C.uint64_t(opt.NPilot)
		o.n_eval = C.uint64_t(opt.NEval)
		o.batch = C.uint64_t(opt.Batch)
		o.rtol = C.double(opt.RTol)
		o.tolerated = C.double(opt.Tolerated)
		if opt.EscapeTransmittance != nil {
			o.escape_transmittance = C.double(*opt.EscapeTransmittance)
		}
		o.resolution = C.double(opt.Resolution)
	}
	return o
}

// escapeTransmittance checks the value of opt.EscapeTransmittance: C takes
// a negative value as off (nil here), so it would pass -0.5 unseen.  Where
// it is allowed is C's to say (CheckMedium with WeightOverPDF).
func escapeTransmittance(opt *CheckOptions) error {
	if opt == nil || opt.EscapeTransmittance == nil {
		return nil
	}
	if t := *opt.EscapeTransmittance; !(t >= 0 && t <= 1) {
		return invalid(fmt.Sprintf("EscapeTransmittance must be in [0, 1] (the transmittance to the surface), got %v", t))
	}
	return nil
}

// RouteReport is one route's outcome.  Values a route does not produce are
// absent (nil): a skipped route has none, a deterministic one no
// statistic or p-value, a statistical one no Where and Value.
type RouteReport struct {
	Route         Route
	State         RouteState
	Deterministic bool // a tolerance check, not a test
	Reject        bool
	Statistic     *float64
	DF            *float64
	PValue        *float64
	PAdjusted     *float64  // Holm-adjusted across the statistical routes
	Effect        *float64  // the departure measured
	Detectable    *float64  // the smallest departure this run detects with probability 0.8
	NFor1Pct      *float64  // samples needed to detect a 1% departure with probability 0.8
	Checked       uint64    // points checked (CELLS: samples)
	Count         uint64    // points beyond tolerance (CELLS: pooled cells)
	Where         []float64 // deterministic routes: the point of the largest difference
	Value         []float64 // deterministic routes: the two values that differ there
	// Why: state RouteInvalid, why the route could not answer and what
	// would let it (libmcstat's sentence); "" otherwise.
	Why string
	// Resolution: statistical routes, the relative numerical floor they
	// applied (nil for the deterministic ones).
	Resolution *float64
}

// Verdict is a check's verdict.
type Verdict int

const (
	// Consistent: no route rejected, and every route the check needed answered.
	Consistent Verdict = C.MCSTAT_CHECK_CONSISTENT
	// Inconsistent: some route rejected (CheckReport.Reject).
	Inconsistent Verdict = C.MCSTAT_CHECK_INCONSISTENT
	// Inconclusive: no route rejected, but a route the check needed could
	// not answer (CheckReport.Unanswered): "consistent" would claim an
	// error rate the battery did not have.
	Inconclusive Verdict = C.MCSTAT_CHECK_INCONCLUSIVE
)

func (v Verdict) String() string {
	if s := C.mcstat_check_verdict_name(C.int(v)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("Verdict(%d)", int(v))
}

// CheckReport is a renderer check's report; String() is its text block.
// The totals a check cannot form are NaN (a warp has no albedo: no eval()).
type CheckReport struct {
	Kind           CheckKind
	Domain         Domain
	Reject         bool // some route rejected: the model is wrong
	HeavyTailed    bool // a tail index below 2 made routes invalid
	Alpha          float64
	PValue         float64   // smallest adjusted p-value (0 when a deterministic route failed)
	WI             []float64 // BSDFs: the direction checked; nil otherwise
	N, NFailed     uint64    // samples drawn, and how many failed
	NPilot, NEval  uint64
	Cells          uint64 // cells of the tree (before pooling)
	Calls          uint64 // callback calls
	PDFWithoutEval uint64 // points where pdf > 0 but eval = 0 (wasted samples, not an error)
	// ZeroWeight counts samples with weight 0 where the reported pdf and eval
	// are > 0, counted as successes: a sampler that marks a failed sample by
	// its weight alone shows here (mark it by pdf 0 instead).
	ZeroWeight uint64
	// Discrete lobes (Model.Lobes): how many, the samples that fell on
	// them, the sum of their masses and of their values (the discrete part
	// of the albedo; Albedo is the smooth part's); 0 without.
	Lobes      uint64
	NLobe      uint64
	LobeMass   float64
	LobeAlbedo float64
	// CheckMedium with EscapeTransmittance: the mean over the n flights of
	// the escapes' weights (0 for a scattering), which RouteMass tests
	// against T(tmax), and its standard error (NaN with fewer than 2
	// escapes of weight > 0); both NaN otherwise.
	EscapeWeight   float64
	EscapeWeightSE float64
	Mass           float64
	MassError      float64
	MassSampled    float64
	MassSampledSE  float64
	Albedo         float64
	AlbedoSE       float64
	AlbedoEval     float64
	AlbedoEvalSE   float64
	TailIndex      [2]float64    // of the weights, of the eval-only estimates
	Routes         []RouteReport // indexed by Route
	// Verdict: consistent, inconsistent, or inconclusive, with the routes
	// that could not answer (libmcstat's mcstat_check_verdict).
	Verdict    Verdict
	Unanswered []Route
	raw        C.struct_mcstat_check_report
}

func (r *CheckReport) String() string {
	return formatC("check report", func(buf *C.char, size C.size_t, n *C.size_t) C.int {
		return C.mcstat_check_format(&r.raw, buf, size, n)
	})
}

func reportFromC(c *C.struct_mcstat_check_report) *CheckReport {
	r := &CheckReport{Kind: CheckKind(c.kind), Domain: Domain(c.domain), Reject: c.reject != 0,
		HeavyTailed: c.heavy_tailed != 0, Alpha: float64(c.alpha), PValue: float64(c.p_value),
		N: uint64(c.n), NFailed: uint64(c.n_failed), NPilot: uint64(c.n_pilot), NEval: uint64(c.n_eval),
		Cells: uint64(c.cells), Calls: uint64(c.calls), PDFWithoutEval: uint64(c.pdf_without_eval),
		ZeroWeight: uint64(C.gomcstat_zero_weight(c)),
		Lobes:      uint64(C.gomcstat_lobes_count(c)), NLobe: uint64(C.gomcstat_n_lobe(c)),
		LobeMass: float64(C.gomcstat_lobe_mass(c)), LobeAlbedo: float64(C.gomcstat_lobe_albedo(c)),
		EscapeWeight: float64(C.gomcstat_escape_weight(c)), EscapeWeightSE: float64(C.gomcstat_escape_weight_se(c)),
		Mass: float64(c.mass), MassError: float64(c.mass_error), MassSampled: float64(c.mass_sampled),
		MassSampledSE: float64(c.mass_sampled_se), Albedo: float64(c.albedo), AlbedoSE: float64(c.albedo_se),
		AlbedoEval: float64(c.albedo_eval), AlbedoEvalSE: float64(c.albedo_eval_se),
		TailIndex: [2]float64{float64(c.tail_index[0]), float64(c.tail_index[1])}, raw: *c}
	if r.Kind == KindBSDF || r.Kind == KindPhase {
		r.WI = []float64{float64(c.wi[0]), float64(c.wi[1]), float64(c.wi[2])}
	}
	r.Routes = make([]RouteReport, NumRoutes)
	for i := range r.Routes {
		q := &c.route[i]
		r.Routes[i] = RouteReport{Route: Route(i), State: RouteState(q.state), Deterministic: q.deterministic != 0,
			Reject: q.reject != 0, Statistic: optional(q.statistic), DF: optional(q.df), PValue: optional(q.p_value),
			PAdjusted: optional(q.p_adjusted), Effect: optional(q.effect), Detectable: optional(q.detectable),
			NFor1Pct: optional(q.n_for_1pct), Checked: uint64(q.checked), Count: uint64(q.count),
			Where: present(q.where[0], q.where[1], q.where[2]), Value: present(q.value[0], q.value[1]),
			Resolution: optional(C.gomcstat_route_resolution(q))}
		if r.Routes[i].State == RouteInvalid {
			if w := C.mcstat_check_why_text(C.gomcstat_route_why(q)); w != nil {
				r.Routes[i].Why = C.GoString(w)
			}
		}
	}
	var v C.int
	var mask C.uint32_t
	// a report the library wrote: never refused
	if C.mcstat_check_verdict(c, &v, &mask) == C.MCSTAT_OK {
		r.Verdict = Verdict(v)
		for i := 0; i < NumRoutes; i++ {
			if mask&(1<<uint(i)) != 0 {
				r.Unanswered = append(r.Unanswered, Route(i))
			}
		}
	}
	return r
}

// CallbackError is a renderer check stopped by its callbacks; it matches
// ErrCallback with errors.Is.  Err is the Go callback's error (a recovered
// panic becomes a *PanicError), nil when the callback returned invalid
// values (NaN, a point outside the domain, ...) rather than failing.
type CallbackError struct {
	Callback string // "sample", "pdf", "eval" or "lobes" when a Go callback failed
	Message  string // libmcstat's sentence: the callback, the point and the value
	Err      error
}

func (e *CallbackError) Error() string {
	if e.Err != nil {
		return fmt.Sprintf("mcstat: %s callback failed: %v", e.Callback, e.Err)
	}
	return "mcstat: " + e.Message
}

// Is makes errors.Is(err, ErrCallback) true.
func (e *CallbackError) Is(target error) bool {
	t, ok := target.(*Error)
	return ok && t.Status == int(C.MCSTAT_ECALLBACK)
}

func (e *CallbackError) Unwrap() error { return e.Err }

// PanicError is a panic recovered in a check's callback.
type PanicError struct{ Value any }

func (p *PanicError) Error() string { return fmt.Sprintf("panic: %v", p.Value) }

// checkCall is one check in flight: the model and the first failure of its
// callbacks, reached from the C callbacks through a cgo.Handle.
type checkCall struct {
	model    *Model
	dims, nu int
	callback string
	err      error
}

// withModel builds the C model of m, whose callbacks reach m through a
// handle kept in C memory (a Go pointer may not be stored in C memory), and
// runs f with it.  On a refusal, why is C's reason (mcstat_last_error).
// That is the OS thread's, and a goroutine may move to another thread
// between two cgo calls: the call and the read share one locked thread.
func withModel(m *Model, f func(cm *C.struct_mcstat_check_model) C.int) (call *checkCall, st C.int, why string) {
	call = &checkCall{model: m, dims: m.Domain.Dims(), nu: m.NUniforms}
	h := cgo.NewHandle(call)
	defer h.Delete()
	slot := (*C.uintptr_t)(C.malloc(C.size_t(unsafe.Sizeof(C.uintptr_t(0)))))
	defer C.free(unsafe.Pointer(slot))
	*slot = C.uintptr_t(h)
	var cm C.struct_mcstat_check_model
	cm.domain = C.int32_t(m.Domain)
	cm.n_uniforms = C.int32_t(m.NUniforms)
	cm.weight = C.int32_t(m.Weight)
	cm.sample_reports = C.int32_t(b2i(m.SampleReports))
	C.gomcstat_model_callbacks(&cm, unsafe.Pointer(slot), b2i(m.Eval != nil), b2i(m.Lobes != nil))
	runtime.LockOSThread()
	defer runtime.UnlockOSThread()
	if st = f(&cm); st != C.MCSTAT_OK {
		why = C.GoString(C.mcstat_last_error())
	}
	return call, st, why
}

func validModel(m *Model) error {
	switch {
	case m == nil:
		return invalid("model is nil")
	case m.Sample == nil:
		return invalid("model.Sample is nil")
	case m.PDF == nil:
		return invalid("model.PDF is nil")
	}
	return nil
}

func runCheck(m *Model, f func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int) (*CheckReport, error) {
	var out C.struct_mcstat_check_report
	call, st, why := withModel(m, func(cm *C.struct_mcstat_check_model) C.int { return f(cm, &out) })
	if st == C.MCSTAT_ECALLBACK {
		return nil, &CallbackError{Callback: call.callback, Message: C.GoString(&out.message[0]), Err: call.err}
	}
	if st != C.MCSTAT_OK {
		return nil, refusal(st, why)
	}
	return reportFromC(&out), nil
}

// fitsInt32 is false for a Go int that C's int32_t field would wrap.
func fitsInt32(v int) bool { return v >= math.MinInt32 && v <= math.MaxInt32 }

// checkArgs gives the C options, refusing only what C cannot see: a model
// without Go functions, and values the conversion would change (n < 0, a
// Cells or NUniforms past int32, a negative EscapeTransmittance, which C
// takes for off).  The ranges are C's, and so are the reasons it refuses
// them with (refusal).
func checkArgs(m *Model, n int, opt *CheckOptions) (C.struct_mcstat_check_options, error) {
	fail := func(err error) (C.struct_mcstat_check_options, error) { return C.struct_mcstat_check_options{}, err }
	if err := validModel(m); err != nil {
		return fail(err)
	}
	if n < 0 {
		return fail(invalid(fmt.Sprintf("n must be >= 0 (a size_t), got %d", n)))
	}
	if !fitsInt32(m.NUniforms) {
		return fail(invalid(fmt.Sprintf("Model.NUniforms %d does not fit C's int32_t", m.NUniforms)))
	}
	if opt != nil && !fitsInt32(opt.Cells) {
		return fail(invalid(fmt.Sprintf("CheckOptions.Cells %d does not fit C's int32_t", opt.Cells)))
	}
	if err := escapeTransmittance(opt); err != nil {
		return fail(err)
	}
	return opt.toC(), nil
}

// CheckBSDF checks a BSDF's sample(), pdf(), eval() and weights at the
// incident direction wi with n >= 1000 samples at battery level alpha;
// opt nil means DefaultCheckOptions().  Reproducible for a given seed.
func CheckBSDF(m *Model, wi [3]float64, n int, seed uint64, alpha float64, opt *CheckOptions) (*CheckReport, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return nil, err
	}
	w := [3]C.double{C.double(wi[0]), C.double(wi[1]), C.double(wi[2])}
	return runCheck(m, func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int {
		return C.mcstat_check_bsdf(cm, &w[0], C.size_t(n), C.uint64_t(seed), C.double(alpha), &o, nil, 0, out)
	})
}

// CheckEmitter checks an emitter's direction sampling (domain Sphere or
// Hemisphere; the reference point is the callbacks' business).
func CheckEmitter(m *Model, n int, seed uint64, alpha float64, opt *CheckOptions) (*CheckReport, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return nil, err
	}
	return runCheck(m, func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int {
		return C.mcstat_check_emitter(cm, C.size_t(n), C.uint64_t(seed), C.double(alpha), &o, nil, 0, out)
	})
}

// CheckWarp checks a warp (a sampler and its density; Eval is ignored).
func CheckWarp(m *Model, n int, seed uint64, alpha float64, opt *CheckOptions) (*CheckReport, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return nil, err
	}
	return runCheck(m, func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int {
		return C.mcstat_check_warp(cm, C.size_t(n), C.uint64_t(seed), C.double(alpha), &o, nil, 0, out)
	})
}

// CheckPhase checks a phase function p(wi, wo) (domain Sphere; Eval is p,
// no cosine): the routes of CheckBSDF, with RouteEnergy testing albedo == 1
// (two-sided) and RouteReciprocity (when asked) p(wi, wo) == p(wo, wi).
func CheckPhase(m *Model, wi [3]float64, n int, seed uint64, alpha float64, opt *CheckOptions) (*CheckReport, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return nil, err
	}
	w := [3]C.double{C.double(wi[0]), C.double(wi[1]), C.double(wi[2])}
	return runCheck(m, func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int {
		return C.mcstat_check_phase(cm, &w[0], C.size_t(n), C.uint64_t(seed), C.double(alpha), &o, nil, 0, out)
	})
}

// CheckMedium checks distance sampling along a ray (domain Interval): the
// callbacks' points are distances t >= 0, mapped inside to x = 1 -
// exp(-sigmaRef t); a flight that passes the surface is a failed sample
// (pdf 0, weight 0), or with opt.EscapeTransmittance one that reports pdf
// 0 and the weight it carries on; Eval is sigma_s T(t).
func CheckMedium(m *Model, sigmaRef float64, n int, seed uint64, alpha float64, opt *CheckOptions) (*CheckReport, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return nil, err
	}
	return runCheck(m, func(cm *C.struct_mcstat_check_model, out *C.struct_mcstat_check_report) C.int {
		return C.mcstat_check_medium(cm, C.double(sigmaRef), C.size_t(n), C.uint64_t(seed), C.double(alpha), &o, nil,
			0, out)
	})
}

// CheckWorkSize is the scratch memory, in bytes, a check of m with n
// samples allocates (and frees) inside the call.  It refuses what the
// checks refuse, with C's reason.
func CheckWorkSize(m *Model, n int, opt *CheckOptions) (int, error) {
	o, err := checkArgs(m, n, opt)
	if err != nil {
		return 0, err
	}
	var bytes C.size_t
	_, st, why := withModel(m, func(cm *C.struct_mcstat_check_model) C.int {
		return C.mcstat_check_work_size(cm, C.size_t(n), &o, &bytes)
	})
	if st != C.MCSTAT_OK {
		return 0, refusal(st, why)
	}
	return int(bytes), nil
}
