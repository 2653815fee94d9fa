package mcstat

// PixelsTest: every test in both layouts and both widths against the single
// calls on each pixel's values (bit for bit but Welch's and the variance
// tests, within the bounds of mcstat.h), threads, bad arguments.

import (
	"errors"
	"math"
	"testing"
)

func lcg(seed uint64, n int) []float64 {
	s := seed
	v := make([]float64, n)
	for i := range v {
		s = s*6364136223846793005 + 1442695040888963407
		v[i] = 1 + float64(s>>11)*0x1p-53 - 0.5
	}
	return v
}

func TestPixelsTestMatchesSingleCalls(t *testing.T) {
	const n, p = 6, 200
	xs, ys := lcg(3, n*p), lcg(5, n*p) // seeds-major: value s of pixel i at s*p + i
	for s := 0; s < n; s++ {
		xs[s*p+4] = 2 // pixel 4 constant
	}
	rows := func(v []float64) []float64 {
		r := make([]float64, len(v))
		for k := range r {
			r[k] = v[(k%n)*p+k/n]
		}
		return r
	}
	f32 := func(v []float64) []float32 {
		r := make([]float32, len(v))
		for k := range v {
			r[k] = float32(v[k])
		}
		return r
	}
	xr, yr := rows(xs), rows(ys)
	single := map[PixelTest]func(x, y []float64, nv float64, alt Alternative) (*Result, error){
		PixelT1: func(x, _ []float64, nv float64, a Alternative) (*Result, error) { return TTest1(x, nv, a, 0.05) },
		PixelT2: func(x, y []float64, nv float64, a Alternative) (*Result, error) { return TTest2(x, y, nv, a, 0.05) },
		PixelT2Pooled: func(x, y []float64, nv float64, a Alternative) (*Result, error) {
			return TTest2Pooled(x, y, nv, a, 0.05)
		},
		PixelTPaired: func(x, y []float64, nv float64, a Alternative) (*Result, error) {
			return TTestPaired(x, y, nv, a, 0.05)
		},
		PixelVar1: func(x, _ []float64, nv float64, a Alternative) (*Result, error) { return VarTest1(x, nv, a, 0.05) },
		PixelVar2: func(x, y []float64, nv float64, a Alternative) (*Result, error) { return VarTest2(x, y, nv, a, 0.05) },
	}
	for test, call := range single {
		nv := 0.05
		if test == PixelVar1 || test == PixelVar2 {
			nv = 0.09
		}
		block := test == PixelT2 || test == PixelVar1 || test == PixelVar2
		for _, alt := range []Alternative{TwoSided, Less, Greater} {
			for layout := 0; layout < 4; layout++ {
				x := Pixels{N: n, ValueStride: p, PixelStride: 1}
				if layout%2 == 1 {
					x.ValueStride, x.PixelStride = 1, n
				}
				y := x
				switch layout {
				case 0:
					x.F64, y.F64 = xs, ys
				case 1:
					x.F64, y.F64 = xr, yr
				case 2:
					x.F32, y.F32 = f32(xs), f32(ys)
				default:
					x.F32, y.F32 = f32(xr), f32(yr)
				}
				var py *Pixels
				if test.twoSample() {
					py = &y
				}
				r, _ := PixelsTest(test, x, py, p, nv, alt, 0.05, 0, 2)
				if r == nil {
					t.Fatalf("test %d layout %d: no results", test, layout)
				}
				for i := 0; i < p; i++ {
					sx, sy := make([]float64, n), make([]float64, n)
					for s := 0; s < n; s++ {
						sx[s], sy[s] = xs[s*p+i], ys[s*p+i]
						if layout >= 2 {
							sx[s], sy[s] = float64(float32(sx[s])), float64(float32(sy[s]))
						}
					}
					want, err := call(sx, sy, nv, alt)
					if err != nil {
						var e *Error
						if !errors.As(err, &e) || int(r.Status[i]) != e.Status || !math.IsNaN(r.PValue[i]) {
							t.Fatalf("test %d layout %d pixel %d: status %d, single call %v", test, layout, i, r.Status[i], err)
						}
						continue
					}
					if r.Status[i] != 0 || r.NX[i] != want.N[0] {
						t.Fatalf("test %d layout %d pixel %d: status %d n %d", test, layout, i, r.Status[i], r.NX[i])
					}
					pv := want.PValue
					if block {
						tol := 2 * (3e-14 + 4e-16*math.Abs(math.Log(math.Max(pv, math.SmallestNonzeroFloat64))))
						if math.Abs(r.PValue[i]-pv) > tol*pv {
							t.Fatalf("test %d layout %d pixel %d: p %v, single call %v", test, layout, i, r.PValue[i], pv)
						}
					} else if math.Float64bits(r.PValue[i]) != math.Float64bits(pv) ||
						math.Float64bits(r.Statistic[i]) != math.Float64bits(want.Statistic) ||
						math.Float64bits(r.ConfLo[i]) != math.Float64bits(want.ConfInt[0]) ||
						int(r.Decision[i]) != int(want.Decision) {
						t.Fatalf("test %d layout %d pixel %d: not the single call's bits", test, layout, i)
					}
				}
			}
		}
	}
}

func TestPixelsTestThreadsAndBadArguments(t *testing.T) {
	const n, p = 4, 20000
	x := Pixels{F64: lcg(7, n*p), N: n, ValueStride: 1, PixelStride: n}
	y := Pixels{F64: lcg(9, n*p), N: n, ValueStride: 1, PixelStride: n}
	for _, test := range []PixelTest{PixelT2, PixelVar2} {
		nv := 0.0
		if test == PixelVar2 {
			nv = 1
		}
		a, err1 := PixelsTest(test, x, &y, p, nv, TwoSided, 0.05, 0, 1)
		b, err2 := PixelsTest(test, x, &y, p, nv, TwoSided, 0.05, 0, 2)
		if err1 != nil || err2 != nil {
			t.Fatal(err1, err2)
		}
		for i := range a.PValue {
			if math.Float64bits(a.PValue[i]) != math.Float64bits(b.PValue[i]) ||
				math.Float64bits(a.ConfLo[i]) != math.Float64bits(b.ConfLo[i]) {
				t.Fatalf("test %d pixel %d: threads changed the result", test, i)
			}
		}
	}
	if in, opt, out := PixelStructSizes(); in != 56 || opt != 24 || out != 128 {
		t.Fatalf("struct sizes %d %d %d", in, opt, out)
	}
	short := Pixels{F64: x.F64[:n*p-1], N: n, ValueStride: 1, PixelStride: n}
	bad := []struct {
		name string
		f    func() (*PixelTestResults, error)
	}{
		{"short slice", func() (*PixelTestResults, error) { return PixelsTest(PixelT1, short, nil, p, 0, TwoSided, 0.05, 0, 1) }},
		{"y missing", func() (*PixelTestResults, error) { return PixelsTest(PixelT2, x, nil, p, 0, TwoSided, 0.05, 0, 1) }},
		{"y given", func() (*PixelTestResults, error) { return PixelsTest(PixelT1, x, &y, p, 0, TwoSided, 0.05, 0, 1) }},
		{"alpha", func() (*PixelTestResults, error) { return PixelsTest(PixelT1, x, nil, p, 0, TwoSided, 1.5, 0, 1) }},
		{"threads", func() (*PixelTestResults, error) { return PixelsTest(PixelT1, x, nil, p, 0, TwoSided, 0.05, 0, 0) }},
		{"sigma2", func() (*PixelTestResults, error) { return PixelsTest(PixelVar1, x, nil, p, -1, TwoSided, 0.05, 0, 1) }},
		{"both widths", func() (*PixelTestResults, error) {
			z := x
			z.F32 = []float32{1}
			return PixelsTest(PixelT1, z, nil, p, 0, TwoSided, 0.05, 0, 1)
		}},
		{"weights", func() (*PixelTestResults, error) {
			z := x
			z.Weights = []float64{0.5, 0.5}
			return PixelsTest(PixelT1, z, nil, p, 0, TwoSided, 0.05, 0, 1)
		}},
		{"unequal pairs", func() (*PixelTestResults, error) {
			z := Pixels{F64: y.F64, N: 3, ValueStride: 1, PixelStride: n}
			return PixelsTest(PixelTPaired, x, &z, p, 0, TwoSided, 0.05, 0, 1)
		}},
	}
	for _, c := range bad {
		if r, err := c.f(); err == nil || r != nil {
			t.Errorf("%s: accepted", c.name)
		}
	}
}
