package mcstat

// #include <mcstat.h>
//
// /* The sequential tests' outputs live in mcstat_result's anonymous unions. */
// static void gomcstat_seq(const mcstat_result *r, double d[7], int32_t i[2]) {
//     d[0] = r->seq_looks; d[1] = r->seq_n_decided; d[2] = r->seq_log_e; d[3] = r->seq_log_e_max;
//     d[4] = r->seq_eps; d[5] = r->seq_t_opt; d[6] = r->seq_n_gate;
//     i[0] = r->seq_state; i[1] = r->seq_hold;
// }
import "C"

import (
	"fmt"
	"math"
	"unsafe"
)

// SeqKind is what a Sequential test tests.
type SeqKind int

const (
	SeqMean  SeqKind = C.MCSTAT_SEQ_MEAN_1 // the mean of x against the null value (mu0)
	SeqMean2 SeqKind = C.MCSTAT_SEQ_MEAN_2 // mean(x) - mean(y) against the null value (a difference)
	SeqVar   SeqKind = C.MCSTAT_SEQ_VAR_1  // the variance of x against the null value (sigma0^2 > 0)
	SeqVar2  SeqKind = C.MCSTAT_SEQ_VAR_2  // var(x) / var(y) against the null value (a ratio > 0)
)

// String is libmcstat's name: "mean", "mean2", "var", "var2".
func (k SeqKind) String() string {
	if s := C.mcstat_seq_kind_name(C.int(k)); s != nil {
		return C.GoString(s)
	}
	return fmt.Sprintf("SeqKind(%d)", int(k))
}

// TwoSample reports whether the kind has two samples (SeqMean2, SeqVar2).
func (k SeqKind) TwoSample() bool { return k == SeqMean2 || k == SeqVar2 }

// SeqOutcome is where a sequential test stands: continuing, or its first
// decision, which is final.
type SeqOutcome int

const (
	SeqContinue SeqOutcome = iota // not decided yet (held, or not enough evidence)
	SeqLess                       // H0 rejected: the parameter is below the null value
	SeqEqual                      // equivalence shown: the confidence sequence lies within null +- Eps
	SeqGreater                    // H0 rejected: the parameter is above the null value
)

func seqOutcome(state, decision C.int32_t) SeqOutcome {
	switch {
	case state != C.MCSTAT_SEQ_DECIDED:
		return SeqContinue
	case decision < 0:
		return SeqLess
	case decision == 0:
		return SeqEqual
	}
	return SeqGreater
}

// String is "continue", "less", "equal" or "greater".
func (o SeqOutcome) String() string {
	if d, ok := o.Decision(); ok {
		return d.String()
	}
	if o == SeqContinue {
		return "continue"
	}
	return fmt.Sprintf("SeqOutcome(%d)", int(o))
}

// Decision is the decision, false while continuing.
func (o SeqOutcome) Decision() (Decision, bool) {
	switch o {
	case SeqLess:
		return DecisionLess, true
	case SeqEqual:
		return DecisionEqual, true
	case SeqGreater:
		return DecisionGreater, true
	}
	return DecisionEqual, false
}

// SeqHold is why a sequential test may not decide at its last look: a set
// of SeqHold* bits, 0 when it may.
type SeqHold uint32

const (
	SeqHoldFew        SeqHold = C.MCSTAT_SEQ_HOLD_FEW        // a sample has fewer than MinN values
	SeqHoldDegenerate SeqHold = C.MCSTAT_SEQ_HOLD_DEGENERATE // a sample has no spread yet
	SeqHoldKurtosis   SeqHold = C.MCSTAT_SEQ_HOLD_KURTOSIS   // n < KurtosisGate * kurtosis: rare large values not yet seen often enough
)

// Has reports whether every bit of r is set in h.
func (h SeqHold) Has(r SeqHold) bool { return r != 0 && h&r == r }

// SeqOptions are a Sequential test's options; start from DefaultSeqOptions.
type SeqOptions struct {
	Alternative Alternative
	Alpha       float64 // in (0, 1): the error rate over every look
	// Eps is an equivalence margin >= 0 on a mean (two-sided SeqMean and
	// SeqMean2 only): the test also stops with SeqEqual once the confidence
	// sequence lies within null +- Eps; 0: none.
	Eps          float64
	TOpt         float64 // observations (per sample) where the sequence is tightest, > 0
	KurtosisGate float64 // hold while n < KurtosisGate * kurtosis, >= 0 (0: off)
	VarUCBZ      float64 // the variance's upper-bound factor, >= 0 (0: plain s^2)
	MinN         uint64  // hold while a sample has fewer values, >= 2
}

func seqOptionsInit() C.struct_mcstat_seq_options {
	var o C.struct_mcstat_seq_options
	C.mcstat_seq_options_init_size(&o, C.size_t(unsafe.Sizeof(o)))
	return o
}

// DefaultSeqOptions returns libmcstat's defaults (two-sided, alpha 0.05,
// no margin, TOpt 1e4, KurtosisGate 10, VarUCBZ 3, MinN 100).
func DefaultSeqOptions() SeqOptions {
	o := seqOptionsInit()
	return SeqOptions{Alternative: Alternative(o.alternative), Alpha: float64(o.alpha), Eps: float64(o.eps),
		TOpt: float64(o.t_opt), KurtosisGate: float64(o.kurtosis_gate), VarUCBZ: float64(o.var_ucb_z),
		MinN: uint64(o.min_n)}
}

// diagnose names the first argument libmcstat refuses.
func (o SeqOptions) diagnose(kind SeqKind, null float64) string {
	finiteNonneg := func(v float64) bool { return v >= 0 && !math.IsInf(v, 0) }
	onVar := kind == SeqVar || kind == SeqVar2
	switch {
	case kind.String() == fmt.Sprintf("SeqKind(%d)", int(kind)):
		return fmt.Sprintf("kind %d is not a sequential test kind", int(kind))
	case !(o.Alpha > 0 && o.Alpha < 1):
		return fmt.Sprintf("Alpha = %g is not in (0, 1)", o.Alpha)
	case !finiteNonneg(o.Eps):
		return fmt.Sprintf("Eps = %g is not finite and >= 0", o.Eps)
	case o.Eps > 0 && (onVar || o.Alternative != TwoSided):
		return fmt.Sprintf("Eps = %g needs a two-sided test of a mean (kind %s, %s)", o.Eps, kind, o.Alternative)
	case !(o.TOpt > 0) || math.IsInf(o.TOpt, 0):
		return fmt.Sprintf("TOpt = %g is not finite and > 0", o.TOpt)
	case !finiteNonneg(o.KurtosisGate):
		return fmt.Sprintf("KurtosisGate = %g is not finite and >= 0", o.KurtosisGate)
	case !finiteNonneg(o.VarUCBZ):
		return fmt.Sprintf("VarUCBZ = %g is not finite and >= 0", o.VarUCBZ)
	case o.MinN < 2:
		return fmt.Sprintf("MinN = %d is below 2", o.MinN)
	case math.IsNaN(null) || math.IsInf(null, 0) || (onVar && !(null > 0)):
		return fmt.Sprintf("null value %g is not finite (and > 0 for a variance)", null)
	}
	return fmt.Sprintf("invalid options (Alternative %d)", int(o.Alternative))
}

// SeqDetails are a sequential test's own outputs.  Values that do not
// apply at the last look are nil.
type SeqDetails struct {
	Outcome  SeqOutcome // continuing, or the first (final) decision
	Hold     SeqHold    // why no decision is allowed at the last look (0: none)
	Looks    uint64     // pushes so far
	NDecided *uint64    // n (of x) at the look that decided; nil while continuing
	Z        *float64   // the z of the last look; nil while held (Statistic is then NaN)
	LogE     *float64   // log of the e-value at the last look; nil while held
	// LogEMax is the running maximum of LogE (PValue = min(1,
	// exp(-LogEMax))); nil before the first look that was not held.
	LogEMax *float64
	Eps     *float64 // the equivalence margin; nil when none
	TOpt    float64  // the n where the confidence sequence is tightest
	NGate   *float64 // the n the kurtosis gate asks for; nil when it is open
}

func finite(v C.double) *float64 {
	f := float64(v)
	if math.IsNaN(f) || math.IsInf(f, 0) {
		return nil
	}
	return &f
}

func positive(v C.double) *float64 {
	f := float64(v)
	if !(f > 0) {
		return nil
	}
	return &f
}

func seqDetails(r *C.struct_mcstat_result) *SeqDetails {
	var d [7]C.double
	var i [2]C.int32_t
	C.gomcstat_seq(r, &d[0], &i[0])
	s := &SeqDetails{Outcome: seqOutcome(i[0], C.int32_t(r.decision)), Hold: SeqHold(i[1]),
		Looks: uint64(d[0]), Z: finite(r.statistic), LogE: finite(d[2]), LogEMax: finite(d[3]),
		Eps: positive(d[4]), TOpt: float64(d[5]), NGate: positive(d[6])}
	if i[0] == C.MCSTAT_SEQ_DECIDED {
		n := uint64(d[1])
		s.NDecided = &n
	}
	return s
}

// HeavyTailError is Finish's error when the kurtosis gate was still closed
// at the last look: the tails never allowed a decision in this budget.  It
// matches ErrHeavyTail with errors.Is.
type HeavyTailError struct {
	N     uint64  // values pushed (x and y)
	NGate float64 // the n the kurtosis gate asked for at the last look
}

func (e *HeavyTailError) Error() string {
	return fmt.Sprintf("mcstat: %s: %d values, the kurtosis gate asks for %.0f (status %d)",
		ErrHeavyTail.Message, e.N, e.NGate, ErrHeavyTail.Status)
}

// Is makes errors.Is(err, ErrHeavyTail) hold.
func (e *HeavyTailError) Is(target error) bool { return ErrHeavyTail.Is(target) }

// Sequential is a sequential, anytime-valid test (mcstat_seq, 448 bytes of
// plain data held by value): push a batch after each frame and look at it
// every time; it stops (Outcome) with SeqLess or SeqGreater once H0 is
// rejected, or SeqEqual once the bias is shown below Eps, and its error
// rate over all the looks stays at most Alpha.  While a sample is too
// small, without spread, or its kurtosis says its rare large values have
// not been seen often enough, the test holds (Hold); Finish then returns a
// *HeavyTailError if the kurtosis gate was still closed.  Copying the value
// keeps a state.  Not safe for concurrent use.
type Sequential struct{ raw C.struct_mcstat_seq }

// NewSequential returns an empty test of kind against nullValue (a mean, a
// difference, a variance or a ratio); opt nil means DefaultSeqOptions().
// ErrInvalidArgument names the bad argument.
func NewSequential(kind SeqKind, nullValue float64, opt *SeqOptions) (*Sequential, error) {
	o := DefaultSeqOptions()
	if opt != nil {
		o = *opt
	}
	c := seqOptionsInit()
	c.alternative = C.int32_t(o.Alternative)
	c.alpha = C.double(o.Alpha)
	c.eps = C.double(o.Eps)
	c.t_opt = C.double(o.TOpt)
	c.kurtosis_gate = C.double(o.KurtosisGate)
	c.var_ucb_z = C.double(o.VarUCBZ)
	c.min_n = C.uint64_t(o.MinN)
	s := &Sequential{}
	st := C.mcstat_seq_init(&s.raw, C.int(kind), C.double(nullValue), &c)
	if st == C.MCSTAT_EINVAL {
		return nil, invalid(o.diagnose(kind, nullValue))
	}
	if err := check(st); err != nil {
		return nil, err
	}
	return s, nil
}

func (s *Sequential) c(call string, twoSample bool) (*C.struct_mcstat_seq, error) {
	if s == nil {
		return nil, invalid(call + " on a nil *Sequential")
	}
	if s.raw.version == 0 {
		return nil, invalid(call + " on a Sequential not made by NewSequential")
	}
	if k := s.Kind(); k.TwoSample() != twoSample {
		if twoSample {
			return nil, invalid(fmt.Sprintf("%s needs a two-sample test (mean2, var2); this one is %s", call, k))
		}
		return nil, invalid(fmt.Sprintf("%s needs a one-sample test (mean, var); this one is %s", call, k))
	}
	return &s.raw, nil
}

// Push takes one look after adding a batch of x (one-sample tests).
// ErrNonFinite for NaN or Inf in the batch; s is unchanged on an error.
func (s *Sequential) Push(x []float64) error {
	c, err := s.c("Push", false)
	if err != nil {
		return err
	}
	return check(C.mcstat_seq_push_array(c, ptr(x), C.size_t(len(x))))
}

// PushMoments takes one look after adding a batch given as an accumulator
// (e.g. a frame's per-goroutine accumulators, merged).
func (s *Sequential) PushMoments(batch *Moments) error {
	c, err := s.c("PushMoments", false)
	if err != nil {
		return err
	}
	return check(C.mcstat_seq_push_moments(c, batch.c()))
}

// PushStream takes one look after adding a stream's values (a frame's
// merged Stream); ErrNonFinite if the stream has seen NaN or Inf.
func (s *Sequential) PushStream(frame *Stream) error {
	c, err := s.c("PushStream", false)
	if err != nil {
		return err
	}
	return check(C.mcstat_seq_push_stream(c, frame.c()))
}

// Push2 takes one look after adding a batch of each sample (two-sample
// tests; either may be empty).
func (s *Sequential) Push2(x, y []float64) error {
	c, err := s.c("Push2", true)
	if err != nil {
		return err
	}
	return check(C.mcstat_seq_push_2_array(c, ptr(x), C.size_t(len(x)), ptr(y), C.size_t(len(y))))
}

// PushMoments2 is Push2 on accumulators.
func (s *Sequential) PushMoments2(x, y *Moments) error {
	c, err := s.c("PushMoments2", true)
	if err != nil {
		return err
	}
	return check(C.mcstat_seq_push_2_moments(c, x.c(), y.c()))
}

// Result is the test at the last look: PValue the anytime p-value, ConfInt
// the confidence sequence, Reject once decided SeqLess or SeqGreater, and
// Seq the sequential outputs.  nil for a nil or uninitialised s.
func (s *Sequential) Result() *Result {
	if s == nil {
		return nil
	}
	r, err := run(func(o *C.struct_mcstat_result) C.int { return C.mcstat_seq_result(&s.raw, o) })
	if err != nil {
		return nil
	}
	return r
}

// Finish is the test at the end of the caller's budget: the result, and a
// nil error when decided or when undecided with data that allowed a
// decision (more samples may decide); a *HeavyTailError (matching
// ErrHeavyTail) with the result when the kurtosis gate was closed at the
// last look.
func (s *Sequential) Finish() (*Result, error) {
	if s == nil {
		return nil, invalid("Finish on a nil *Sequential")
	}
	var out C.struct_mcstat_result
	st := C.mcstat_seq_finish(&s.raw, &out)
	if st == C.MCSTAT_EHEAVYTAIL {
		r := fromC(&out)
		gate := 0.0
		if r.Seq.NGate != nil {
			gate = *r.Seq.NGate
		}
		return r, &HeavyTailError{N: uint64(out.n[0] + out.n[1]), NGate: gate}
	}
	if err := check(st); err != nil {
		return nil, err
	}
	return fromC(&out), nil
}

// state is s's C struct, or an empty one for a nil s (the accessors
// then read zeros rather than panic).
func (s *Sequential) state() *C.struct_mcstat_seq {
	if s == nil {
		return &C.struct_mcstat_seq{}
	}
	return &s.raw
}

// Kind is what s tests.
func (s *Sequential) Kind() SeqKind { return SeqKind(s.state().kind) }

// Outcome is SeqContinue, or the first decision (final).
func (s *Sequential) Outcome() SeqOutcome { return seqOutcome(s.state().state, s.state().decision) }

// Decided reports whether s has decided.
func (s *Sequential) Decided() bool { return s.state().state == C.MCSTAT_SEQ_DECIDED }

// Hold is why no decision was allowed at the last look.
func (s *Sequential) Hold() SeqHold { return SeqHold(s.state().hold) }

// Looks is the number of pushes so far.
func (s *Sequential) Looks() uint64 { return uint64(s.state().looks) }

// N is the number of values of x pushed so far; NY of y (0 for one sample).
func (s *Sequential) N() uint64  { return uint64(s.state().x.n) }
func (s *Sequential) NY() uint64 { return uint64(s.state().y.n) }

// NDecided is n of x at the deciding look; false while continuing.
func (s *Sequential) NDecided() (uint64, bool) {
	return uint64(s.state().n_decided), s.Decided()
}

// String is libmcstat's R-style block of the last look.
func (s *Sequential) String() string {
	r := s.Result()
	if r == nil {
		return "<invalid Sequential>"
	}
	return r.String()
}
