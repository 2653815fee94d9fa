package mcstat

// #include <mcstat.h>
//
// /* mcstat_stream_add is a static inline function of the header, which cgo
//    cannot call: these wrappers inline it (the slice form pays cgo's call
//    overhead once per slice instead of once per value). */
// static void gomcstat_stream_add(mcstat_stream *s, double x) { mcstat_stream_add(s, x); }
// static void gomcstat_stream_add_n(mcstat_stream *s, const double *x, size_t n) {
//     for (size_t i = 0; i < n; i++)
//         mcstat_stream_add(s, x[i]);
// }
// static uint64_t gomcstat_stream_n_overflow(const mcstat_stream *s) { return s->n_overflow; }
import "C"

// Stream is a buffered accumulator for checks inside a renderer: adding a
// value stores it in a 492-value buffer, flushed into exact moments when
// full, so the moments are exactly what Moments.AddSlice gives on the same
// values.  NaN and Inf values are not added but counted (NNonFinite), and a
// check on a stream that has seen one fails with ErrNonFinite.  A Stream is
// not safe for concurrent use: keep one per goroutine and Merge them at the
// end of a frame.  The zero value is an empty stream.
type Stream struct{ raw C.struct_mcstat_stream }

// NewStream returns an empty stream.
func NewStream() *Stream {
	s := &Stream{}
	C.mcstat_stream_init(&s.raw)
	return s
}

// Reset empties s.
func (s *Stream) Reset() error {
	if s == nil {
		return invalid("Reset of a nil *Stream")
	}
	return check(C.mcstat_stream_init(&s.raw))
}

// c is the C stream, initialised on first use (the zero value is empty),
// or NULL for a nil s (libmcstat then refuses with ErrInvalidArgument).
func (s *Stream) c() *C.struct_mcstat_stream {
	if s == nil {
		return nil
	}
	if s.raw.version == 0 && s.raw.count == 0 && s.raw.moments.n == 0 && s.raw.n_nonfinite == 0 {
		C.mcstat_stream_init(&s.raw)
	}
	return &s.raw
}

// ready guards the inline add, which writes through the buffer index
// without any check of its own.
func (s *Stream) ready() bool {
	c := s.c()
	return c != nil && c.version == C.MCSTAT_STREAM_VERSION && c.count < C.MCSTAT_STREAM_CAPACITY
}

// Add adds one value (ErrInvalidArgument for a stream not made by NewStream).
func (s *Stream) Add(x float64) error {
	if !s.ready() {
		return invalid("nil or damaged *Stream")
	}
	C.gomcstat_stream_add(s.c(), C.double(x))
	return nil
}

// AddSlice adds values in order, as repeated Add.
func (s *Stream) AddSlice(x []float64) error {
	if !s.ready() {
		return invalid("nil or damaged *Stream")
	}
	if len(x) > 0 {
		C.gomcstat_stream_add_n(s.c(), ptr(x), C.size_t(len(x)))
	}
	return nil
}

// Flush adds the buffered values to the moments (ErrTooBig when the count
// would pass 2^64 - 1: they are then left out and counted in NOverflow).
func (s *Stream) Flush() error { return check(C.mcstat_stream_flush(s.c())) }

// Merge merges other into s (other unchanged; it may be s).
func (s *Stream) Merge(other *Stream) error { return check(C.mcstat_stream_merge(s.c(), other.c())) }

// Moments returns the moments of every value s has seen, flushed or not.
func (s *Stream) Moments() (*Moments, error) {
	m := &Moments{}
	if err := check(C.mcstat_stream_moments(s.c(), &m.raw)); err != nil {
		return nil, err
	}
	return m, nil
}

// NNonFinite is the number of NaN and Inf values seen (and left out).
func (s *Stream) NNonFinite() uint64 {
	if s == nil {
		return 0
	}
	return uint64(s.raw.n_nonfinite)
}

// NOverflow is the number of values left out because the count would pass 2^64 - 1.
func (s *Stream) NOverflow() uint64 {
	if s == nil {
		return 0
	}
	return uint64(C.gomcstat_stream_n_overflow(&s.raw))
}

// CheckMean checks that the mean of the values is reference to within
// tolerance (>= 0) at level alpha: the two-sided one-sample t test when
// tolerance is 0, else two one-sided tests at alpha/2 against
// reference +- tolerance (the Result is the one with the smaller p-value).
// Result.Reject means the check failed.
func (s *Stream) CheckMean(reference, tolerance, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_stream_check_mean(s.c(), C.double(reference), C.double(tolerance), C.double(alpha), o)
	})
}

// CheckVar checks that the variance of the values is below bound (> 0):
// the one-sided chi-squared test at alpha; Result.Reject means the variance
// is significantly above the bound.
func (s *Stream) CheckVar(bound, alpha float64) (*Result, error) {
	return run(func(o *C.struct_mcstat_result) C.int {
		return C.mcstat_stream_check_var(s.c(), C.double(bound), C.double(alpha), o)
	})
}
