package mcstat

// #include <stdlib.h>
// #include <mcstat.h>
import "C"

import (
	"fmt"
	"unsafe"
)

// ---- equivalence (TOST) ---------------------------------------------------------

// EquivalenceTest1 asks whether mean(x) lies within [mu0 + lower, mu0 +
// upper] (lower < upper, typically -margin and margin) by two one-sided t
// tests at alpha in (0, 0.5).  Result.Reject means EQUIVALENT; Decision is
// -1 when the lower bound's test failed, +1 the upper's; Result.TOST holds
// both tests.
func EquivalenceTest1(x []float64, mu0, lower, upper, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_equivalence_test_1(ptr(x), C.size_t(len(x)), C.double(mu0), C.double(lower),
			C.double(upper), C.double(alpha), o)
	})
}

// EquivalenceTest1Moments is EquivalenceTest1 on an accumulator.
func EquivalenceTest1Moments(x *Moments, mu0, lower, upper, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_equivalence_test_1_moments(x.c(), C.double(mu0), C.double(lower), C.double(upper),
			C.double(alpha), o)
	})
}

// EquivalenceTest2 asks whether mean(x) - mean(y) lies within [lower,
// upper] (Welch's t: unequal variances).
func EquivalenceTest2(x, y []float64, lower, upper, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_equivalence_test_2(ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y)), C.double(lower),
			C.double(upper), C.double(alpha), o)
	})
}

// EquivalenceTest2Moments is EquivalenceTest2 on accumulators.
func EquivalenceTest2Moments(x, y *Moments, lower, upper, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_equivalence_test_2_moments(x.c(), y.c(), C.double(lower), C.double(upper),
			C.double(alpha), o)
	})
}

// ---- binomial and battery -------------------------------------------------------

// BinomTest is R's binom.test of x successes in n trials against P(success)
// = p: exact p-value (Result.Binom.LogPValue where it underflows),
// Clopper-Pearson interval, and Critical the acceptance region of counts.
func BinomTest(x, n uint64, p float64, alt Alternative, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_binom_test(C.uint64_t(x), C.uint64_t(n), C.double(p), C.int(alt), C.double(alpha), o)
	})
}

// BatteryTest asks whether `rejections` among k tests at level `level` is
// consistent with that level (BinomTest(rejections, k, level, ...));
// Greater asks "too many rejections?", the usual question.
func BatteryTest(rejections, k uint64, level float64, alt Alternative, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_battery_test(C.uint64_t(rejections), C.uint64_t(k), C.double(level), C.int(alt),
			C.double(alpha), o)
	})
}

// BatteryTestPValues is BatteryTest from the battery's p-values (a test
// rejects when its p-value is <= level).
func BatteryTestPValues(pValues []float64, level float64, alt Alternative, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_battery_test_pvalues(ptr(pValues), C.size_t(len(pValues)), C.double(level), C.int(alt),
			C.double(alpha), o)
	})
}

// ---- chi-squared goodness of fit ------------------------------------------------

// GOFExpected says what GOFChisqTest's expected values are.
type GOFExpected int

const (
	GOFProbabilities GOFExpected = C.MCSTAT_GOF_PROBABILITIES // cell probabilities, summing to 1
	GOFCounts        GOFExpected = C.MCSTAT_GOF_COUNTS        // expected counts, summing to the observed total
)

// GOFOptions are the chi-squared goodness-of-fit options; start from
// DefaultGOFOptions.
type GOFOptions struct {
	Expected    GOFExpected
	Pool        bool    // pool consecutive cells until the expected count reaches MinExpected
	Rescale     bool    // scale expected to the right total instead of requiring it
	MinExpected float64 // the pooling threshold, >= 0
	NEstimated  int     // parameters of the expected probabilities estimated from the counts
}

func gofOptionsInit() C.struct_mcstat_gof_options {
	var o C.struct_mcstat_gof_options
	C.mcstat_gof_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// GOFDefaultMinExpected is the default pooling threshold (Cochran's rule, 5).
func GOFDefaultMinExpected() float64 { return float64(C.mcstat_gof_default_min_expected()) }

// DefaultGOFOptions returns libmcstat's defaults: probabilities, pooling
// at GOFDefaultMinExpected, no rescaling, nothing estimated.
func DefaultGOFOptions() GOFOptions {
	o := gofOptionsInit()
	return GOFOptions{Expected: GOFExpected(o.expected), Pool: o.pool != 0, Rescale: o.rescale != 0,
		MinExpected: float64(o.min_expected), NEstimated: int(o.n_estimated)}
}

// GOFChisqTest is Pearson's chi-squared test of observed counts against
// expected (equal lengths); opt nil means DefaultGOFOptions().
func GOFChisqTest(observed, expected []float64, opt *GOFOptions, alpha float64) (*Result, error) {
	if len(observed) != len(expected) {
		return nil, invalid(fmt.Sprintf("observed has %d cells, expected %d", len(observed), len(expected)))
	}
	o := gofOptionsInit()
	if opt != nil {
		o.expected = C.int32_t(opt.Expected)
		o.pool = C.int32_t(b2i(opt.Pool))
		o.rescale = C.int32_t(b2i(opt.Rescale))
		o.min_expected = C.double(opt.MinExpected)
		o.n_estimated = C.int32_t(opt.NEstimated)
	}
	return run(func(r *C.struct_mcstat_result) C.int {
		return C.mcstat_gof_chisq_test(ptr(observed), ptr(expected), C.size_t(len(observed)), &o, C.double(alpha), r)
	})
}

// ---- multiple testing -----------------------------------------------------------

// PAdjustMethod is a method of R's p.adjust.
type PAdjustMethod int

const (
	PAdjustNone       PAdjustMethod = C.MCSTAT_P_ADJUST_NONE
	PAdjustBonferroni PAdjustMethod = C.MCSTAT_P_ADJUST_BONFERRONI
	PAdjustHolm       PAdjustMethod = C.MCSTAT_P_ADJUST_HOLM
	PAdjustHochberg   PAdjustMethod = C.MCSTAT_P_ADJUST_HOCHBERG
	PAdjustHommel     PAdjustMethod = C.MCSTAT_P_ADJUST_HOMMEL
	PAdjustBH         PAdjustMethod = C.MCSTAT_P_ADJUST_BH // Benjamini-Hochberg (FDR)
	PAdjustBY         PAdjustMethod = C.MCSTAT_P_ADJUST_BY // Benjamini-Yekutieli (FDR, any dependence)
	// e-BH on the e-values p^(-9/10) / 10 (FDR, any dependence; less
	// powerful than BY on the same p-values): see EBH.
	PAdjustEBH PAdjustMethod = C.MCSTAT_P_ADJUST_E_BH
)

// ParsePAdjustMethod accepts R's names: "none", "bonferroni", "holm",
// "hochberg", "hommel", "BH" (also "bh", "fdr"), "BY" (also "by"); and
// "e-BH" (also "ebh", "e_bh").
func ParsePAdjustMethod(name string) (PAdjustMethod, error) {
	cs := C.CString(name)
	defer C.free(unsafe.Pointer(cs))
	var v C.int
	if err := check(C.mcstat_p_adjust_method_parse(cs, &v)); err != nil {
		return PAdjustNone, err
	}
	return PAdjustMethod(v), nil
}

func (m PAdjustMethod) String() string {
	if s := C.mcstat_p_adjust_method_name(C.int(m)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("PAdjustMethod(%d)", int(m))
}

// PAdjust returns R's p.adjust(p, method): NaN entries stay NaN and are not
// counted as tests.  ErrInvalidArgument for a p-value outside [0, 1].
func PAdjust(p []float64, method PAdjustMethod) ([]float64, error) {
	var bytes C.size_t
	if err := check(C.mcstat_p_adjust_work_size(C.size_t(len(p)), C.int(method), &bytes)); err != nil {
		return nil, err
	}
	out := make([]float64, len(p))
	if len(p) == 0 {
		return out, nil
	}
	// scratch as float64s: aligned for double, as the library requires
	work := make([]float64, (int(bytes)+7)/8)
	var wp unsafe.Pointer
	if len(work) > 0 {
		wp = unsafe.Pointer(&work[0])
	}
	if err := check(C.mcstat_p_adjust(ptr(p), C.size_t(len(p)), C.int(method), wp, bytes, ptr(out))); err != nil {
		return nil, err
	}
	return out, nil
}

// EBH returns e-BH's adjusted values (Wang & Ramdas 2022) of the e-values e:
// false discovery rate control under any dependence; reject where the value
// is <= alpha.  NaN entries stay NaN and are not counted; a single e-value
// gives min(1, 1/e).  ErrInvalidArgument for a negative e-value.
func EBH(e []float64) ([]float64, error) {
	var bytes C.size_t
	if err := check(C.mcstat_p_adjust_work_size(C.size_t(len(e)), C.MCSTAT_P_ADJUST_E_BH, &bytes)); err != nil {
		return nil, err
	}
	out := make([]float64, len(e))
	if len(e) == 0 {
		return out, nil
	}
	work := make([]float64, (int(bytes)+7)/8)
	var wp unsafe.Pointer
	if len(work) > 0 {
		wp = unsafe.Pointer(&work[0])
	}
	if err := check(C.mcstat_e_bh(ptr(e), C.size_t(len(e)), wp, bytes, ptr(out))); err != nil {
		return nil, err
	}
	return out, nil
}
