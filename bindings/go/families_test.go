package mcstat

// The families beyond the four tests, against the C tests' reference files
// (tests/data: R's binom.test, TOST by t.test, p.adjust, power.t.test and
// chisq.test values, written by tools/refgen) and closed forms; and bad
// input, which must give errors, never panics.

import (
	"bufio"
	"encoding/json"
	"errors"
	"math"
	"os"
	"strconv"
	"strings"
	"testing"
)

func readLines(t *testing.T, name string) [][]string {
	t.Helper()
	f, err := os.Open("../../tests/data/" + name)
	if err != nil {
		t.Fatal(err)
	}
	defer f.Close()
	sep := "\t"
	if strings.HasSuffix(name, ".csv") {
		sep = ","
	} else if strings.HasSuffix(name, ".txt") {
		sep = " "
	}
	var out [][]string
	sc := bufio.NewScanner(f)
	sc.Buffer(make([]byte, 1<<20), 1<<24)
	for sc.Scan() {
		if l := sc.Text(); l != "" && !strings.HasPrefix(l, "#") {
			out = append(out, strings.Split(l, sep))
		}
	}
	if err := sc.Err(); err != nil {
		t.Fatal(err)
	}
	return out
}

// num parses a decimal or hexadecimal float; "NA" and "NaN" are NaN.
func num(t *testing.T, s string) float64 {
	t.Helper()
	if s == "NA" || s == "NaN" {
		return math.NaN()
	}
	v, err := strconv.ParseFloat(s, 64)
	if err != nil {
		t.Fatalf("number %q: %v", s, err)
	}
	return v
}

func nums(t *testing.T, s string) []float64 {
	var v []float64
	for _, f := range strings.Split(s, ",") {
		v = append(v, num(t, f))
	}
	return v
}

// ---- Result: fields that do not apply are absent --------------------------------

func TestResultHasNoPlaceholders(t *testing.T) {
	x := []float64{1.1, 2.3, 1.9, 3.2, 2.8, 2.2}
	y := []float64{0.4, 1.7, 2.1, 0.9, 1.3}
	w, err := TTest2(x, y, 0, TwoSided, 0.05)
	if err != nil {
		t.Fatal(err)
	}
	if len(w.DF) != 1 || len(w.N) != 2 || len(w.Estimate) != 2 || len(w.ConfInt) != 2 || w.StdError == nil ||
		w.NullValue == nil || *w.NullValue != 0 || w.KS != nil || w.TOST != nil {
		t.Errorf("Welch: %+v", w)
	}
	one, _ := TTest1(x, 2, Greater, 0.05)
	if len(one.N) != 1 || len(one.Estimate) != 1 || len(one.DF) != 1 || !math.IsInf(one.ConfInt[1], 1) ||
		!math.IsInf(one.Critical[0], -1) {
		t.Errorf("one-sample, one-sided: %+v", one)
	}
	f, _ := VarTest2(x, y, 1, TwoSided, 0.05)
	if len(f.DF) != 2 || f.DF[0] != 5 || f.DF[1] != 4 || f.StdError != nil {
		t.Errorf("F: DF %v StdError %v", f.DF, f.StdError)
	}
	k, err := KSTest2(x, y, TwoSided, 0.05, nil)
	if err != nil {
		t.Fatal(err)
	}
	if k.DF != nil || k.Estimate != nil || k.ConfInt != nil || k.NullValue != nil || k.StdError != nil ||
		k.KS == nil || k.KS.Weight != KSWeightCanner || len(k.Critical) != 2 {
		t.Errorf("K-S: %+v %+v", k, k.KS)
	}
	o := DefaultKSOptions()
	o.Critical = false
	if k, _ = KSTest2(x, y, TwoSided, 0.05, &o); k.Critical != nil {
		t.Errorf("K-S without critical value: %v", k.Critical)
	}
	for _, tt := range []Test{TestT1, TestKS2, TestChisqGOF} {
		if strings.HasPrefix(tt.String(), "Test(") {
			t.Errorf("%d has no name", int(tt))
		}
	}
}

// ---- equivalence ------------------------------------------------------------------

func TestEquivalenceAgainstR(t *testing.T) {
	rows := readLines(t, "equivalence_ref.tsv")
	for _, r := range rows {
		x := nums(t, r[0])
		var y []float64
		if r[1] != "-" {
			y = nums(t, r[1])
		}
		mu0, lower, upper, alpha := num(t, r[2]), num(t, r[3]), num(t, r[4]), num(t, r[5])
		var res, resM *Result
		var err, errM error
		mx := NewMoments()
		_ = mx.AddSlice(x)
		if y == nil {
			res, err = EquivalenceTest1(x, mu0, lower, upper, alpha)
			resM, errM = EquivalenceTest1Moments(mx, mu0, lower, upper, alpha)
		} else {
			my := NewMoments()
			_ = my.AddSlice(y)
			res, err = EquivalenceTest2(x, y, lower, upper, alpha)
			resM, errM = EquivalenceTest2Moments(mx, my, lower, upper, alpha)
		}
		if err != nil || errM != nil {
			t.Fatalf("%v: %v %v", r[2:6], err, errM)
		}
		want := []float64{num(t, r[6]), num(t, r[7]), num(t, r[8]), num(t, r[9]), num(t, r[10]), num(t, r[11]),
			num(t, r[12])}
		for _, g := range []*Result{res, resM} {
			// R forms mean(x) - mu in double: at a large offset its t carries an
			// error of ~eps |mean| / se, which mcstat's double-double mean does
			// not; the tolerances grow with that condition number (as in
			// tests/c/test_equivalence.c)
			cond := 1 + math.Abs(g.Estimate[0])/(*g.StdError*math.Min(math.Abs(want[0]), math.Abs(want[2])))
			ttol := 1e-11 + 8*2.2e-16*cond
			ptol := 1e-9 + 30*ttol
			got := []float64{g.TOST.TLower, g.TOST.PLower, g.TOST.TUpper, g.TOST.PUpper, g.DF[0]}
			for i, tol := range []float64{ttol, ptol, ttol, ptol, 1e-12} {
				if e := relErr(got[i], want[i]); e > tol {
					t.Errorf("%v field %d: %.17g vs R %.17g", r[2:6], i, got[i], want[i])
				}
			}
			ctol := 1e-10*(want[6]-want[5]) + 4*2.2e-16*math.Abs(g.Estimate[0])
			if math.Abs(g.ConfInt[0]-want[5]) > ctol || math.Abs(g.ConfInt[1]-want[6]) > ctol {
				t.Errorf("%v: interval %v, R [%.17g, %.17g]", r[2:6], g.ConfInt, want[5], want[6])
			}
			equivalent := math.Max(want[1], want[3]) <= alpha
			if g.Reject != equivalent || g.PValue != math.Max(g.TOST.PLower, g.TOST.PUpper) ||
				g.TOST.Lower != mu0+lower || g.TOST.Upper != mu0+upper {
				t.Errorf("%v: reject %v p %g (%+v)", r[2:6], g.Reject, g.PValue, g.TOST)
			}
			if want := []string{"equivalent", "not equivalent"}[b2int(!equivalent)]; !strings.Contains(g.String(), want) {
				t.Errorf("block lacks %q:\n%s", want, g)
			}
		}
	}
	if len(rows) < 20 {
		t.Fatalf("%d equivalence rows", len(rows))
	}
	if _, err := EquivalenceTest1([]float64{1, 2, 3}, 0, 1, -1, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("lower > upper: %v", err)
	}
	if _, err := EquivalenceTest1([]float64{1, 2, 3}, 0, -1, 1, 0.6); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("alpha 0.6: %v", err)
	}
}

func b2int(b bool) int {
	if b {
		return 1
	}
	return 0
}

// ---- binomial and battery -----------------------------------------------------------

func TestBinomAgainstR(t *testing.T) {
	rows := readLines(t, "binom_ref.csv")[1:]
	for _, r := range rows {
		x, _ := strconv.ParseUint(r[0], 10, 64)
		n, _ := strconv.ParseUint(r[1], 10, 64)
		p, alpha := num(t, r[2]), num(t, r[4])
		a, err := ParseAlternative(r[3])
		if err != nil {
			t.Fatal(err)
		}
		res, err := BinomTest(x, n, p, a, alpha)
		if err != nil {
			t.Fatalf("%v: %v", r, err)
		}
		pv, lp, lo, hi := num(t, r[5]), num(t, r[6]), num(t, r[7]), num(t, r[8])
		// R's p-value is denormal below 1e-300, and its two-sided log p the
		// log of that sum (as tests/c/test_binom.c)
		pOK := relErr(res.PValue, pv) <= 1e-10
		if pv <= 1e-300 {
			pOK = res.PValue < 1e-290
		}
		logOK := true
		if !math.IsInf(lp, 0) && lp < -1e-3 && (a != TwoSided || pv > 1e-300) {
			logOK = relErr(res.Binom.LogPValue, lp) <= 1e-10
		}
		if !pOK || !logOK || relErr(res.ConfInt[0], lo) > 1e-9 || relErr(res.ConfInt[1], hi) > 1e-9 {
			t.Errorf("%v: p %.17g log %.17g ci %v", r[:5], res.PValue, res.Binom.LogPValue, res.ConfInt)
		}
		if res.Test != TestBinom || res.Statistic != float64(x) || res.DF != nil || res.StdError != nil ||
			*res.NullValue != p || res.N[0] != n || res.Reject != (res.PValue <= alpha) {
			t.Errorf("%v: %+v", r[:5], res)
		}
		// the battery meta-test is the binomial test of the count against the level
		if p > 0 && p < 1 {
			b, err := BatteryTest(x, n, p, a, alpha)
			if err != nil || b.PValue != res.PValue {
				t.Errorf("battery %v: %v %v", r[:5], b, err)
			}
		}
	}
	if len(rows) < 100 {
		t.Fatalf("%d binomial rows", len(rows))
	}
	// from p-values: a test rejects when p <= level
	pv := []float64{0.01, 0.2, 0.04, 0.5, 0.05, 0.9, 0.3, 0.07}
	b, err := BatteryTestPValues(pv, 0.05, Greater, 0.05)
	c, _ := BatteryTest(3, 8, 0.05, Greater, 0.05)
	if err != nil || b.PValue != c.PValue || b.Statistic != 3 {
		t.Errorf("battery from p-values: %v %v", b, err)
	}
	if _, err := BatteryTestPValues([]float64{0.1, math.NaN()}, 0.05, Greater, 0.05); !errors.Is(err, ErrNonFinite) {
		t.Errorf("NaN p-value: %v", err)
	}
	if _, err := BatteryTestPValues(nil, 0.05, Greater, 0.05); !errors.Is(err, ErrTooFew) {
		t.Errorf("no p-values: %v", err)
	}
	if _, err := BinomTest(5, 3, 0.5, TwoSided, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("x > n: %v", err)
	}
	if _, err := BinomTest(0, 0, 0.5, TwoSided, 0.05); !errors.Is(err, ErrTooFew) {
		t.Errorf("n = 0: %v", err)
	}
	if _, err := BatteryTest(1, 10, 1.5, TwoSided, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("level 1.5: %v", err)
	}
}

// ---- chi-squared goodness of fit --------------------------------------------------

func TestGOFAgainstR(t *testing.T) {
	raw, err := os.ReadFile("../../tests/data/chisq_ref.json")
	if err != nil {
		t.Fatal(err)
	}
	var cases []struct {
		Name        string
		X, P        []float64
		Pool        int
		MinExpected float64 `json:"min_expected"`
		NEstimated  int     `json:"n_estimated"`
		Counts      int
		Statistic   float64
		DF          float64
		PValue      float64
		Cells       int
	}
	if err := json.Unmarshal(raw, &cases); err != nil {
		t.Fatal(err)
	}
	for _, c := range cases {
		o := DefaultGOFOptions()
		o.Pool, o.MinExpected, o.NEstimated = c.Pool != 0, c.MinExpected, c.NEstimated
		if c.Counts != 0 {
			o.Expected = GOFCounts
		}
		res, err := GOFChisqTest(c.X, c.P, &o, 0.05)
		if err != nil {
			t.Errorf("%s: %v", c.Name, err)
			continue
		}
		if math.Abs(res.Statistic-c.Statistic) > 1e-12*math.Max(1, c.Statistic) || res.DF[0] != c.DF ||
			relErr(res.PValue, c.PValue) > 1e-11 || res.GOF.Cells != c.Cells || res.GOF.CellsGiven != len(c.X) {
			t.Errorf("%s: X2 %.17g df %v p %.17g cells %d; R %.17g %g %.17g %d", c.Name, res.Statistic, res.DF,
				res.PValue, res.GOF.Cells, c.Statistic, c.DF, c.PValue, c.Cells)
		}
		if res.Test != TestChisqGOF || res.ConfInt != nil || res.Estimate != nil || res.NullValue != nil {
			t.Errorf("%s: fields %+v", c.Name, res)
		}
	}
	if len(cases) < 10 {
		t.Fatalf("%d GOF cases", len(cases))
	}
	if d := DefaultGOFOptions(); !d.Pool || d.MinExpected != GOFDefaultMinExpected() || GOFDefaultMinExpected() != 5 {
		t.Errorf("defaults %+v", d)
	}
	res, err := GOFChisqTest([]float64{30, 20, 50}, []float64{0.3, 0.2, 0.5}, nil, 0.05)
	if err != nil || res.Statistic != 0 || res.GOF.PoolBelow != 5 {
		t.Errorf("exact fit: %v %v", res, err)
	}
	if _, err := GOFChisqTest([]float64{1, 2}, []float64{0.5}, nil, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("lengths differ: %v", err)
	}
	if _, err := GOFChisqTest([]float64{10, 20}, []float64{0.5, 0.6}, nil, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("probabilities summing to 1.1: %v", err)
	}
	if _, err := GOFChisqTest(nil, nil, nil, 0.05); err == nil {
		t.Error("no cells accepted")
	}
}

// ---- p.adjust ---------------------------------------------------------------------

func TestPAdjustAgainstR(t *testing.T) {
	rows := readLines(t, "p_adjust_ref.txt")
	cases := 0
	for i := 0; i < len(rows); i++ {
		if rows[i][0] != "case" {
			continue
		}
		m, err := ParsePAdjustMethod(rows[i][2])
		if err != nil || m.String() != rows[i][2] {
			t.Fatalf("method %q: %v %v", rows[i][2], m, err)
		}
		var p, want []float64
		for _, s := range rows[i+1][1:] {
			p = append(p, num(t, s))
		}
		for _, s := range rows[i+2][1:] {
			want = append(want, num(t, s))
		}
		got, err := PAdjust(p, m)
		if err != nil || len(got) != len(want) {
			t.Fatalf("%v: %v", rows[i], err)
		}
		for k := range want {
			if relErr(got[k], want[k]) > 1e-13 {
				t.Errorf("%v [%d]: %.17g vs R %.17g", rows[i], k, got[k], want[k])
			}
		}
		cases++
	}
	if cases != 72 {
		t.Fatalf("%d p.adjust cases", cases)
	}
	for _, alias := range []string{"fdr", "bh"} {
		if m, err := ParsePAdjustMethod(alias); err != nil || m != PAdjustBH {
			t.Errorf("%s: %v %v", alias, m, err)
		}
	}
	if _, err := ParsePAdjustMethod("sidak"); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("sidak: %v", err)
	}
	if _, err := PAdjust([]float64{0.1, 1.2}, PAdjustHolm); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("p 1.2: %v", err)
	}
	if _, err := PAdjust([]float64{0.1}, PAdjustMethod(42)); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("method 42: %v", err)
	}
	if out, err := PAdjust(nil, PAdjustHommel); err != nil || len(out) != 0 {
		t.Errorf("empty: %v %v", out, err)
	}
}

// ---- power ------------------------------------------------------------------------

func TestPowerAgainstR(t *testing.T) {
	tests := map[string]PowerTest{"t_1": PowerT1, "t_2": PowerT2, "welch": PowerWelch, "var_1": PowerVar1,
		"var_2": PowerVar2}
	counts := map[string]int{}
	for _, r := range readLines(t, "power_ref.tsv") {
		o := DefaultPowerOptions()
		o.Test = tests[r[1]]
		a, err := ParseAlternative(r[2])
		if err != nil {
			t.Fatal(err)
		}
		o.Alternative, o.Strict = a, r[3] == "1"
		o.N, o.NRatio, o.SDRatio = num(t, r[4]), num(t, r[5]), num(t, r[6])
		o.Effect, o.Alpha, o.Power = num(t, r[7]), num(t, r[8]), num(t, r[9])
		counts[r[0]]++
		switch r[0] {
		case "power":
			p, err := o.Compute()
			if err != nil || math.Abs(p-o.Power) > 1e-10+1e-9*o.Power {
				t.Errorf("%v: power %.15g (%v)", r, p, err)
			}
		case "n":
			want := o.N
			o.N = math.NaN() // the unknown's field is ignored
			s, err := o.Solve(SolveN)
			if err != nil {
				t.Fatalf("%v: %v", r, err)
			}
			// R's n is the continuous root for the t tests; mcstat's the next integer
			up := math.Ceil(want - 1e-7)
			if o.Test >= PowerVar1 {
				up = want
			}
			if (s.N != up && !(math.Abs(want-math.Round(want)) < 1e-6 && s.N == math.Round(want)+1)) || s.Power < o.Power {
				t.Errorf("%v: n %g power %g", r, s.N, s.Power)
			}
		case "effect":
			want := o.Effect
			s, err := o.Solve(SolveEffect)
			if err != nil || relErr(s.Effect, want) > 1e-8 {
				t.Errorf("%v: effect %.15g (%v)", r, s.Effect, err)
			}
		case "alpha":
			want := o.Alpha
			o.Alpha = math.NaN()
			s, err := o.Solve(SolveAlpha)
			if err != nil || math.Abs(s.Alpha-want) > 1e-11+1e-7*want {
				t.Errorf("%v: alpha %.15g (%v)", r, s.Alpha, err)
			}
		}
	}
	if counts["power"] < 1000 || counts["n"] < 100 || counts["effect"] < 30 || counts["alpha"] < 10 {
		t.Fatalf("rows %v", counts)
	}
	// power.t.test(delta = .5, power = .9, type = "one.sample"): n = 43.99552
	o := DefaultPowerOptions()
	o.Effect, o.Power = 0.5, 0.9
	s, err := o.Solve(SolveN)
	if err != nil || s.N != 44 || s.Power < 0.9 {
		t.Fatalf("n: %+v %v", s, err)
	}
	text := s.String()
	for _, want := range []string{"\n     One-sample t test power calculation \n\n", "              n = 44\n",
		"      sig.level = 0.05\n", "    alternative = two.sided\n"} {
		if !strings.Contains(text, want) {
			t.Errorf("block lacks %q:\n%s", want, text)
		}
	}
	if d := DefaultPowerOptions(); d.Test != PowerT1 || !d.Strict || d.Alpha != 0.05 || d.NRatio != 1 || d.SDRatio != 1 {
		t.Errorf("defaults %+v", d)
	}
	bad := o
	bad.N = 1
	if _, err := bad.Compute(); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("n = 1: %v", err)
	}
	bad = o
	bad.Effect = 0
	if _, err := bad.Solve(SolveN); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("no n detects a zero effect: %v", err)
	}
	if _, err := o.Solve(PowerUnknown(7)); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("unknown 7: %v", err)
	}
	if text := (PowerOptions{}).String(); !strings.HasPrefix(text, "<mcstat power: ") {
		t.Errorf("zero options formatted: %q", text)
	}
}

// ---- diagnostics ------------------------------------------------------------------

func TestDiagnostics(t *testing.T) {
	// Hill's estimate in closed form: tails i^(-1/a), i = 1..k+1
	for _, a := range []float64{0.7, 1.5, 2.0, 4.0} {
		for _, k := range []int{10, 31, 100} {
			x := []float64{0}
			for i := 0; i <= k; i++ {
				v := math.Pow(float64(i+1), -1/a)
				x = append(x, v, -v)
			}
			for i := 0; i < 20; i++ {
				v := 1e-3 * math.Pow(float64(k+2), -1/a) * float64(i+1) / 21
				x = append(x, v, -v)
			}
			lg, _ := math.Lgamma(float64(k) + 1)
			want := a * float64(k) / (float64(k)*math.Log(float64(k)+1) - lg)
			idx, err := TailIndex(x, k)
			if err != nil || relErr(idx[0], want) > 1e-13 || relErr(idx[1], want) > 1e-13 {
				t.Errorf("a %g k %d: %v vs %g (%v)", a, k, idx, want, err)
			}
		}
	}
	// the Edgeworth rates in closed form: exponential (g = 2, c = 6), k = 1, m = 10
	z := 1.959963984540054
	phi := math.Exp(-0.5*z*z) / math.Sqrt(2*math.Pi)
	A := 2.0 * (2*z*z + 1) / 6 * phi / math.Sqrt(10)
	B := z * (6.0*(z*z-3)/12 - 4.0*(z*z*z*z+2*z*z-3)/18) * phi / 10
	s, err := TSize(2, 6, 1, 10, 0.05)
	if err != nil || relErr(s[0], 0.025+A-B) > 1e-12 || relErr(s[1], math.Max(0, 0.025-A-B)) > 1e-12 {
		t.Errorf("t size %v (%v)", s, err)
	}
	if s, _ = TSize(0, 0, 1, 10, 0.05); s != [2]float64{0.025, 0.025} {
		t.Errorf("normal t size %v", s)
	}
	k1, err1 := BatchSize(1, 1, 20, 0.05, 0.2)
	k2, err2 := BatchSize(4, 1, 20, 0.05, 0.2)
	if err1 != nil || err2 != nil || k2 <= 10*k1 {
		t.Errorf("batch sizes %d %d (%v %v)", k1, k2, err1, err2)
	}
	if k, err := BatchSize(0, 0, 10, 0.05, 0.2); err != nil || k != 1 {
		t.Errorf("normal batch size %d %v", k, err)
	}
	// the whole report on exponential data (deterministic: inverse CDF on a grid)
	x := make([]float64, 20000)
	for i := range x {
		x[i] = -math.Log(1 - (float64(i)+0.5)/float64(len(x)))
	}
	d, err := Diagnose(x, nil)
	if err != nil {
		t.Fatal(err)
	}
	m := NewMoments()
	_ = m.AddSlice(x)
	if d.N != 20000 || d.Skewness != m.Skewness() || d.Kurtosis != m.Kurtosis() || d.HeavyTail || d.K != 1 ||
		d.M != 30 || d.TSize[0] <= d.TSize[1] || d.RecommendedK < 2 || d.Alpha != 0.05 {
		t.Errorf("diagnostics %+v", d)
	}
	o := DefaultDiagOptions()
	o.K = 100
	if d, err = Diagnose(x, &o); err != nil || d.K != 100 || d.M != 200 {
		t.Errorf("k 100: %+v %v", d, err)
	}
	// bad input
	if _, err := Diagnose(x[:7], nil); !errors.Is(err, ErrTooFew) {
		t.Errorf("7 values: %v", err)
	}
	c := make([]float64, 64)
	if _, err := Diagnose(c, nil); !errors.Is(err, ErrDegenerate) {
		t.Errorf("constant: %v", err)
	}
	c[3] = math.Inf(1)
	if _, err := TailIndex(c, 0); !errors.Is(err, ErrNonFinite) {
		t.Errorf("Inf: %v", err)
	}
	o = DefaultDiagOptions()
	o.Tolerance = 1.5
	if _, err := Diagnose(x, &o); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("tolerance 1.5: %v", err)
	}
	if _, err := TailIndex(x, -1); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("tailK -1: %v", err)
	}
	if _, err := TSize(math.NaN(), 0, 1, 10, 0.05); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("NaN skewness: %v", err)
	}
	if _, err := BatchSize(0, 0, 1, 0.05, 0.2); !errors.Is(err, ErrTooFew) {
		t.Errorf("m = 1: %v", err)
	}
}

// ---- sizes, versions, GSL -------------------------------------------------------------

func TestABIAndVersion(t *testing.T) {
	if err := CheckABI(); err != nil {
		t.Error(err)
	}
	v := strings.Split(headerVersion(t), ".")
	maj, _ := strconv.Atoi(v[0])
	min, _ := strconv.Atoi(v[1])
	pat, _ := strconv.Atoi(v[2])
	if VersionNumber() != uint(maj*10000+min*100+pat) {
		t.Errorf("version number %d for %s", VersionNumber(), headerVersion(t))
	}
	// once turned off, GSL's handler is no longer the default
	GSLHandlerOffIfDefault()
	if GSLHandlerOffIfDefault() {
		t.Error("GSL handler: turned off twice")
	}
	GSLHandlerOff()
}

func TestEBH(t *testing.T) {
	// descending 20, 10, 1, 0.5 with m = 4: 4/(k e_(k)) = 0.2, 0.2, 4/3, 2,
	// the minimum from each rank on, capped at 1
	got, err := EBH([]float64{20, 10, 1, 0.5})
	want := []float64{0.2, 0.2, 1, 1}
	if err != nil {
		t.Fatal(err)
	}
	for i := range want {
		if math.Abs(got[i]-want[i]) > 1e-15 {
			t.Errorf("[%d] %v, want %v", i, got[i], want[i])
		}
	}
	// m = 3 (NaN not counted), descending inf, 4, 0: 3/(2*4) = 0.375 for the 4
	got, err = EBH([]float64{math.NaN(), 4, math.Inf(1), 0})
	if err != nil || !math.IsNaN(got[0]) || math.Abs(got[1]-0.375) > 1e-15 || got[2] != 0 || got[3] != 1 {
		t.Errorf("NaN/inf/0: %v %v", got, err)
	}
	if _, err := EBH([]float64{1, -1}); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("negative e-value: %v", err)
	}
	m, err := ParsePAdjustMethod("e-BH")
	if err != nil || m != PAdjustEBH || m.String() != "e-BH" {
		t.Errorf("parse e-BH: %v %v", m, err)
	}
	p := []float64{0.001, 0.02, 0.3, 0}
	e := make([]float64, len(p))
	for i, v := range p {
		e[i] = math.Inf(1)
		if v > 0 {
			e[i] = 0.1 * math.Pow(v, -0.9)
		}
	}
	viaE, err1 := EBH(e)
	adj, err2 := PAdjust(p, PAdjustEBH)
	if err1 != nil || err2 != nil {
		t.Fatal(err1, err2)
	}
	for i := range p {
		if math.Abs(adj[i]-viaE[i]) > 1e-12*math.Abs(viaE[i]) {
			t.Errorf("[%d] PAdjust e-BH %v, EBH on calibrated %v", i, adj[i], viaE[i])
		}
	}
}
