package mcstat

// Sequential, anytime-valid tests on deterministic data: decisions, holds,
// errors, and the numbers of the C state itself.

import (
	"errors"
	"math"
	"strings"
	"testing"
)

// xorshift is a deterministic generator (fixed seeds).
type xorshift uint64

func newXorshift(seed uint64) *xorshift {
	x := xorshift(seed*0x9E3779B97F4A7C15 | 1)
	return &x
}

func (x *xorshift) uniform() float64 {
	*x ^= *x << 13
	*x ^= *x >> 7
	*x ^= *x << 17
	return float64(uint64(*x)>>11) / (1 << 53)
}

func (x *xorshift) normals(n int, mean float64) []float64 {
	v := make([]float64, n)
	for i := range v {
		u, w := x.uniform(), x.uniform()
		v[i] = mean + math.Sqrt(-2*math.Log(1-u))*math.Cos(2*math.Pi*w)
	}
	return v
}

// sparse is 99% exact zeros and 1% exponential values of mean 100.
func (x *xorshift) sparse(n int) []float64 {
	v := make([]float64, n)
	for i := range v {
		if x.uniform() < 0.01 {
			v[i] = -100 * math.Log(1-x.uniform())
		}
	}
	return v
}

func TestSequentialShiftedMeanDecidesGreater(t *testing.T) {
	rng := newXorshift(1)
	s, err := NewSequential(SeqMean, 0, nil)
	if err != nil {
		t.Fatal(err)
	}
	if s.Kind() != SeqMean || s.Outcome() != SeqContinue || s.Looks() != 0 {
		t.Fatalf("fresh test: %v %v %d", s.Kind(), s.Outcome(), s.Looks())
	}
	for !s.Decided() && s.N() < 5000 {
		if err := s.Push(rng.normals(100, 0.5)); err != nil {
			t.Fatal(err)
		}
	}
	n, ok := s.NDecided()
	if s.Outcome() != SeqGreater || !ok || n < 200 || n > 5000 {
		t.Fatalf("outcome %v at n = %d (%v)", s.Outcome(), n, ok)
	}
	if d, ok := s.Outcome().Decision(); !ok || d != DecisionGreater {
		t.Fatalf("decision %v %v", d, ok)
	}
	r := s.Result()
	if r.Test != TestSeqMean1 || r.Method != MethodAsymptotic || !r.Reject || r.Decision != DecisionGreater ||
		r.PValue > 0.05 || len(r.N) != 1 || r.N[0] != n || r.DF != nil {
		t.Fatalf("result %+v", r)
	}
	if len(r.ConfInt) != 2 || !(r.ConfInt[0] > 0) || math.IsInf(r.ConfInt[1], 0) {
		t.Fatalf("sequence %v", r.ConfInt)
	}
	q := r.Seq
	if q == nil || q.Outcome != SeqGreater || q.Hold != 0 || q.Looks != n/100 || q.NDecided == nil ||
		*q.NDecided != n || q.Z == nil || *q.Z <= 0 || q.LogE == nil || q.NGate != nil || q.Eps != nil ||
		q.TOpt != 1e4 {
		t.Fatalf("details %+v", q)
	}
	if r.KS != nil || r.TOST != nil || r.Binom != nil || r.GOF != nil {
		t.Fatal("other tests' details set")
	}
	// a decision is final
	if err := s.Push(rng.normals(100, 0.5)); err != nil {
		t.Fatal(err)
	}
	if m, _ := s.NDecided(); s.Outcome() != SeqGreater || m != n {
		t.Fatalf("after the decision: %v at %d", s.Outcome(), m)
	}
	if f, err := s.Finish(); err != nil || f.Decision != DecisionGreater {
		t.Fatalf("finish: %v %v", f, err)
	}
	text := s.String()
	if !strings.Contains(text, "Anytime-valid sequential test of the mean") ||
		!strings.Contains(text, "decision at alpha = 0.05: greater (at n = ") || text != s.Result().Format("x", "y") {
		t.Fatalf("block:\n%s", text)
	}
}

func TestSequentialTrueNullContinues(t *testing.T) {
	rng := newXorshift(2)
	s, _ := NewSequential(SeqMean, 0, nil)
	for i := 0; i < 50; i++ {
		if err := s.Push(rng.normals(100, 0)); err != nil {
			t.Fatal(err)
		}
	}
	r, err := s.Finish()
	if err != nil || s.Outcome() != SeqContinue || s.Hold() != 0 || s.N() != 5000 || r.Reject || r.PValue <= 0.05 {
		t.Fatalf("%v %v %+v", err, s.Outcome(), r)
	}
	if !strings.Contains(s.String(), "decision at alpha = 0.05: continue") {
		t.Fatal(s.String())
	}
}

func TestSequentialAllZerosHold(t *testing.T) {
	s, _ := NewSequential(SeqMean, 1, nil)
	if err := s.Push(make([]float64, 1000)); err != nil {
		t.Fatal(err)
	}
	h := s.Hold()
	if s.Outcome() != SeqContinue || !h.Has(SeqHoldDegenerate) || h.Has(SeqHoldFew) || h.Has(SeqHoldKurtosis) {
		t.Fatalf("%v hold %b", s.Outcome(), h)
	}
	r := s.Result()
	if r.PValue != 1 || !math.IsInf(r.ConfInt[0], -1) || !math.IsInf(r.ConfInt[1], 1) || r.StdError != nil {
		t.Fatalf("%+v", r)
	}
	q := r.Seq
	if q.Z != nil || q.LogE != nil || q.LogEMax != nil || q.NDecided != nil || q.NGate != nil || q.Looks != 1 {
		t.Fatalf("%+v", q)
	}
	// held for want of spread, not for the tails
	if _, err := s.Finish(); err != nil {
		t.Fatal(err)
	}
}

func TestSequentialMostlyZerosHeavyTail(t *testing.T) {
	rng := newXorshift(3)
	s, _ := NewSequential(SeqMean, 0, nil)
	frame := NewStream()
	for i := 0; i < 6; i++ {
		if err := frame.AddSlice(rng.sparse(100)); err != nil {
			t.Fatal(err)
		}
		if err := s.PushStream(frame); err != nil {
			t.Fatal(err)
		}
		if err := frame.Reset(); err != nil {
			t.Fatal(err)
		}
	}
	h := s.Hold()
	if s.N() != 600 || s.Looks() != 6 || h != SeqHoldKurtosis || s.Outcome() != SeqContinue {
		t.Fatalf("n %d looks %d hold %b %v", s.N(), s.Looks(), h, s.Outcome())
	}
	r, err := s.Finish()
	var ht *HeavyTailError
	if !errors.Is(err, ErrHeavyTail) || !errors.As(err, &ht) || ht.N != 600 || !(ht.NGate > 600) {
		t.Fatalf("finish: %v", err)
	}
	if errors.Is(err, ErrInvalidArgument) || r == nil || r.Seq.NGate == nil || *r.Seq.NGate != ht.NGate || r.Seq.LogE != nil {
		t.Fatalf("result with the error: %+v", r)
	}
	if !strings.Contains(err.Error(), "600 values") || ErrHeavyTail.Status != 11 {
		t.Fatal(err)
	}
}

func TestSequentialBadArguments(t *testing.T) {
	d := DefaultSeqOptions()
	bad := func(o SeqOptions, kind SeqKind, null float64, word string) {
		t.Helper()
		_, err := NewSequential(kind, null, &o)
		if !errors.Is(err, ErrInvalidArgument) || !strings.Contains(err.Error(), word) {
			t.Errorf("%s: %v", word, err)
		}
	}
	with := func(f func(o *SeqOptions)) SeqOptions { o := d; f(&o); return o }
	bad(with(func(o *SeqOptions) { o.Alpha = 1 }), SeqMean, 0, "Alpha")
	bad(with(func(o *SeqOptions) { o.Alpha = math.NaN() }), SeqMean, 0, "Alpha")
	bad(with(func(o *SeqOptions) { o.Eps = -1 }), SeqMean, 0, "Eps")
	bad(with(func(o *SeqOptions) { o.Eps = 0.1 }), SeqVar, 1, "Eps")
	bad(with(func(o *SeqOptions) { o.Eps, o.Alternative = 0.1, Less }), SeqMean, 0, "Eps")
	bad(with(func(o *SeqOptions) { o.TOpt = 0 }), SeqMean, 0, "TOpt")
	bad(with(func(o *SeqOptions) { o.KurtosisGate = -1 }), SeqMean, 0, "KurtosisGate")
	bad(with(func(o *SeqOptions) { o.VarUCBZ = math.Inf(1) }), SeqMean, 0, "VarUCBZ")
	bad(with(func(o *SeqOptions) { o.MinN = 1 }), SeqMean, 0, "MinN")
	bad(with(func(o *SeqOptions) { o.Alternative = 7 }), SeqMean, 0, "Alternative")
	bad(d, SeqVar, 0, "null value")
	bad(d, SeqMean2, math.NaN(), "null value")
	bad(d, SeqKind(9), 0, "kind 9")

	s, _ := NewSequential(SeqMean, 0, nil)
	if err := s.Push([]float64{1, 2}); err != nil {
		t.Fatal(err)
	}
	before := s.raw
	if err := s.Push([]float64{1, math.NaN()}); !errors.Is(err, ErrNonFinite) {
		t.Error(err)
	}
	if err := s.Push2([]float64{1}, []float64{2}); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	if err := s.PushMoments2(NewMoments(), NewMoments()); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	if err := s.PushMoments(nil); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	st := NewStream()
	st.Add(math.Inf(1))
	if err := s.PushStream(st); !errors.Is(err, ErrNonFinite) {
		t.Error(err)
	}
	if s.raw != before {
		t.Error("an error changed the test")
	}
	u, _ := NewSequential(SeqVar2, 1, nil)
	if err := u.Push([]float64{1}); !errors.Is(err, ErrInvalidArgument) || !strings.Contains(err.Error(), "one-sample") {
		t.Error(err)
	}
	if err := u.PushStream(st); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	// nil and zero values: errors, never panics
	var nilSeq *Sequential
	if err := nilSeq.Push([]float64{1}); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	if _, err := nilSeq.Finish(); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	if nilSeq.Result() != nil || nilSeq.Outcome() != SeqContinue || nilSeq.N() != 0 || nilSeq.String() != "<invalid Sequential>" {
		t.Error("nil accessors")
	}
	var zero Sequential
	if err := zero.Push([]float64{1}); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
	if _, err := zero.Finish(); !errors.Is(err, ErrInvalidArgument) {
		t.Error(err)
	}
}

func TestSequentialTwoSamplesAndVariances(t *testing.T) {
	rng := newXorshift(4)
	opt := DefaultSeqOptions()
	opt.Alternative = Less
	a, err := NewSequential(SeqMean2, 0, &opt)
	if err != nil {
		t.Fatal(err)
	}
	b := *a // a copy is an independent state
	for !a.Decided() && a.N() < 10000 {
		x, y := rng.normals(100, 0), rng.normals(150, 0.5)
		if err := a.Push2(x, y); err != nil {
			t.Fatal(err)
		}
		mx, my := NewMoments(), NewMoments()
		mx.AddSlice(x)
		my.AddSlice(y)
		if err := b.PushMoments2(mx, my); err != nil {
			t.Fatal(err)
		}
	}
	ra, rb := a.Result(), b.Result()
	if a.Outcome() != SeqLess || ra.Test != TestSeqMean2 || len(ra.N) != 2 || ra.N[1] != a.NY() ||
		2*a.NY() != 3*a.N() || ra.PValue != rb.PValue || b.Outcome() != SeqLess {
		t.Fatalf("%v %+v", a.Outcome(), ra)
	}

	v, _ := NewSequential(SeqVar, 1, nil)
	w, _ := NewSequential(SeqVar2, 1, nil)
	for i := 0; i < 30; i++ {
		x := rng.normals(100, 0)
		for j := range x {
			x[j] *= 2
		}
		v.Push(x)
		w.Push2(rng.normals(100, 0), rng.normals(100, 0))
	}
	if v.Outcome() != SeqGreater || v.Result().Test != TestSeqVar1 || w.Outcome() != SeqContinue ||
		w.Result().Test != TestSeqVar2 || len(w.Result().Estimate) != 1 {
		t.Fatalf("variances: %v %v", v.Outcome(), w.Outcome())
	}

	eq := DefaultSeqOptions()
	eq.Eps = 0.2
	e, _ := NewSequential(SeqMean, 0, &eq)
	for !e.Decided() && e.N() < 100000 {
		e.Push(rng.normals(500, 0))
	}
	r := e.Result()
	if e.Outcome() != SeqEqual || r.Reject || r.Seq.Eps == nil || *r.Seq.Eps != 0.2 {
		t.Fatalf("equivalence: %v %+v", e.Outcome(), r.Seq)
	}
	if SeqVar2.String() != "var2" || SeqKind(0).String() != "SeqKind(0)" || SeqContinue.String() != "continue" ||
		SeqEqual.String() != "equal" || TestSeqVar2.String() != "seq_var_2" {
		t.Error("names")
	}
}

// The Result is the C state: every number read from mcstat_seq itself, and
// a batch pushed as an array, an accumulator or a stream is one look.
func TestSequentialResultIsTheCState(t *testing.T) {
	rng := newXorshift(5)
	opt := DefaultSeqOptions()
	opt.TOpt, opt.KurtosisGate = 2000, 5
	a, _ := NewSequential(SeqMean, 0.1, &opt)
	b, _ := NewSequential(SeqMean, 0.1, &opt)
	c, _ := NewSequential(SeqMean, 0.1, &opt)
	for i := 0; i < 12; i++ {
		x := rng.normals(100, 0.3)
		if err := a.Push(x); err != nil {
			t.Fatal(err)
		}
		m := NewMoments()
		m.AddSlice(x)
		if err := b.PushMoments(m); err != nil {
			t.Fatal(err)
		}
		st := NewStream()
		st.AddSlice(x)
		if err := c.PushStream(st); err != nil {
			t.Fatal(err)
		}
		r := a.Result()
		q := r.Seq
		if b.Result().PValue != r.PValue || math.Abs(c.Result().Statistic-r.Statistic) > 1e-12*math.Abs(r.Statistic) {
			t.Fatalf("look %d: array, accumulator and stream differ", i)
		}
		raw := &a.raw
		if q.Looks != uint64(raw.looks) || q.Hold != SeqHold(raw.hold) || r.ConfInt[0] != float64(raw.cs[0]) ||
			r.ConfInt[1] != float64(raw.cs[1]) || r.N[0] != uint64(raw.x.n) {
			t.Fatalf("look %d: %+v against the state", i, q)
		}
		if lm := float64(raw.log_e_max); math.IsInf(lm, -1) {
			if q.LogEMax != nil || r.PValue != 1 {
				t.Fatalf("look %d: log_e_max -Inf", i)
			}
		} else if p := math.Min(1, math.Exp(-lm)); *q.LogEMax != lm || math.Abs(r.PValue-p) > 4e-16*p { // C's exp, Go's exp
			t.Fatalf("look %d: p %g, log_e_max %g", i, r.PValue, lm)
		}
		if le := float64(raw.log_e); math.IsInf(le, -1) != (q.LogE == nil) || (q.LogE != nil && *q.LogE != le) {
			t.Fatalf("look %d: log_e %g", i, le)
		}
		if (q.Z == nil) != math.IsNaN(r.Statistic) || (q.Z != nil && *q.Z != r.Statistic) {
			t.Fatalf("look %d: z", i)
		}
	}
	if err := CheckABI(); err != nil {
		t.Fatal(err)
	}
}
