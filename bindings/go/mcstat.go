// Package mcstat binds libmcstat, statistical hypothesis tests for Monte
// Carlo estimators, through cgo.  The library is found with pkg-config
// through mcstat-rpath.pc, installed beside mcstat.pc by `cmake --install`:
// it adds a run path to the installed library, so programs and tests run
// without LD_LIBRARY_PATH (cgo takes only --cflags and --libs from
// pkg-config and cannot compute a run path itself).  For a non-system
// prefix set PKG_CONFIG_PATH to the absolute path of PREFIX/lib/pkgconfig.
//
// The numbers, decisions and R-style text are computed by libmcstat; this
// package converts types and errors.  Errors are *Error values carrying the
// C status and its sentence (for a renderer check's refusal, C's reason,
// naming the field and its value); compare with errors.Is against the Err*
// sentinels:
//
//	r, err := mcstat.TTest2(newEst, trusted, 0, mcstat.TwoSided, 0.05)
//	if errors.Is(err, mcstat.ErrDegenerate) { ... }
//	fmt.Print(r)                          // R's print.htest block + the decision
//	fmt.Print(r.Format("new", "trusted"))
//
// The families, in the order of mcstat.h:
//
//   - accumulators: Moments (MarshalBinary is the portable 96-byte form),
//     MomentsRows (one per pixel), Stream (a renderer thread's buffer);
//   - the tests: TTest1, TTest2 (Welch), VarTest1, VarTest2 (F) on slices
//     and on accumulators, KSTest2 (KSOptions, KSCache);
//   - per-pixel rows: the *Matrix tests on a Matrix and the *Rows tests on
//     a MomentsRows, one RowResult (a Result or an error) per row;
//   - PAdjust (R's p.adjust); NewEscalation (a two-stage test instead of
//     reruns); EquivalenceTest1/2 (TOST);
//   - PowerOptions (Compute, Solve, String as R's power.t.test);
//   - Diagnose, TailIndex, TSize, BatchSize;
//   - GOFChisqTest, BinomTest, BatteryTest, BatteryTestPValues;
//   - CheckBSDF, CheckEmitter, CheckWarp, CheckPhase, CheckMedium: a
//     Model's Go functions called back from libmcstat (an error or panic
//     in one ends the check with an error matching ErrCallback);
//     Model.Lobes gives a BSDF's discrete (specular) lobes,
//     CheckOptions.EscapeTransmittance has a medium's escape weights
//     checked;
//   - Sequential: anytime-valid tests looked at after every batch
//     (NewSequential, Push, PushStream, Result, Finish);
//   - the t, chi-squared and F distributions (TCDF, ...);
//   - Version, VersionNumber, CheckABI, GSLHandlerOff.
//
// Result fields that do not apply to a test are absent (nil, or a shorter
// slice), never NaN placeholders.  Bad input gives an error, never a panic.
package mcstat

// #cgo pkg-config: mcstat-rpath
// #cgo CFLAGS: -DMCSTAT_EXPERIMENTAL
// #include <stdlib.h>
// #include <mcstat.h>
//
// /* mcstat_result's per-test outputs live in anonymous unions, which cgo
//    cannot name: read them here. */
// static int32_t gomcstat_ks_weight(const mcstat_result *r) { return r->ks_weight; }
// static double gomcstat_ks_critical_se(const mcstat_result *r) { return r->ks_critical_se; }
// static double gomcstat_ks_n_sim(const mcstat_result *r) { return r->ks_n_sim; }
// static double gomcstat_binom_log_p_value(const mcstat_result *r) { return r->binom_log_p_value; }
// static void gomcstat_tost(const mcstat_result *r, double d[6]) {
//     d[0] = r->tost_t_lower; d[1] = r->tost_t_upper; d[2] = r->tost_p_lower;
//     d[3] = r->tost_p_upper; d[4] = r->tost_lower; d[5] = r->tost_upper;
// }
// static void gomcstat_gof(const mcstat_result *r, double d[3], int i[2]) {
//     d[0] = r->chisq_cells_given; d[1] = r->chisq_min_expected; d[2] = r->chisq_pool_below;
//     i[0] = r->chisq_cells; i[1] = r->chisq_n_estimated;
// }
// static void gomcstat_eff(const mcstat_result *r, double d[6], int i[2]) {
//     d[0] = r->eff_var_ratio; d[1] = r->eff_time_ratio; d[2] = r->eff_se_log_var_x;
//     d[3] = r->eff_se_log_var_y; d[4] = r->eff_se_log_time_x; d[5] = r->eff_se_log_time_y;
//     i[0] = r->eff_batches_x; i[1] = r->eff_batches_y;
// }
import "C"

import (
	"fmt"
	"math"
	"runtime"
	"unsafe"
)

// ---- errors --------------------------------------------------------------------

// Error is a non-zero libmcstat status with a message: mcstat_strerror's
// sentence, or one naming what is wrong.  The renderer checks (CheckBSDF,
// CheckEmitter, CheckWarp, CheckPhase, CheckMedium, CheckWorkSize) and the
// t and variance tests (TTest1, VarTest2, their Moments forms, ...) give
// libmcstat's reason for every ErrInvalidArgument and ErrTooBig they
// return (C's mcstat_last_error(), read on the OS thread of the call),
// verbatim: it names the field as C spells it, with C's prefix, e.g.
// "options.cells must be 0 (automatic) or 2..1048576, got 1" for
// CheckOptions.Cells, "model.n_uniforms must be in 1..8, got 9" for
// Model.NUniforms, "alpha must be in (0, 1), got 1.5".
type Error struct {
	Status  int
	Message string
}

func (e *Error) Error() string { return fmt.Sprintf("mcstat: %s (status %d)", e.Message, e.Status) }

// Is makes errors.Is(err, ErrX) compare statuses.
func (e *Error) Is(target error) bool {
	t, ok := target.(*Error)
	return ok && t.Status == e.Status
}

func newError(status C.int) *Error {
	return &Error{Status: int(status), Message: C.GoString(C.mcstat_strerror(status))}
}

// Sentinels, one per status (match them with errors.Is).
var (
	ErrInvalidArgument = newError(C.MCSTAT_EINVAL)
	ErrTooFew          = newError(C.MCSTAT_ETOOFEW)
	ErrNonFinite       = newError(C.MCSTAT_ENONFINITE)
	ErrDegenerate      = newError(C.MCSTAT_EDEGENERATE)
	ErrNoMemory        = newError(C.MCSTAT_ENOMEM)
	ErrNumeric         = newError(C.MCSTAT_ENUMERIC)
	ErrBufferSize      = newError(C.MCSTAT_EBUFSIZE)
	ErrCorrupt         = newError(C.MCSTAT_ECORRUPT)
	ErrTooBig          = newError(C.MCSTAT_ETOOBIG)
	ErrCallback        = newError(C.MCSTAT_ECALLBACK) // a renderer check's callback failed (mcstat/check.h)
	// ErrHeavyTail: a sequential test ended with its kurtosis gate closed
	// (Sequential.Finish returns it as a *HeavyTailError).
	ErrHeavyTail = newError(C.MCSTAT_EHEAVYTAIL)
)

func check(status C.int) error {
	if status == C.MCSTAT_OK {
		return nil
	}
	return newError(status)
}

// refusal is the error of a failing status of a function that gives
// reasons: why is its mcstat_last_error(), read on the OS thread of the
// call (withModel), or "" for none, which leaves the status's sentence.
func refusal(status C.int, why string) error {
	e := newError(status)
	if why != "" {
		e.Message = why
	}
	return e
}

// Version of the linked library, "MAJOR.MINOR.PATCH".
func Version() string { return C.GoString(C.mcstat_version()) }

// ---- enums ---------------------------------------------------------------------

// Alternative is a claim about the first sample: Less means mean(x) < mu0
// (or var(x) < sigma2, mean(x) < mean(y), ...; for K-S, x tends to be smaller).
type Alternative int

const (
	TwoSided Alternative = C.MCSTAT_TWO_SIDED
	Less     Alternative = C.MCSTAT_LESS
	Greater  Alternative = C.MCSTAT_GREATER
)

// ParseAlternative accepts "two-sided" (also "two.sided", "two_sided"), "less", "greater".
func ParseAlternative(name string) (Alternative, error) {
	cs := C.CString(name)
	defer C.free(unsafe.Pointer(cs))
	var v C.int
	if err := check(C.mcstat_alternative_parse(cs, &v)); err != nil {
		return TwoSided, err
	}
	return Alternative(v), nil
}

func (a Alternative) String() string {
	if s := C.mcstat_alternative_name(C.int(a)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("Alternative(%d)", int(a))
}

// Decision is the paper's three-way outcome.
type Decision int

const (
	DecisionLess    Decision = -1
	DecisionEqual   Decision = 0
	DecisionGreater Decision = 1
)

func (d Decision) String() string { return C.GoString(C.mcstat_decision_name(C.int(d))) }

// Test identifies the test that produced a Result.
type Test int

const (
	TestT1       Test = C.MCSTAT_TEST_T_1        // one-sample t
	TestT2       Test = C.MCSTAT_TEST_T_2        // Welch's two-sample t
	TestVar1     Test = C.MCSTAT_TEST_VAR_1      // one-sample chi-squared test of the variance
	TestVar2     Test = C.MCSTAT_TEST_VAR_2      // F test of the ratio of variances
	TestKS2      Test = C.MCSTAT_TEST_KS_2       // two-sample Kolmogorov-Smirnov
	TestEquiv1   Test = C.MCSTAT_TEST_EQUIV_1    // one-sample equivalence (TOST)
	TestEquiv2   Test = C.MCSTAT_TEST_EQUIV_2    // Welch two-sample equivalence (TOST)
	TestBinom    Test = C.MCSTAT_TEST_BINOM      // exact binomial test (also the battery meta-test)
	TestChisqGOF Test = C.MCSTAT_TEST_CHISQ_GOF  // Pearson's chi-squared goodness of fit
	TestT2Pooled Test = C.MCSTAT_TEST_T_2_POOLED // Student's pooled-variance two-sample t
	TestTPaired  Test = C.MCSTAT_TEST_T_PAIRED   // paired t (the differences' one-sample t)
	TestSeqMean1 Test = C.MCSTAT_TEST_SEQ_MEAN_1 // sequential (anytime-valid) test of a mean (Sequential)
	TestSeqMean2 Test = C.MCSTAT_TEST_SEQ_MEAN_2 // sequential test of a difference of means
	TestSeqVar1  Test = C.MCSTAT_TEST_SEQ_VAR_1  // sequential test of a variance
	TestSeqVar2  Test = C.MCSTAT_TEST_SEQ_VAR_2  // sequential test of a ratio of variances
	// TestEfficiency is the ratio of two estimators' efficiencies, 1 / (variance x time).
	TestEfficiency Test = C.MCSTAT_TEST_EFFICIENCY
)

var testNames = map[Test]string{TestT1: "t_1", TestT2: "t_2", TestVar1: "var_1", TestVar2: "var_2",
	TestKS2: "ks_2", TestEquiv1: "equiv_1", TestEquiv2: "equiv_2", TestBinom: "binom", TestChisqGOF: "chisq_gof",
	TestT2Pooled: "t_2_pooled", TestTPaired: "t_paired", TestEfficiency: "efficiency", TestSeqMean1: "seq_mean_1",
	TestSeqMean2: "seq_mean_2", TestSeqVar1: "seq_var_1", TestSeqVar2: "seq_var_2"}

func (t Test) String() string {
	if s, ok := testNames[t]; ok {
		return s
	}
	return fmt.Sprintf("Test(%d)", int(t))
}

// oneSample reports whether the test has a single sample (N has one entry).
func (t Test) oneSample() bool {
	return t == TestT1 || t == TestVar1 || t == TestEquiv1 || t == TestBinom || t == TestChisqGOF ||
		t == TestSeqMean1 || t == TestSeqVar1
}

// Method says how a p-value was obtained (Auto only as a K-S option).
type Method int

const (
	MethodAnalytic   Method = C.MCSTAT_METHOD_ANALYTIC
	MethodAuto       Method = C.MCSTAT_METHOD_AUTO
	MethodExact      Method = C.MCSTAT_METHOD_EXACT
	MethodSimulate   Method = C.MCSTAT_METHOD_SIMULATE
	MethodAsymptotic Method = C.MCSTAT_METHOD_ASYMPTOTIC
)

// KSWeight is the K-S statistic's weight.
type KSWeight int

const (
	KSWeightNone   KSWeight = C.MCSTAT_KS_WEIGHT_NONE   // Smirnov's D = sup |F - G|
	KSWeightCanner KSWeight = C.MCSTAT_KS_WEIGHT_CANNER // the paper's D2
)

// ---- results -------------------------------------------------------------------

// Result is a test's outcome, copied from libmcstat's mcstat_result.  A
// field that does not apply to the test is absent rather than NaN: a nil
// slice or pointer, or a slice holding only the entries that apply (DF has
// one entry for a t test, two for F, none for K-S).  String() is the R-style
// block with the data named "x" and "y"; Format names them.
type Result struct {
	Test        Test
	Method      Method      // how the p-value was obtained
	Alternative Alternative // GOF: Greater; TOST: TwoSided (unused)
	Reject      bool        // H0 rejected at Alpha (TOST: equivalence shown)
	Decision    Decision    // the paper's three-way outcome
	N           []uint64    // per sample (binomial: trials; GOF: total count)
	Statistic   float64     // t, X-squared, F, D (K-S), x (binomial)
	DF          []float64   // degrees of freedom: t, chi-squared 1 entry, F 2; K-S, binomial none
	PValue      float64
	PValueSE    float64   // Monte Carlo standard error of a simulated p-value; 0 when exact
	ConfInt     []float64 // [lower, upper] at 1-Alpha (TOST: 1-2 Alpha), an open end +-Inf; nil when none was computed
	Estimate    []float64 // mean(s), variance, ratio of variances, proportion; nil for K-S and GOF
	NullValue   *float64  // mu0, sigma0^2, ratio or p under H0; nil for K-S and GOF
	Alpha       float64
	// Critical is [lower, upper]: reject when Statistic < Critical[0] or >
	// Critical[1] (an absent side is -Inf or +Inf).  For the binomial test
	// it is the acceptance region of counts.  nil when not computed (K-S
	// with Critical false, rows with NoIntervals).
	Critical []float64
	StdError *float64 // standard error of the estimate (t tests, TOST); nil otherwise

	KS    *KSDetails    // K-S only
	TOST  *TOSTDetails  // equivalence tests only
	Binom *BinomDetails // binomial and battery tests only
	GOF   *GOFDetails   // chi-squared goodness of fit only
	Seq   *SeqDetails   // sequential tests only (Statistic is NaN while one holds: read Seq.Z)
	Eff   *EffDetails   // efficiency-ratio test only

	raw C.struct_mcstat_result
}

// KSDetails are the K-S test's own outputs.
type KSDetails struct {
	Weight     KSWeight
	CriticalSE float64 // Monte Carlo standard error of Critical[1]; 0 unless simulated
	NSim       float64 // replicates simulated; 0 unless simulated
}

// TOSTDetails are the two one-sided tests of an equivalence test.
type TOSTDetails struct {
	TLower, TUpper float64 // t for H1: mean > Lower, and for H1: mean < Upper
	PLower, PUpper float64 // their one-sided p-values
	Lower, Upper   float64 // the bounds tested (mu0 + lower, mu0 + upper)
}

// BinomDetails are the binomial test's own outputs.
type BinomDetails struct {
	LogPValue float64 // log(PValue), finite where PValue underflows to 0
}

// GOFDetails are the chi-squared goodness-of-fit test's own outputs.
type GOFDetails struct {
	Cells       int     // cells after pooling
	NEstimated  int     // parameters estimated from the counts
	CellsGiven  int     // cells given (k)
	MinExpected float64 // smallest expected count after pooling
	PoolBelow   float64 // the pooling threshold; 0 when pooling was off
}

// EffDetails are the efficiency-ratio test's own outputs: the factors of
// the ratio (y over x: above 1 is x's advantage) and the delta-method
// standard errors of the four logs.
type EffDetails struct {
	VarRatio, TimeRatio    float64 // s_y^2 / s_x^2, mean time y / mean time x
	SELogVarX, SELogVarY   float64
	SELogTimeX, SELogTimeY float64
	BatchesX, BatchesY     int // timed batches
}

// present returns v without its trailing NaN entries (nil when none is left).
func present(v ...C.double) []float64 {
	n := len(v)
	for n > 0 && math.IsNaN(float64(v[n-1])) {
		n--
	}
	if n == 0 {
		return nil
	}
	out := make([]float64, n)
	for i := range out {
		out[i] = float64(v[i])
	}
	return out
}

// pair returns [a, b], or nil when either is NaN (not computed).
func pair(a, b C.double) []float64 {
	if math.IsNaN(float64(a)) || math.IsNaN(float64(b)) {
		return nil
	}
	return []float64{float64(a), float64(b)}
}

func optional(v C.double) *float64 {
	if math.IsNaN(float64(v)) {
		return nil
	}
	f := float64(v)
	return &f
}

func fromC(r *C.struct_mcstat_result) *Result {
	t := Test(r.test)
	n := []uint64{uint64(r.n[0]), uint64(r.n[1])}
	if t.oneSample() {
		n = n[:1]
	}
	res := &Result{
		Test: t, Method: Method(r.method), Alternative: Alternative(r.alternative),
		Reject: r.reject != 0, Decision: Decision(r.decision), N: n,
		Statistic: float64(r.statistic), DF: present(r.df[0], r.df[1]),
		PValue: float64(r.p_value), PValueSE: float64(r.p_value_se),
		ConfInt:   pair(r.conf_int[0], r.conf_int[1]),
		Estimate:  present(r.estimate[0], r.estimate[1]),
		NullValue: optional(r.null_value), Alpha: float64(r.alpha),
		Critical: pair(r.critical[0], r.critical[1]), StdError: optional(r.std_error),
		raw: *r,
	}
	switch t {
	case TestKS2:
		res.KS = &KSDetails{Weight: KSWeight(C.gomcstat_ks_weight(r)),
			CriticalSE: float64(C.gomcstat_ks_critical_se(r)), NSim: float64(C.gomcstat_ks_n_sim(r))}
	case TestEquiv1, TestEquiv2:
		var d [6]C.double
		C.gomcstat_tost(r, &d[0])
		res.TOST = &TOSTDetails{TLower: float64(d[0]), TUpper: float64(d[1]), PLower: float64(d[2]),
			PUpper: float64(d[3]), Lower: float64(d[4]), Upper: float64(d[5])}
	case TestBinom:
		res.Binom = &BinomDetails{LogPValue: float64(C.gomcstat_binom_log_p_value(r))}
	case TestChisqGOF:
		var d [3]C.double
		var i [2]C.int
		C.gomcstat_gof(r, &d[0], &i[0])
		res.GOF = &GOFDetails{Cells: int(i[0]), NEstimated: int(i[1]), CellsGiven: int(d[0]),
			MinExpected: float64(d[1]), PoolBelow: float64(d[2])}
	case TestSeqMean1, TestSeqMean2, TestSeqVar1, TestSeqVar2:
		res.Seq = seqDetails(r)
	case TestEfficiency:
		var d [6]C.double
		var i [2]C.int
		C.gomcstat_eff(r, &d[0], &i[0])
		res.Eff = &EffDetails{VarRatio: float64(d[0]), TimeRatio: float64(d[1]), SELogVarX: float64(d[2]),
			SELogVarY: float64(d[3]), SELogTimeX: float64(d[4]), SELogTimeY: float64(d[5]),
			BatchesX: int(i[0]), BatchesY: int(i[1])}
	}
	return res
}

// Format returns the R-style block (R's print.htest plus a "decision at
// alpha" line) with the data named xName and yName.
func (r *Result) Format(xName, yName string) string {
	if r == nil {
		return "<nil>"
	}
	xn, yn := C.CString(xName), C.CString(yName)
	defer C.free(unsafe.Pointer(xn))
	defer C.free(unsafe.Pointer(yn))
	return formatC("result", func(buf *C.char, size C.size_t, n *C.size_t) C.int {
		return C.mcstat_result_format(&r.raw, xn, yn, buf, size, n)
	})
}

func (r *Result) String() string { return r.Format("x", "y") }

func ptr(x []float64) *C.double {
	if len(x) == 0 {
		return nil
	}
	return (*C.double)(unsafe.Pointer(&x[0]))
}

func run(f func(out *C.struct_mcstat_result) C.int) (*Result, error) {
	var out C.struct_mcstat_result
	if err := check(f(&out)); err != nil {
		return nil, err
	}
	return fromC(&out), nil
}

// runReasons is run for the calls that give reasons (the t and variance
// tests): a refusal carries C's reason, read on the OS thread of the call.
func runReasons(f func(out *C.struct_mcstat_result) C.int) (*Result, error) {
	var out C.struct_mcstat_result
	runtime.LockOSThread()
	defer runtime.UnlockOSThread()
	if st := f(&out); st != C.MCSTAT_OK {
		return nil, refusal(st, C.GoString(C.mcstat_last_error()))
	}
	return fromC(&out), nil
}

// ---- the tests on slices -------------------------------------------------------

// TTest1 is the one-sample t test of mean(x) against mu0.
func TTest1(x []float64, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_1(ptr(x), C.size_t(len(x)), C.double(mu0), C.int(alt), C.double(alpha), o)
	})
}

// TTest2 is Welch's two-sample t test of mean(x) - mean(y) against mu0.
func TTest2(x, y []float64, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_2(ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y)), C.double(mu0), C.int(alt),
			C.double(alpha), o)
	})
}

// TTest2Pooled is Student's pooled-variance two-sample t test of mean(x) -
// mean(y) against mu0 (R's t.test(var.equal = TRUE), SciPy's ttest_ind
// default).
func TTest2Pooled(x, y []float64, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_2_pooled(ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y)), C.double(mu0),
			C.int(alt), C.double(alpha), o)
	})
}

// TTestPaired is the paired t test of mean(x - y) against mu0 (R's
// t.test(paired = TRUE), SciPy's ttest_rel); x and y have the same length.
func TTestPaired(x, y []float64, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	if len(x) != len(y) {
		return nil, invalid(fmt.Sprintf("paired samples differ in length: x has %d, y %d", len(x), len(y)))
	}
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_paired(ptr(x), ptr(y), C.size_t(len(x)), C.double(mu0), C.int(alt),
			C.double(alpha), o)
	})
}

// LogPValue is the natural logarithm of the p-value, finite wherever the
// tail is representable in log, also where PValue underflows to 0.
func (r *Result) LogPValue() (float64, error) {
	if r == nil {
		return 0, invalid("nil *Result")
	}
	var v C.double
	if err := check(C.mcstat_result_log_p_value(&r.raw, &v)); err != nil {
		return 0, err
	}
	return float64(v), nil
}

// ConfIntAt is the confidence interval at confidenceLevel in (0, 1)
// instead of 1 - Alpha (a one-sided alternative keeps its infinite end);
// an error for tests without a parameter interval (K-S, goodness of fit).
func (r *Result) ConfIntAt(confidenceLevel float64) ([2]float64, error) {
	if r == nil {
		return [2]float64{}, invalid("nil *Result")
	}
	var ci [2]C.double
	if err := check(C.mcstat_result_conf_int(&r.raw, C.double(confidenceLevel), &ci[0])); err != nil {
		return [2]float64{}, err
	}
	return [2]float64{float64(ci[0]), float64(ci[1])}, nil
}

// VarTest1 is the one-sample chi-squared test of var(x) against sigma2.
func VarTest1(x []float64, sigma2 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_var_test_1(ptr(x), C.size_t(len(x)), C.double(sigma2), C.int(alt), C.double(alpha), o)
	})
}

// VarTest2 is the F test of var(x)/var(y) against ratio.
func VarTest2(x, y []float64, ratio float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_var_test_2(ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y)), C.double(ratio), C.int(alt),
			C.double(alpha), o)
	})
}

// ---- accumulators --------------------------------------------------------------

// Moments is a streaming, mergeable accumulator (mcstat_moments, 128 bytes).
// The zero value is an empty accumulator.  Not safe for concurrent use.
type Moments struct{ raw C.struct_mcstat_moments }

// NewMoments returns an empty accumulator.
func NewMoments() *Moments {
	m := &Moments{}
	C.mcstat_moments_init(&m.raw)
	return m
}

// c is the C accumulator, initialised on first use (the zero value is
// empty), or NULL for a nil m (libmcstat then refuses with
// ErrInvalidArgument).
func (m *Moments) c() *C.struct_mcstat_moments {
	if m == nil {
		return nil
	}
	if m.raw.version == 0 && m.raw.n == 0 {
		C.mcstat_moments_init(&m.raw)
	}
	return &m.raw
}

// Add adds one value (ErrNonFinite for NaN or Inf; m unchanged).
func (m *Moments) Add(x float64) error { return check(C.mcstat_moments_add(m.c(), C.double(x))) }

// AddSlice adds values (ErrNonFinite if any is NaN or Inf; m unchanged).
func (m *Moments) AddSlice(x []float64) error {
	return check(C.mcstat_moments_add_array(m.c(), ptr(x), C.size_t(len(x))))
}

// AddSliceOmitNaN adds values, skipping NaN ones, and returns how many it
// skipped (ErrNonFinite if any is +-Inf; m unchanged).
func (m *Moments) AddSliceOmitNaN(x []float64) (omitted int, err error) {
	var o C.size_t
	if err := check(C.mcstat_moments_add_array_omit_nan(m.c(), ptr(x), C.size_t(len(x)), &o)); err != nil {
		return 0, err
	}
	return int(o), nil
}

// MomentsFromSummary returns an accumulator standing for n values of mean
// `mean` and sum of squared deviations m2 = (n-1) var, as read from a file of
// summaries: the t and variance tests on it give exactly the summary's
// results (its skewness, kurtosis, min and max describe a two-point
// stand-in, not the data).  ErrTooFew for n == 0, ErrInvalidArgument for
// m2 < 0, ErrNonFinite for NaN or Inf.
func MomentsFromSummary(n uint64, mean, m2 float64) (*Moments, error) {
	m := &Moments{}
	if err := check(C.mcstat_moments_from_summary(C.uint64_t(n), C.double(mean), C.double(m2), &m.raw)); err != nil {
		return nil, err
	}
	return m, nil
}

// Merge merges other into m exactly.
func (m *Moments) Merge(other *Moments) error {
	return check(C.mcstat_moments_merge(m.c(), other.c()))
}

// N is the number of values added.
func (m *Moments) N() uint64 {
	if c := m.c(); c != nil {
		return uint64(c.n)
	}
	return 0
}

// Mean, Var, SD, Skewness (g1) and Kurtosis (excess g2) are NaN when
// undefined (too few values).
func (m *Moments) Mean() float64     { return float64(C.mcstat_moments_mean(m.c())) }
func (m *Moments) Var() float64      { return float64(C.mcstat_moments_var(m.c())) }
func (m *Moments) SD() float64       { return float64(C.mcstat_moments_sd(m.c())) }
func (m *Moments) Skewness() float64 { return float64(C.mcstat_moments_skewness(m.c())) }
func (m *Moments) Kurtosis() float64 { return float64(C.mcstat_moments_kurtosis(m.c())) }

// Min and Max are the extreme values added (+Inf and -Inf when empty).
func (m *Moments) Min() float64 {
	if c := m.c(); c != nil {
		return float64(c.min)
	}
	return math.Inf(1)
}

func (m *Moments) Max() float64 {
	if c := m.c(); c != nil {
		return float64(c.max)
	}
	return math.Inf(-1)
}

// MarshalBinary writes the portable, versioned, checksummed form (96 bytes).
func (m *Moments) MarshalBinary() ([]byte, error) {
	b := make([]byte, C.MCSTAT_MOMENTS_BYTES)
	if err := check(C.mcstat_moments_to_bytes(m.c(), (*C.uchar)(unsafe.Pointer(&b[0])), C.size_t(len(b)))); err != nil {
		return nil, err
	}
	return b, nil
}

// UnmarshalBinary reads MarshalBinary's form (ErrCorrupt for damaged bytes; m unchanged).
func (m *Moments) UnmarshalBinary(b []byte) error {
	if len(b) == 0 {
		return newError(C.MCSTAT_ECORRUPT)
	}
	if m == nil {
		return invalid("UnmarshalBinary into a nil *Moments")
	}
	var tmp C.struct_mcstat_moments
	if err := check(C.mcstat_moments_from_bytes((*C.uchar)(unsafe.Pointer(&b[0])), C.size_t(len(b)), &tmp)); err != nil {
		return err
	}
	m.raw = tmp
	return nil
}

// TTest1Moments is TTest1 on an accumulator.
func TTest1Moments(x *Moments, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_1_moments(x.c(), C.double(mu0), C.int(alt), C.double(alpha), o)
	})
}

// TTest2Moments is TTest2 on accumulators.
func TTest2Moments(x, y *Moments, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_2_moments(x.c(), y.c(), C.double(mu0), C.int(alt), C.double(alpha), o)
	})
}

// EfficiencyTest tests rho = eff(x) / eff(y) = (var_y tau_y) / (var_x
// tau_x) against ratio: x and y accumulate the estimators' samples, timeX
// and timeY the time per sample of k >= 2 timed batches each.  The
// standard error of log rho is the delta method's without assuming normal
// data, the statistic a t on Satterthwaite's df; Greater means x is the
// more efficient (mcstat.h, "Efficiency ratio of two estimators").
func EfficiencyTest(x, y, timeX, timeY *Moments, ratio float64, alt Alternative, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_efficiency_test(x.c(), y.c(), timeX.c(), timeY.c(), C.double(ratio), C.int(alt),
			C.double(alpha), o)
	})
}

// TTest2PooledMoments is TTest2Pooled on accumulators.
func TTest2PooledMoments(x, y *Moments, mu0 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_t_test_2_pooled_moments(x.c(), y.c(), C.double(mu0), C.int(alt), C.double(alpha), o)
	})
}

// VarTest1Moments is VarTest1 on an accumulator.
func VarTest1Moments(x *Moments, sigma2 float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_var_test_1_moments(x.c(), C.double(sigma2), C.int(alt), C.double(alpha), o)
	})
}

// VarTest2Moments is VarTest2 on accumulators.
func VarTest2Moments(x, y *Moments, ratio float64, alt Alternative, alpha float64) (*Result, error) {
	return runReasons(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_var_test_2_moments(x.c(), y.c(), C.double(ratio), C.int(alt), C.double(alpha), o)
	})
}

// ---- Kolmogorov-Smirnov ---------------------------------------------------------

// KSCache holds simulated null distributions shared by K-S tests (safe for
// concurrent use: libmcstat locks it).  Close frees it.
type KSCache struct{ raw *C.struct_mcstat_ks_cache }

// NewKSCache makes a cache of at most maxBytes (least recently used dropped).
func NewKSCache(maxBytes int) (*KSCache, error) {
	c := &KSCache{}
	if err := check(C.mcstat_ks_cache_new(C.size_t(maxBytes), &c.raw)); err != nil {
		return nil, err
	}
	return c, nil
}

// Close frees the cache; no test may be using it.
func (c *KSCache) Close() {
	if c == nil {
		return
	}
	C.mcstat_ks_cache_free(c.raw)
	c.raw = nil
}

// Stats returns the lookups that hit, those that missed, and the entries held.
func (c *KSCache) Stats() (hits, misses, entries uint64) {
	var h, m, e C.uint64_t
	if c == nil {
		return 0, 0, 0
	}
	C.mcstat_ks_cache_stats(c.raw, &h, &m, &e)
	return uint64(h), uint64(m), uint64(e)
}

// ksOptionsInit is libmcstat's default options, initialised for the size of
// the struct this package was compiled against (cgo cannot call the
// header's mcstat_ks_options_init macro).
func ksOptionsInit() C.struct_mcstat_ks_options {
	var o C.struct_mcstat_ks_options
	C.mcstat_ks_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// KSOptions are the K-S test's options; start from DefaultKSOptions.
type KSOptions struct {
	Weight   KSWeight
	Method   Method
	Threads  int
	NSim     int64
	Seed     uint64
	Critical bool // compute Critical[1]
	Cache    *KSCache
}

// DefaultKSOptions returns libmcstat's defaults (Canner's weight, method
// auto, 1 thread (none started), 10000 simulations, seed 0, critical value
// computed).
func DefaultKSOptions() KSOptions {
	o := ksOptionsInit()
	return KSOptions{Weight: KSWeight(o.weight), Method: Method(o.method), Threads: int(o.threads),
		NSim: int64(o.n_sim), Seed: uint64(o.seed), Critical: o.critical != 0}
}

// KSTest2 is the two-sample Kolmogorov-Smirnov test of x against y; opt nil
// means DefaultKSOptions().
func KSTest2(x, y []float64, alt Alternative, alpha float64, opt *KSOptions) (*Result, error) {
	o := ksOptionsInit()
	if opt != nil {
		o.weight = C.int32_t(opt.Weight)
		o.method = C.int32_t(opt.Method)
		o.threads = C.int32_t(opt.Threads)
		o.n_sim = C.int64_t(opt.NSim)
		o.seed = C.uint64_t(opt.Seed)
		o.critical = 0
		if opt.Critical {
			o.critical = 1
		}
		if opt.Cache != nil {
			o.cache = opt.Cache.raw
		}
	}
	return run(func(r *C.struct_mcstat_result) C.int {
		return C.mcstat_ks_test_2(ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y)), C.int(alt), C.double(alpha),
			&o, r)
	})
}

// ---- distributions -------------------------------------------------------------
// upper selects the tail: false gives P[X <= x], true P[X > x]; a quantile
// solves that tail's probability = p.

func b2i(b bool) C.int {
	if b {
		return 1
	}
	return 0
}

func dist(f func(out *C.double) C.int) (float64, error) {
	var v C.double
	if err := check(f(&v)); err != nil {
		return 0, err
	}
	return float64(v), nil
}

func TCDF(x, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_t_cdf(C.double(x), C.double(df), b2i(upper), o) })
}
func TLogCDF(x, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_t_logcdf(C.double(x), C.double(df), b2i(upper), o) })
}
func TQuantile(p, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_t_quantile(C.double(p), C.double(df), b2i(upper), o) })
}

// TQuantiles is TQuantile(p, df[i], upper) for every df[i] at one level, to
// the same accuracy, fast where many df differ (per-pixel critical values).
// Where one fails (NaN or non-positive df) its value is NaN, the others are
// computed, and the error is the first one's.
func TQuantiles(p float64, df []float64, upper bool) ([]float64, error) {
	x := make([]float64, len(df))
	if len(df) == 0 {
		return x, check(C.mcstat_t_quantiles(C.double(p), nil, 0, b2i(upper), nil))
	}
	st := C.mcstat_t_quantiles(C.double(p), (*C.double)(unsafe.Pointer(&df[0])), C.size_t(len(df)), b2i(upper),
		(*C.double)(unsafe.Pointer(&x[0])))
	return x, check(st)
}

func ChisqCDF(x, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_chisq_cdf(C.double(x), C.double(df), b2i(upper), o) })
}
func ChisqLogCDF(x, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_chisq_logcdf(C.double(x), C.double(df), b2i(upper), o) })
}
func ChisqQuantile(p, df float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int { return C.mcstat_chisq_quantile(C.double(p), C.double(df), b2i(upper), o) })
}
func FCDF(x, df1, df2 float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int {
		return C.mcstat_f_cdf(C.double(x), C.double(df1), C.double(df2), b2i(upper), o)
	})
}
func FLogCDF(x, df1, df2 float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int {
		return C.mcstat_f_logcdf(C.double(x), C.double(df1), C.double(df2), b2i(upper), o)
	})
}
func FQuantile(p, df1, df2 float64, upper bool) (float64, error) {
	return dist(func(o *C.double) C.int {
		return C.mcstat_f_quantile(C.double(p), C.double(df1), C.double(df2), b2i(upper), o)
	})
}
