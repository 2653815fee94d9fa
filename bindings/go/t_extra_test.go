package mcstat

// The pooled and paired t tests, the log p-value and the interval at
// another level, against R (tests/data/t_ref.tsv, tools/refgen/make_t_ref.R).

import (
	"errors"
	"math"
	"strconv"
	"strings"
	"testing"
)

// near: |got - want| within tol of scale, plus a few ulps of want.
func near(got, want, scale, tol float64) bool {
	return got == want || math.Abs(got-want) <= tol*scale+8*2.220446049250313e-16*math.Abs(want)
}

func TestPooledAndPairedAgainstR(t *testing.T) {
	alts := []Alternative{TwoSided, Less, Greater}
	seen := map[string]int{}
	for _, f := range readLines(t, "t_ref.tsv") {
		kind := f[0]
		if kind != "pooled" && kind != "paired" {
			continue
		}
		seen[kind]++
		a, _ := strconv.Atoi(f[1])
		mu, alpha := num(t, f[2]), num(t, f[3])
		x, y := nums(t, f[4]), nums(t, f[5])
		stat, df, p, logp := num(t, f[6]), num(t, f[7]), num(t, f[8]), num(t, f[9])
		lo, hi, se := num(t, f[10]), num(t, f[11]), num(t, f[14])
		conf2, lo2, hi2 := num(t, f[15]), num(t, f[16]), num(t, f[17])
		var r *Result
		var err error
		if kind == "pooled" {
			r, err = TTest2Pooled(x, y, mu, alts[a], alpha)
			if err == nil {
				var mx, my Moments
				mx.AddSlice(x)
				my.AddSlice(y)
				rm, err2 := TTest2PooledMoments(&mx, &my, mu, alts[a], alpha)
				if err2 != nil || rm.Statistic != r.Statistic || rm.PValue != r.PValue {
					t.Errorf("pooled on accumulators differs: %v %v", rm, err2)
				}
			}
		} else {
			r, err = TTestPaired(x, y, mu, alts[a], alpha)
		}
		if err != nil {
			t.Fatalf("%s: %v", kind, err)
		}
		want := map[string]Test{"pooled": TestT2Pooled, "paired": TestTPaired}[kind]
		if r.Test != want || len(r.DF) != 1 {
			t.Errorf("%s: test %v, df %v", kind, r.Test, r.DF)
		}
		if !near(r.Statistic, stat, math.Abs(stat), 1e-11) || !near(r.DF[0], df, df, 1e-13) {
			t.Errorf("%s: statistic %v df %v, R %v %v", kind, r.Statistic, r.DF[0], stat, df)
		}
		if p > 1e-300 && !near(r.PValue, p, p, 1e-11) {
			t.Errorf("%s: p %v, R %v", kind, r.PValue, p)
		}
		lp, err := r.LogPValue()
		if err != nil || math.IsInf(lp, 0) || !near(lp, logp, math.Max(1, math.Abs(logp)), 1e-12) {
			t.Errorf("%s: log p %v (%v), R %v", kind, lp, err, logp)
		}
		width := hi - lo
		if math.IsInf(width, 0) {
			width = se
		}
		if !near(r.ConfInt[0], lo, width, 1e-10) || !near(r.ConfInt[1], hi, width, 1e-10) {
			t.Errorf("%s: interval %v, R [%v %v]", kind, r.ConfInt, lo, hi)
		}
		width2 := hi2 - lo2
		if math.IsInf(width2, 0) {
			width2 = se
		}
		ci, err := r.ConfIntAt(conf2)
		if err != nil || !near(ci[0], lo2, width2, 1e-10) || !near(ci[1], hi2, width2, 1e-10) {
			t.Errorf("%s at %v: %v (%v), R [%v %v]", kind, conf2, ci, err, lo2, hi2)
		}
	}
	if seen["pooled"] < 20 || seen["paired"] < 20 {
		t.Fatalf("rows read: %v", seen)
	}
}

func TestPairedAndLevelErrors(t *testing.T) {
	x := []float64{1, 2, 3.5, 4}
	if _, err := TTestPaired(x, x[:3], 0, TwoSided, 0.05); !errors.Is(err, ErrInvalidArgument) ||
		!strings.Contains(err.Error(), "x has 4, y 3") {
		t.Errorf("paired lengths: %v", err)
	}
	r, err := TTest2Pooled(x, []float64{0.5, 1, 1.25}, 0, TwoSided, 0.05)
	if err != nil {
		t.Fatal(err)
	}
	for _, bad := range []float64{0, 1, math.NaN(), -0.5} {
		if _, err := r.ConfIntAt(bad); !errors.Is(err, ErrInvalidArgument) {
			t.Errorf("level %v: %v", bad, err)
		}
	}
	var nilResult *Result
	if _, err := nilResult.LogPValue(); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil result: %v", err)
	}
}
