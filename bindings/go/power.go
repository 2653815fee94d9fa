package mcstat

// #include <stdlib.h>
// #include <mcstat.h>
import "C"

import (
	"fmt"
	"unsafe"
)

// ---- power and sample size (experimental) ---------------------------------------

// PowerTest names a design (its values differ from Test's).
type PowerTest int

const (
	PowerT1    PowerTest = C.MCSTAT_POWER_T_1   // one-sample t: effect d = (mean - mu0)/sd
	PowerT2    PowerTest = C.MCSTAT_POWER_T_2   // two-sample t, N per group, common sd (R's power.t.test)
	PowerWelch PowerTest = C.MCSTAT_POWER_WELCH // Welch's t, ny = NRatio N, sd_y = SDRatio sd_x
	PowerVar1  PowerTest = C.MCSTAT_POWER_VAR_1 // chi-squared test: effect rho = sigma^2/sigma0^2
	PowerVar2  PowerTest = C.MCSTAT_POWER_VAR_2 // F test, ny = NRatio N: rho = (var_x/var_y)/ratio0
)

// PowerUnknown is the quantity PowerOptions.Solve finds.
type PowerUnknown int

const (
	SolvePower  PowerUnknown = C.MCSTAT_POWER_SOLVE_POWER
	SolveN      PowerUnknown = C.MCSTAT_POWER_SOLVE_N
	SolveEffect PowerUnknown = C.MCSTAT_POWER_SOLVE_EFFECT
	SolveAlpha  PowerUnknown = C.MCSTAT_POWER_SOLVE_ALPHA
)

// PowerOptions describe a power calculation; start from DefaultPowerOptions
// and set all but the unknown of N, Effect, Alpha and Power.
type PowerOptions struct {
	Test        PowerTest
	Alternative Alternative
	Strict      bool    // two-sided: count rejections in both tails (R's strict = TRUE)
	N           float64 // observations (per group for T2; of x for Welch and Var2), >= 2
	NRatio      float64 // Welch, Var2: ny = NRatio N
	SDRatio     float64 // Welch: sd_y / sd_x
	Effect      float64 // d (t tests) or rho (variance tests, > 0)
	Alpha       float64
	Power       float64
}

func powerOptionsInit() C.struct_mcstat_power_options {
	var o C.struct_mcstat_power_options
	C.mcstat_power_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// DefaultPowerOptions returns libmcstat's defaults: T1, two-sided, strict,
// NRatio and SDRatio 1, Alpha 0.05; N, Effect and Power unset (0).
func DefaultPowerOptions() PowerOptions {
	var o PowerOptions
	c := powerOptionsInit()
	o.fromC(&c)
	return o
}

func (o *PowerOptions) fromC(c *C.struct_mcstat_power_options) {
	*o = PowerOptions{Test: PowerTest(c.test), Alternative: Alternative(c.alternative), Strict: c.strict != 0,
		N: float64(c.n), NRatio: float64(c.n_ratio), SDRatio: float64(c.sd_ratio), Effect: float64(c.effect),
		Alpha: float64(c.alpha), Power: float64(c.power)}
}

func (o PowerOptions) toC() C.struct_mcstat_power_options {
	c := powerOptionsInit()
	c.test = C.int32_t(o.Test)
	c.alternative = C.int32_t(o.Alternative)
	c.strict = C.int32_t(b2i(o.Strict))
	c.n = C.double(o.N)
	c.n_ratio = C.double(o.NRatio)
	c.sd_ratio = C.double(o.SDRatio)
	c.effect = C.double(o.Effect)
	c.alpha = C.double(o.Alpha)
	c.power = C.double(o.Power)
	return c
}

// Compute returns the power at N, Effect and Alpha (Power is ignored).
func (o PowerOptions) Compute() (float64, error) {
	c := o.toC()
	var p C.double
	if err := check(C.mcstat_power_compute(&c, &p)); err != nil {
		return 0, err
	}
	return float64(p), nil
}

// Solve returns o with the unknown found from the other three (solving
// for N gives the smallest integer reaching the power, and sets Power to
// the power there).
func (o PowerOptions) Solve(unknown PowerUnknown) (PowerOptions, error) {
	c := o.toC()
	var out C.struct_mcstat_power_options
	if err := check(C.mcstat_power_solve(&c, C.int(unknown), &out)); err != nil {
		return o, err
	}
	var s PowerOptions
	s.fromC(&out)
	return s, nil
}

// String is R's print.power.htest block for solved options.
func (o PowerOptions) String() string {
	c := o.toC()
	return formatC("power", func(buf *C.char, size C.size_t, n *C.size_t) C.int {
		return C.mcstat_power_format(&c, buf, size, n)
	})
}

// formatC runs a libmcstat formatter twice: once for the length, once into
// a buffer of that size.
func formatC(what string, f func(buf *C.char, size C.size_t, n *C.size_t) C.int) string {
	var n C.size_t
	st := f(nil, 0, &n)
	if st != C.MCSTAT_OK && st != C.MCSTAT_EBUFSIZE {
		return fmt.Sprintf("<mcstat %s: %s>", what, newError(st).Message)
	}
	buf := (*C.char)(C.malloc(n + 1))
	defer C.free(unsafe.Pointer(buf))
	if st = f(buf, n+1, nil); st != C.MCSTAT_OK {
		return fmt.Sprintf("<mcstat %s: %s>", what, newError(st).Message)
	}
	return C.GoStringN(buf, C.int(n))
}

// ---- estimator diagnostics (experimental) ---------------------------------------

// DiagOptions are the diagnostics' options; start from DefaultDiagOptions.
type DiagOptions struct {
	K             uint64  // batch size in use (0: none)
	M             uint64  // batch means the t test sees (0: n/K, or 30 without K)
	TailK         uint64  // order statistics per tail in Hill's estimate (0: the default)
	Alpha         float64 // the t test's level
	Tolerance     float64 // allowed relative error of each tail's rate, in (0, 1)
	TailThreshold float64 // HeavyTail when a tail index is below this
}

func diagOptionsInit() C.struct_mcstat_diag_options {
	var o C.struct_mcstat_diag_options
	C.mcstat_diag_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// DefaultDiagOptions returns libmcstat's defaults (alpha 0.05, tolerance
// 0.2, tail threshold 2.2, the rest chosen from the data).
func DefaultDiagOptions() DiagOptions {
	o := diagOptionsInit()
	return DiagOptions{K: uint64(o.k), M: uint64(o.m), TailK: uint64(o.tail_k), Alpha: float64(o.alpha),
		Tolerance: float64(o.tolerance), TailThreshold: float64(o.tail_threshold)}
}

// Diagnostics describe primary estimates: shape, tails and the batch size
// that keeps a t test on batch means at its level.
type Diagnostics struct {
	N, TailK     uint64
	K, M         uint64 // the batch size and number of batch means TSize is for
	RecommendedK uint64 // the batch size rule's k for M batch means
	HeavyTail    bool   // a tail index is below the threshold: variance estimates are unreliable
	Mean, SD     float64
	Skewness     float64
	SkewnessSE   float64
	Kurtosis     float64 // excess
	KurtosisSE   float64
	TailIndex    [2]float64 // Hill: [0] lower tail, [1] upper (+Inf: no Pareto tail)
	TailIndexSE  [2]float64 // NaN where no tail value was used
	MaxShare     float64    // max_i (x_i - mean)^2 / sum_i (x_i - mean)^2
	TSize        [2]float64 // predicted rejection rates of the lower / upper tail of the two-sided t test
	Alpha        float64
	Tolerance    float64
}

// Diagnose computes every diagnostic of x; opt nil means DefaultDiagOptions().
func Diagnose(x []float64, opt *DiagOptions) (*Diagnostics, error) {
	o := diagOptionsInit()
	if opt != nil {
		o.k, o.m, o.tail_k = C.uint64_t(opt.K), C.uint64_t(opt.M), C.uint64_t(opt.TailK)
		o.alpha, o.tolerance, o.tail_threshold = C.double(opt.Alpha), C.double(opt.Tolerance), C.double(opt.TailThreshold)
	}
	var d C.struct_mcstat_diagnostics
	if err := check(C.mcstat_diag_compute(ptr(x), C.size_t(len(x)), &o, &d)); err != nil {
		return nil, err
	}
	return &Diagnostics{N: uint64(d.n), TailK: uint64(d.tail_k), K: uint64(d.k), M: uint64(d.m),
		RecommendedK: uint64(d.recommended_k), HeavyTail: d.heavy_tail != 0, Mean: float64(d.mean), SD: float64(d.sd),
		Skewness: float64(d.skewness), SkewnessSE: float64(d.skewness_se), Kurtosis: float64(d.kurtosis),
		KurtosisSE:  float64(d.kurtosis_se),
		TailIndex:   [2]float64{float64(d.tail_index[0]), float64(d.tail_index[1])},
		TailIndexSE: [2]float64{float64(d.tail_index_se[0]), float64(d.tail_index_se[1])},
		MaxShare:    float64(d.max_share), TSize: [2]float64{float64(d.t_size[0]), float64(d.t_size[1])},
		Alpha: float64(d.alpha), Tolerance: float64(d.tolerance)}, nil
}

// TailIndex is Hill's tail index of each tail ([0] lower, [1] upper) from
// tailK order statistics (0: the default).
func TailIndex(x []float64, tailK int) ([2]float64, error) {
	var idx [2]C.double
	if tailK < 0 {
		return [2]float64{}, invalid("tailK < 0")
	}
	if err := check(C.mcstat_diag_tail_index(ptr(x), C.size_t(len(x)), C.size_t(tailK), &idx[0])); err != nil {
		return [2]float64{}, err
	}
	return [2]float64{float64(idx[0]), float64(idx[1])}, nil
}

// TSize is the Edgeworth-predicted rejection rates (lower tail, upper tail)
// of the two-sided t test at alpha on m batch means of k values of the
// given skewness and excess kurtosis.
func TSize(skewness, kurtosis float64, k, m uint64, alpha float64) ([2]float64, error) {
	var s [2]C.double
	if err := check(C.mcstat_diag_t_size(C.double(skewness), C.double(kurtosis), C.uint64_t(k), C.uint64_t(m),
		C.double(alpha), &s[0])); err != nil {
		return [2]float64{}, err
	}
	return [2]float64{float64(s[0]), float64(s[1])}, nil
}

// BatchSize is the batch size rule: the smallest k whose predicted tail
// rates are within tolerance * alpha/2 of alpha/2 for m batch means.
func BatchSize(skewness, kurtosis float64, m uint64, alpha, tolerance float64) (uint64, error) {
	var k C.uint64_t
	if err := check(C.mcstat_diag_batch_size(C.double(skewness), C.double(kurtosis), C.uint64_t(m), C.double(alpha),
		C.double(tolerance), &k)); err != nil {
		return 0, err
	}
	return uint64(k), nil
}
