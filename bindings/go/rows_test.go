package mcstat

// Per-pixel rows, arrays of accumulators, streams: each row's result is bit
// for bit the single call on that row (libmcstat's promise), failed rows
// are reported per row, and bad shapes are errors, never out-of-bounds reads.

import (
	"bytes"
	"errors"
	"math"
	"testing"
	"unsafe"
)

// sameBits compares two results as libmcstat wrote them, NaNs included.
func sameBits(a, b *Result) bool {
	n := unsafe.Sizeof(a.raw)
	return bytes.Equal(unsafe.Slice((*byte)(unsafe.Pointer(&a.raw)), n), unsafe.Slice((*byte)(unsafe.Pointer(&b.raw)), n))
}

// pixels is the lew data set as 10 rows of 20 values, and y a second image
// of the same shape (a shifted, rescaled copy, rows reversed).
func pixels(t *testing.T) (x, y Matrix) {
	lew := loadRef(t).data["lew"]
	if len(lew) != 200 {
		t.Fatalf("lew has %d values", len(lew))
	}
	yd := make([]float64, 200)
	for i := range yd {
		yd[i] = 1.5*lew[199-i] + 3
	}
	return Matrix{Data: lew, Rows: 10, Cols: 20}, Matrix{Data: yd, Rows: 10, Cols: 20}
}

func row(m Matrix, i int) []float64 {
	s := m.Stride
	if s == 0 {
		s = m.Cols
	}
	return m.Data[i*s : i*s+m.Cols]
}

func TestMatrixRowsAreTheSingleCalls(t *testing.T) {
	x, y := pixels(t)
	type single func(i int) (*Result, error)
	type rows func(flags RowFlags) ([]RowResult, error)
	cases := []struct {
		name string
		rows rows
		one  single
	}{
		{"t1", func(f RowFlags) ([]RowResult, error) { return TTest1Matrix(x, -2, TwoSided, 0.05, f) },
			func(i int) (*Result, error) { return TTest1(row(x, i), -2, TwoSided, 0.05) }},
		{"t2", func(f RowFlags) ([]RowResult, error) { return TTest2Matrix(x, y, 0.5, Less, 0.1, f) },
			func(i int) (*Result, error) { return TTest2(row(x, i), row(y, i), 0.5, Less, 0.1) }},
		{"var1", func(f RowFlags) ([]RowResult, error) { return VarTest1Matrix(x, 300, Greater, 0.05, f) },
			func(i int) (*Result, error) { return VarTest1(row(x, i), 300, Greater, 0.05) }},
		{"var2", func(f RowFlags) ([]RowResult, error) { return VarTest2Matrix(x, y, 1, TwoSided, 0.01, f) },
			func(i int) (*Result, error) { return VarTest2(row(x, i), row(y, i), 1, TwoSided, 0.01) }},
	}
	for _, c := range cases {
		got, err := c.rows(0)
		if err != nil || len(got) != 10 {
			t.Fatalf("%s: %v", c.name, err)
		}
		cheap, err := c.rows(NoIntervals)
		if err != nil {
			t.Fatalf("%s no intervals: %v", c.name, err)
		}
		for i := range got {
			want, err := c.one(i)
			if err != nil || got[i].Err != nil || !sameBits(got[i].Result, want) {
				t.Errorf("%s row %d: %v %v", c.name, i, got[i], err)
			}
			r := cheap[i].Result
			if r.PValue != want.PValue || r.Critical != nil || r.ConfInt != nil || r.Decision != want.Decision {
				t.Errorf("%s row %d without intervals: %+v", c.name, i, r)
			}
		}
	}
	// a strided view: every other row of x
	half := Matrix{Data: x.Data, Rows: 5, Cols: 20, Stride: 40}
	got, err := TTest1Matrix(half, 0, TwoSided, 0.05, 0)
	if err != nil {
		t.Fatal(err)
	}
	for i := range got {
		want, _ := TTest1(row(x, 2*i), 0, TwoSided, 0.05)
		if !sameBits(got[i].Result, want) {
			t.Errorf("stride 40, row %d", i)
		}
	}
}

func TestMatrixRowErrors(t *testing.T) {
	x, y := pixels(t)
	d := append([]float64(nil), x.Data...)
	d[45] = math.NaN() // row 2
	for i := 60; i < 80; i++ {
		d[i] = 7 // row 3: constant
	}
	m := Matrix{Data: d, Rows: 10, Cols: 20}
	got, err := TTest1Matrix(m, 0, TwoSided, 0.05, 0)
	if !errors.Is(err, ErrNonFinite) || len(got) != 10 {
		t.Fatalf("first failing row's error: %v", err)
	}
	if !errors.Is(got[2].Err, ErrNonFinite) || got[2].Result != nil || !errors.Is(got[3].Err, ErrDegenerate) ||
		got[0].Err != nil || got[9].Result == nil {
		t.Errorf("per-row errors: %v %v %v", got[2], got[3], got[0])
	}
	omit, _ := TTest1Matrix(m, 0, TwoSided, 0.05, OmitNaN)
	clean := append(append([]float64(nil), d[40:45]...), d[46:60]...)
	want, _ := TTest1(clean, 0, TwoSided, 0.05)
	if omit[2].Err != nil || !sameBits(omit[2].Result, want) || omit[2].Result.N[0] != 19 {
		t.Errorf("OmitNaN row: %v", omit[2])
	}
	// shapes: nothing is read past the slice
	short := Matrix{Data: x.Data[:199], Rows: 10, Cols: 20}
	if r, err := TTest1Matrix(short, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) || r != nil {
		t.Errorf("short data: %v", err)
	}
	if _, err := TTest2Matrix(x, Matrix{Data: y.Data, Rows: 9, Cols: 20}, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("rows differ: %v", err)
	}
	if _, err := VarTest1Matrix(Matrix{Data: x.Data, Rows: -1, Cols: 20}, 1, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("negative rows: %v", err)
	}
	huge := Matrix{Data: x.Data, Rows: 3, Cols: 20, Stride: math.MaxInt / 2}
	if _, err := VarTest1Matrix(huge, 1, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("overflowing stride: %v", err)
	}
	if r, err := VarTest2Matrix(x, y, 1, TwoSided, 0.05, RowFlags(64)); !errors.Is(err, ErrInvalidArgument) || r != nil {
		t.Errorf("unknown flag: %v", err)
	}
	if r, err := TTest1Matrix(Matrix{}, 0, TwoSided, 0.05, 0); err != nil || len(r) != 0 {
		t.Errorf("no rows: %v %v", r, err)
	}
}

func TestMomentsRows(t *testing.T) {
	x, y := pixels(t)
	a, err := NewMomentsRows(10)
	if err != nil {
		t.Fatal(err)
	}
	// two batches of 10 values per pixel into one array, and into two merged
	first := Matrix{Data: x.Data, Rows: 10, Cols: 10, Stride: 20}
	second := Matrix{Data: x.Data[10:], Rows: 10, Cols: 10, Stride: 20}
	if _, err := a.Add(first, 0); err != nil {
		t.Fatal(err)
	}
	if _, err := a.Add(second, 0); err != nil {
		t.Fatal(err)
	}
	b, _ := NewMomentsRows(10)
	c, _ := NewMomentsRows(10)
	_, _ = b.Add(first, 0)
	_, _ = c.Add(second, 0)
	if err := b.Merge(c); err != nil {
		t.Fatal(err)
	}
	ab, err := a.MarshalBinary()
	bb, _ := b.MarshalBinary()
	if err != nil || len(ab) != 960 || !bytes.Equal(ab, bb) {
		t.Fatalf("batches A then B differ from A merged with B (%v)", err)
	}
	for i := 0; i < 10; i++ {
		m := NewMoments()
		_ = m.AddSlice(row(x, i))
		if a.At(i).N() != 20 || relErr(a.At(i).Mean(), m.Mean()) > 1e-15 || relErr(a.At(i).Var(), m.Var()) > 1e-13 {
			t.Errorf("pixel %d: mean %g var %g vs %g %g", i, a.At(i).Mean(), a.At(i).Var(), m.Mean(), m.Var())
		}
	}
	back := &MomentsRows{}
	if err := back.UnmarshalBinary(ab); err != nil || back.Len() != 10 {
		t.Fatalf("UnmarshalBinary: %v", err)
	}
	if bb2, _ := back.MarshalBinary(); !bytes.Equal(bb2, ab) {
		t.Error("round trip changed the bytes")
	}
	bad := append([]byte(nil), ab...)
	bad[96*4+40] ^= 1
	if err := back.UnmarshalBinary(bad); !errors.Is(err, ErrCorrupt) || back.Len() != 10 {
		t.Errorf("corrupt record: %v", err)
	}
	if err := back.UnmarshalBinary(ab[:500]); !errors.Is(err, ErrCorrupt) {
		t.Errorf("truncated: %v", err)
	}
	// the tests on the array are the tests on each accumulator
	ya, _ := NewMomentsRows(10)
	_, _ = ya.Add(y, 0)
	checks := []struct {
		name string
		rows func() ([]RowResult, error)
		one  func(i int) (*Result, error)
	}{
		{"t1", func() ([]RowResult, error) { return TTest1MomentsRows(a, -2, TwoSided, 0.05, 0) },
			func(i int) (*Result, error) { return TTest1Moments(a.At(i), -2, TwoSided, 0.05) }},
		{"t2", func() ([]RowResult, error) { return TTest2MomentsRows(a, ya, 0, Greater, 0.05, 0) },
			func(i int) (*Result, error) { return TTest2Moments(a.At(i), ya.At(i), 0, Greater, 0.05) }},
		{"var1", func() ([]RowResult, error) { return VarTest1MomentsRows(a, 200, Less, 0.05, 0) },
			func(i int) (*Result, error) { return VarTest1Moments(a.At(i), 200, Less, 0.05) }},
		{"var2", func() ([]RowResult, error) { return VarTest2MomentsRows(a, ya, 0.5, TwoSided, 0.05, 0) },
			func(i int) (*Result, error) { return VarTest2Moments(a.At(i), ya.At(i), 0.5, TwoSided, 0.05) }},
	}
	for _, c := range checks {
		got, err := c.rows()
		if err != nil || len(got) != 10 {
			t.Fatalf("%s: %v", c.name, err)
		}
		for i := range got {
			want, err := c.one(i)
			if err != nil || got[i].Err != nil || !sameBits(got[i].Result, want) {
				t.Errorf("%s row %d: %v %v", c.name, i, got[i], err)
			}
		}
	}
	// a failing row is left unchanged and reported; the others are added
	d := append([]float64(nil), x.Data[:20]...)
	d[13] = math.Inf(1)
	before := a.At(1).N()
	rowErr, err := a.Add(Matrix{Data: d, Rows: 10, Cols: 2}, 0)
	if !errors.Is(err, ErrNonFinite) || !errors.Is(rowErr[6], ErrNonFinite) || rowErr[1] != nil ||
		a.At(6).N() != 20 || a.At(1).N() != before+2 {
		t.Errorf("failing row: %v %v", err, rowErr)
	}
	if _, err := TTest2MomentsRows(a, c, 0, TwoSided, 0.05, 0); err != nil {
		t.Errorf("equal lengths: %v", err)
	}
	short, _ := NewMomentsRows(3)
	if _, err := TTest2MomentsRows(a, short, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("lengths differ: %v", err)
	}
	if err := a.Merge(short); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("merge lengths differ: %v", err)
	}
	if _, err := a.Add(Matrix{Data: x.Data, Rows: 3, Cols: 1}, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("add rows differ: %v", err)
	}
	if _, err := TTest1MomentsRows(a, 0, TwoSided, 0.05, OmitNaN); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("OmitNaN on accumulators: %v", err)
	}
	if _, err := NewMomentsRows(-1); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("-1 rows: %v", err)
	}
	var zero MomentsRows // the zero value is an empty array
	if r, err := TTest1MomentsRows(&zero, 0, TwoSided, 0.05, 0); err != nil || len(r) != 0 {
		t.Errorf("empty array: %v", err)
	}
}

func TestMomentsOmitNaNAndSummary(t *testing.T) {
	lew := loadRef(t).data["lew"]
	m := NewMoments()
	withNaN := append(append([]float64{math.NaN()}, lew...), math.NaN())
	if o, err := m.AddSliceOmitNaN(withNaN); err != nil || o != 2 || m.N() != 200 {
		t.Errorf("omitted %d (%v)", o, err)
	}
	if _, err := m.AddSliceOmitNaN([]float64{1, math.Inf(-1)}); !errors.Is(err, ErrNonFinite) || m.N() != 200 {
		t.Errorf("Inf: %v", err)
	}
	// a summary gives exactly the tests of its data
	s, err := MomentsFromSummary(m.N(), m.Mean(), m.Var()*float64(m.N()-1))
	if err != nil {
		t.Fatal(err)
	}
	a, _ := TTest1Moments(m, -2, TwoSided, 0.05)
	b, _ := TTest1Moments(s, -2, TwoSided, 0.05)
	if relErr(a.PValue, b.PValue) > 1e-12 || relErr(a.Statistic, b.Statistic) > 1e-12 {
		t.Errorf("summary: %g vs %g", b.PValue, a.PValue)
	}
	// the zero value is an empty accumulator, bit for bit NewMoments'
	var zero Moments
	if !math.IsInf(zero.Min(), 1) || zero.N() != 0 {
		t.Errorf("zero value: min %g", zero.Min())
	}
	_ = zero.AddSlice(lew)
	zb, _ := zero.MarshalBinary()
	fresh := NewMoments()
	_ = fresh.AddSlice(lew)
	if fb, _ := fresh.MarshalBinary(); !bytes.Equal(zb, fb) {
		t.Error("the zero Moments differs from NewMoments()")
	}
	// nil accumulators are refused
	var none *Moments
	if err := none.Add(1); !errors.Is(err, ErrInvalidArgument) || none.N() != 0 || !math.IsNaN(none.Mean()) {
		t.Errorf("nil Add: %v", err)
	}
	if _, err := TTest2Moments(fresh, none, 0, TwoSided, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil y: %v", err)
	}
	if _, err := none.MarshalBinary(); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil MarshalBinary: %v", err)
	}
	if err := none.UnmarshalBinary(zb); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil UnmarshalBinary: %v", err)
	}
	if err := fresh.Merge(none); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("merging nil: %v", err)
	}
	var rows *MomentsRows
	if r, err := TTest1MomentsRows(rows, 0, TwoSided, 0.05, 0); err != nil || len(r) != 0 || rows.At(0) != nil {
		t.Errorf("nil rows: %v", err)
	}
	if err := rows.UnmarshalBinary(zb); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil rows UnmarshalBinary: %v", err)
	}
	var cache *KSCache
	cache.Close()
	if h, m, e := cache.Stats(); h+m+e != 0 {
		t.Error("nil cache stats")
	}
	var res *Result
	if res.String() != "<nil>" {
		t.Error("nil result")
	}
	if _, err := MomentsFromSummary(0, 1, 0); !errors.Is(err, ErrTooFew) {
		t.Errorf("n = 0: %v", err)
	}
	if _, err := MomentsFromSummary(5, 1, -1); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("m2 < 0: %v", err)
	}
	if _, err := MomentsFromSummary(5, math.NaN(), 1); !errors.Is(err, ErrNonFinite) {
		t.Errorf("NaN mean: %v", err)
	}
}

func TestStream(t *testing.T) {
	lew := loadRef(t).data["lew"]
	var data []float64
	for k := 0; k < 6; k++ { // 1200 values: the buffer (492) is flushed twice
		data = append(data, lew...)
	}
	s := NewStream()
	for _, v := range data[:700] {
		if err := s.Add(v); err != nil {
			t.Fatal(err)
		}
	}
	if err := s.AddSlice(data[700:]); err != nil {
		t.Fatal(err)
	}
	got, err := s.Moments()
	want := NewMoments()
	_ = want.AddSlice(data)
	if err != nil || got.N() != 1200 || relErr(got.Mean(), want.Mean()) > 1e-15 || relErr(got.Var(), want.Var()) > 1e-13 {
		t.Fatalf("stream moments %v: n %d mean %g var %g", err, got.N(), got.Mean(), got.Var())
	}
	r, err := s.CheckMean(-1.5, 0, 0.05)
	w, _ := TTest1Moments(got, -1.5, TwoSided, 0.05)
	if err != nil || !sameBits(r, w) {
		t.Errorf("CheckMean with no tolerance is the t test: %v\n%v", r, w)
	}
	tol, err := s.CheckMean(w.Estimate[0]+0.1, 0.5, 0.05)
	if err != nil || tol.Reject || tol.Alpha != 0.025 {
		t.Errorf("within tolerance: %v %v", tol, err)
	}
	v, err := s.CheckVar(1e-3, 0.05)
	vw, _ := VarTest1Moments(got, 1e-3, Greater, 0.05)
	if err != nil || !v.Reject || !sameBits(v, vw) {
		t.Errorf("CheckVar: %v %v", v, err)
	}
	// merge, flush, non-finite values
	other := NewStream()
	_ = other.AddSlice(data[:10])
	_ = other.Add(math.NaN())
	if err := s.Merge(other); err != nil || s.NNonFinite() != 1 || s.NOverflow() != 0 {
		t.Fatalf("merge: %v, %d non-finite", err, s.NNonFinite())
	}
	if err := s.Flush(); err != nil {
		t.Fatal(err)
	}
	if m, _ := s.Moments(); m.N() != 1210 {
		t.Errorf("after merge: n %d", m.N())
	}
	if _, err := s.CheckMean(0, 0, 0.05); !errors.Is(err, ErrNonFinite) {
		t.Errorf("a stream that saw NaN: %v", err)
	}
	if err := s.Reset(); err != nil || s.NNonFinite() != 0 {
		t.Errorf("reset: %v", err)
	}
	if _, err := s.CheckMean(0, -1, 0.05); err == nil {
		t.Error("negative tolerance accepted")
	}
	// the zero value is an empty stream; a nil one is refused, never written through
	var zero Stream
	if err := zero.AddSlice(data[:600]); err != nil {
		t.Fatal(err)
	}
	if m, err := zero.Moments(); err != nil || m.N() != 600 {
		t.Errorf("zero stream: %v", err)
	}
	var none *Stream
	if err := none.Add(1); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil stream Add: %v", err)
	}
	if err := none.AddSlice([]float64{1, 2}); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil stream AddSlice: %v", err)
	}
	if err := none.Flush(); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil stream Flush: %v", err)
	}
	if _, err := none.CheckVar(1, 0.05); !errors.Is(err, ErrInvalidArgument) || none.NNonFinite() != 0 {
		t.Errorf("nil stream CheckVar: %v", err)
	}
	if err := s.Merge(none); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("merging a nil stream: %v", err)
	}
}

// The names before 0.2.0 give the same results as the ones they became.
func TestDeprecatedRowsNames(t *testing.T) {
	a, _ := NewMomentsRows(3)
	b, _ := NewMomentsRows(3)
	if _, err := a.Add(Matrix{Data: []float64{1, 2, 4, 0, 3, 1, 5, 2, 2, 7, 1, 4}, Rows: 3, Cols: 4, Stride: 4}, 0); err != nil {
		t.Fatal(err)
	}
	if _, err := b.Add(Matrix{Data: []float64{2, 3, 1, 5, 0, 1, 8, 2, 2, 6, 3, 3, 9, 1, 0}, Rows: 3, Cols: 5, Stride: 5}, 0); err != nil {
		t.Fatal(err)
	}
	type call func() ([]RowResult, error)
	pairs := [][2]call{
		{func() ([]RowResult, error) { return TTest1Rows(a, 1, TwoSided, 0.05, 0) },
			func() ([]RowResult, error) { return TTest1MomentsRows(a, 1, TwoSided, 0.05, 0) }},
		{func() ([]RowResult, error) { return TTest2Rows(a, b, 0, Less, 0.05, 0) },
			func() ([]RowResult, error) { return TTest2MomentsRows(a, b, 0, Less, 0.05, 0) }},
		{func() ([]RowResult, error) { return VarTest1Rows(a, 2, Greater, 0.05, 0) },
			func() ([]RowResult, error) { return VarTest1MomentsRows(a, 2, Greater, 0.05, 0) }},
		{func() ([]RowResult, error) { return VarTest2Rows(a, b, 1, TwoSided, 0.05, 0) },
			func() ([]RowResult, error) { return VarTest2MomentsRows(a, b, 1, TwoSided, 0.05, 0) }},
	}
	for k, p := range pairs {
		old, err1 := p[0]()
		cur, err2 := p[1]()
		if err1 != nil || err2 != nil || len(old) != 3 || len(cur) != 3 {
			t.Fatalf("pair %d: %v %v", k, err1, err2)
		}
		for i := range old {
			if old[i].Err != nil || cur[i].Err != nil || !sameBits(old[i].Result, cur[i].Result) {
				t.Errorf("pair %d row %d differs", k, i)
			}
		}
	}
}
