package mcstat

// TTest2Pixels: every pixel against TTest2 on its two samples, float32 and
// float64, luminance weights, pixels that cannot be tested, bad sizes.

import (
	"errors"
	"math"
	"testing"
)

func TestTTest2PixelsMatchesTTest2(t *testing.T) {
	const nx, ny, pixels, ch = 6, 9, 40, 3
	w := []float64{0.2126, 0.7152, 0.0722}
	s := uint64(3)
	next := func() float64 {
		s = s*6364136223846793005 + 1442695040888963407
		return float64(s>>11)*0x1p-53 - 0.5
	}
	x, y := make([]float64, nx*pixels*ch), make([]float64, ny*pixels*ch)
	for i := range x {
		x[i] = 1 + next() + 0.2*float64(i%7)
	}
	for i := range y {
		y[i] = 1 + 2*next()
	}
	for k := 0; k < nx; k++ { // pixel 5 constant in both samples
		for c := 0; c < ch; c++ {
			x[k*pixels*ch+5*ch+c] = 2
		}
	}
	for k := 0; k < ny; k++ {
		for c := 0; c < ch; c++ {
			y[k*pixels*ch+5*ch+c] = 2
		}
	}
	x[2*pixels*ch+7*ch+1] = math.NaN() // pixel 7
	xf, yf := make([]float32, len(x)), make([]float32, len(y))
	for i := range x {
		xf[i] = float32(x[i])
	}
	for i := range y {
		yf[i] = float32(y[i])
	}
	for _, f32 := range []bool{false, true} {
		var r *PixelResults
		var err error
		if f32 {
			r, err = TTest2PixelsF32(xf, nx, yf, ny, pixels, ch, w, 0, TwoSided, 0.05, 0)
		} else {
			r, err = TTest2Pixels(x, nx, y, ny, pixels, ch, w, 0, TwoSided, 0.05, 0)
		}
		if !errors.Is(err, ErrDegenerate) { // pixel 5's, the first that fails
			t.Fatalf("f32 %v: error %v, want the first failing pixel's", f32, err)
		}
		for i := 0; i < pixels; i++ {
			sx, sy := make([]float64, nx), make([]float64, ny)
			val := func(k, i, c int, isx bool) float64 {
				j := k*pixels*ch + i*ch + c
				switch {
				case isx && f32:
					return float64(xf[j])
				case isx:
					return x[j]
				case f32:
					return float64(yf[j])
				}
				return y[j]
			}
			for k := range sx {
				for c := 0; c < ch; c++ {
					sx[k] += w[c] * val(k, i, c, true)
				}
			}
			for k := range sy {
				for c := 0; c < ch; c++ {
					sy[k] += w[c] * val(k, i, c, false)
				}
			}
			one, err := TTest2(sx, sy, 0, TwoSided, 0.05)
			if i == 5 || i == 7 {
				if err == nil || r.Status[i] == 0 || !math.IsNaN(r.PValue[i]) || !math.IsNaN(r.ConfLo[i]) {
					t.Errorf("pixel %d: status %d, p %g; want a failure (TTest2: %v)", i, r.Status[i], r.PValue[i], err)
				}
				continue
			}
			if err != nil || r.Status[i] != 0 {
				t.Fatalf("pixel %d: status %d, TTest2 %v", i, r.Status[i], err)
			}
			if e := math.Abs(r.PValue[i]-one.PValue) / one.PValue; e > 6e-14 {
				t.Errorf("pixel %d: p %.17g, TTest2 %.17g", i, r.PValue[i], one.PValue)
			}
			if math.Abs(r.Statistic[i]-one.Statistic) > 1e-14*math.Max(1, math.Abs(one.Statistic)) ||
				math.Abs(r.DF[i]-one.DF[0]) > 1e-13*one.DF[0] ||
				math.Abs(r.ConfLo[i]-one.ConfInt[0]) > 1e-13*math.Max(1, math.Abs(one.ConfInt[0])) ||
				math.Abs(r.ConfHi[i]-one.ConfInt[1]) > 1e-13*math.Max(1, math.Abs(one.ConfInt[1])) {
				t.Errorf("pixel %d: t %g df %g [%g, %g], TTest2 %g %g %v", i, r.Statistic[i], r.DF[i], r.ConfLo[i],
					r.ConfHi[i], one.Statistic, one.DF[0], one.ConfInt)
			}
		}
	}
	r, _ := TTest2Pixels(x, nx, y, ny, pixels, ch, w, 0, TwoSided, 0.05, NoIntervals)
	if r.ConfLo != nil || r.ConfHi != nil || len(r.PValue) != pixels {
		t.Errorf("NoIntervals: intervals %v %v", r.ConfLo, r.ConfHi)
	}
}

func TestTTest2PixelsBadArguments(t *testing.T) {
	x := make([]float64, 12)
	if _, err := TTest2Pixels(x, 3, x, 3, 5, 1, nil, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("short data: %v", err)
	}
	if _, err := TTest2Pixels(x, 2, x, 2, 2, 3, []float64{1, 1}, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("2 weights for 3 channels: %v", err)
	}
	if _, err := TTest2Pixels(x, 2, x, 2, 2, 3, nil, 0, TwoSided, 0.05, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("no weights for 3 channels: %v", err)
	}
	if _, err := TTest2Pixels(x, 2, x, 2, 6, 1, nil, 0, TwoSided, 1.5, 0); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("alpha 1.5: %v", err)
	}
	if _, err := TTest2PixelsF32(nil, 2, nil, 2, 0, 1, nil, 0, TwoSided, 0.05, 0); err != nil {
		t.Errorf("no pixels: %v", err)
	}
}

func TestTQuantilesMatchTheSingleCall(t *testing.T) {
	df := []float64{0.5, 2e3, 1e9}
	for i := 0; i < 500; i++ {
		df = append(df, 1.0+0.37*float64(i))
	}
	for _, c := range []struct {
		p     float64
		upper bool
	}{{0.025, true}, {1e-9, false}, {0.4, true}} {
		x, err := TQuantiles(c.p, df, c.upper)
		if err != nil {
			t.Fatal(err)
		}
		for i, d := range df {
			want, err := TQuantile(c.p, d, c.upper)
			if err != nil || math.Abs(x[i]-want) > 2e-14*math.Abs(want) {
				t.Fatalf("p %g df %g: %g vs %g (%v)", c.p, d, x[i], want, err)
			}
		}
	}
	x, err := TQuantiles(0.05, []float64{3, math.NaN()}, true)
	if err == nil || !math.IsNaN(x[1]) || math.IsNaN(x[0]) {
		t.Fatalf("a NaN df: %v %v", x, err)
	}
	if _, err := TQuantiles(math.NaN(), []float64{3}, true); err == nil {
		t.Fatal("p NaN accepted")
	}
}
