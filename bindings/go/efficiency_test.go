package mcstat

// The efficiency-ratio test against the 50-digit mpmath oracle
// (tests/data/efficiency_ref.tsv, tools/refgen/make_efficiency_ref.py).

import (
	"errors"
	"strconv"
	"testing"
)

func TestEfficiencyAgainstOracle(t *testing.T) {
	alts := []Alternative{TwoSided, Less, Greater}
	rows := 0
	for _, f := range readLines(t, "efficiency_ref.tsv") {
		a, _ := strconv.Atoi(f[1])
		var m [4]Moments
		for k := range m {
			if err := m[k].AddSlice(nums(t, f[4+k])); err != nil {
				t.Fatal(err)
			}
		}
		r, err := EfficiencyTest(&m[0], &m[1], &m[2], &m[3], num(t, f[2]), alts[a], num(t, f[3]))
		if err != nil {
			t.Fatalf("%s: %v", f[0], err)
		}
		if r.Test != TestEfficiency || r.Eff == nil || r.StdError == nil {
			t.Fatalf("%s: %+v", f[0], r)
		}
		lp, err := r.LogPValue()
		if err != nil {
			t.Fatal(err)
		}
		for _, c := range []struct {
			name      string
			got, want float64
		}{{"statistic", r.Statistic, num(t, f[8])}, {"df", r.DF[0], num(t, f[9])},
			{"log p", lp, num(t, f[11])}, {"time ratio", r.Eff.TimeRatio, num(t, f[16])},
			{"std error", *r.StdError, num(t, f[17])}} {
			if !near(c.got, c.want, abs(c.want), 1e-12) {
				t.Errorf("%s %s: %v, want %v", f[0], c.name, c.got, c.want)
			}
		}
		if r.Eff.BatchesX != len(nums(t, f[6])) {
			t.Errorf("%s: batches %d", f[0], r.Eff.BatchesX)
		}
		rows++
	}
	if rows < 6 {
		t.Fatalf("%d rows", rows)
	}
}

func TestEfficiencyErrors(t *testing.T) {
	var x, tm, one, c Moments
	x.AddSlice([]float64{1, 2, 4})
	tm.AddSlice([]float64{1, 1.1})
	one.AddSlice([]float64{1})
	c.AddSlice([]float64{3, 3})
	if _, err := EfficiencyTest(&x, &x, &tm, &one, 1, TwoSided, 0.05); !errors.Is(err, ErrTooFew) {
		t.Errorf("one batch: %v", err)
	}
	if _, err := EfficiencyTest(&x, &x, &tm, &tm, -1, TwoSided, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("ratio -1: %v", err)
	}
	if _, err := EfficiencyTest(&c, &x, &tm, &tm, 1, TwoSided, 0.05); !errors.Is(err, ErrDegenerate) {
		t.Errorf("constant x: %v", err)
	}
}

func abs(v float64) float64 {
	if v < 0 {
		return -v
	}
	return v
}
