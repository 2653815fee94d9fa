package mcstat

// The Go API against the C tests' reference numbers (tests/data/ffi_ref.txt,
// written by tools/refgen/make_ffi_ref.py from 50-digit mpmath values,
// exact K-S fractions and R's printed blocks).

import (
	"bufio"
	"encoding/hex"
	"errors"
	"math"
	"os"
	"regexp"
	"strconv"
	"strings"
	"testing"
)

type ref struct {
	lines [][]string
	data  map[string][]float64
}

func bits(t string) float64 {
	u, err := strconv.ParseUint(t, 16, 64)
	if err != nil {
		panic(err)
	}
	return math.Float64frombits(u)
}

func text(t string) string {
	b, err := hex.DecodeString(t)
	if err != nil {
		panic(err)
	}
	return string(b)
}

func floats(ts []string) []float64 {
	v := make([]float64, len(ts))
	for i, t := range ts {
		v[i] = bits(t)
	}
	return v
}

func relErr(got, want float64) float64 {
	switch {
	case got == want || (math.IsNaN(got) && math.IsNaN(want)):
		return 0
	case math.IsNaN(got) || math.IsNaN(want) || math.IsInf(got, 0) || math.IsInf(want, 0):
		return math.Inf(1)
	case want == 0:
		return math.Abs(got)
	}
	return math.Abs((got - want) / want)
}

// at is v[i], or NaN when v has no entry i (a field that does not apply).
func at(v []float64, i int) float64 {
	if i < len(v) {
		return v[i]
	}
	return math.NaN()
}

func stripDecision(s string) string {
	var out []string
	for _, l := range strings.Split(s, "\n") {
		if !strings.HasPrefix(l, "decision at alpha = ") {
			out = append(out, l)
		}
	}
	return strings.Join(out, "\n")
}

func loadRef(t *testing.T) *ref {
	f, err := os.Open("../../tests/data/ffi_ref.txt")
	if err != nil {
		t.Fatal(err)
	}
	defer f.Close()
	r := &ref{data: map[string][]float64{}}
	sc := bufio.NewScanner(f)
	sc.Buffer(make([]byte, 1<<20), 1<<24)
	for sc.Scan() {
		line := sc.Text()
		if strings.HasPrefix(line, "#") {
			continue
		}
		tok := strings.Split(line, " ")
		r.lines = append(r.lines, tok)
		switch tok[0] {
		case "data":
			n, _ := strconv.Atoi(tok[2])
			r.data[tok[1]] = floats(tok[5 : 5+n])
		case "formula":
			n, _ := strconv.ParseUint(tok[2], 10, 64)
			base := bits(tok[3])
			mult, _ := strconv.ParseUint(tok[4], 10, 64)
			mod, _ := strconv.ParseUint(tok[5], 10, 64)
			v := make([]float64, n)
			for i := uint64(0); i < n; i++ {
				v[i] = base + float64((i*mult)%mod)*math.Ldexp(1, -20)
			}
			r.data[tok[1]] = v
		}
	}
	if err := sc.Err(); err != nil {
		t.Fatal(err)
	}
	return r
}

func (r *ref) records(kind string) [][]string {
	var out [][]string
	for _, l := range r.lines {
		if l[0] == kind {
			out = append(out, l)
		}
	}
	return out
}

func alt(code string) Alternative {
	a, err := strconv.Atoi(code)
	if err == nil {
		return Alternative(a)
	}
	p, err := ParseAlternative(code)
	if err != nil {
		panic(err)
	}
	return p
}

func TestFourTestsOnSlicesAndAccumulators(t *testing.T) {
	r := loadRef(t)
	cases := r.records("case")
	if len(cases) != 38 {
		t.Fatalf("%d cases", len(cases))
	}
	for _, c := range cases {
		kind, x, y := c[1], r.data[c[2]], r.data[c[3]]
		null, a, want := bits(c[4]), alt(c[5]), floats(c[6:])
		alpha := want[0]
		var res *Result
		var err error
		switch kind {
		case "T_1":
			res, err = TTest1(x, null, a, alpha)
		case "T_2":
			res, err = TTest2(x, y, null, a, alpha)
		case "VAR_1":
			res, err = VarTest1(x, null, a, alpha)
		default:
			res, err = VarTest2(x, y, null, a, alpha)
		}
		if err != nil {
			t.Fatalf("%s %s: %v", kind, c[2], err)
		}
		// accumulators: a third one value at a time, the rest at once, merged
		mx, rest := NewMoments(), NewMoments()
		cut := len(x) / 3
		for _, v := range x[:cut] {
			if err := mx.Add(v); err != nil {
				t.Fatal(err)
			}
		}
		if err := rest.AddSlice(x[cut:]); err != nil {
			t.Fatal(err)
		}
		if err := mx.Merge(rest); err != nil {
			t.Fatal(err)
		}
		my := NewMoments()
		if y != nil {
			if err := my.AddSlice(y); err != nil {
				t.Fatal(err)
			}
		}
		var resM *Result
		switch kind {
		case "T_1":
			resM, err = TTest1Moments(mx, null, a, alpha)
		case "T_2":
			resM, err = TTest2Moments(mx, my, null, a, alpha)
		case "VAR_1":
			resM, err = VarTest1Moments(mx, null, a, alpha)
		default:
			resM, err = VarTest2Moments(mx, my, null, a, alpha)
		}
		if err != nil {
			t.Fatalf("%s %s (moments): %v", kind, c[2], err)
		}
		for _, got := range []*Result{res, resM} {
			// the references hold NaN where a field does not apply; the Result leaves it out
			fields := []float64{got.Statistic, at(got.DF, 0), at(got.DF, 1), got.PValue, at(got.Critical, 0),
				at(got.Critical, 1), at(got.ConfInt, 0), at(got.ConfInt, 1), at(got.Estimate, 0), at(got.Estimate, 1)}
			for k, g := range fields {
				if e := relErr(g, want[k+1]); e > 1e-9 {
					t.Errorf("%s %s %s field %d: %g vs %g (rel err %.2g)", kind, c[2], c[3], k, g, want[k+1], e)
				}
			}
			if got.Reject != (want[4] <= alpha) || (got.Decision == DecisionEqual) == got.Reject {
				t.Errorf("%s %s: reject %v decision %v", kind, c[2], got.Reject, got.Decision)
			}
		}
	}
}

func TestMomentsAgainst50DigitReferences(t *testing.T) {
	r := loadRef(t)
	n := 0
	for _, c := range append(r.records("data"), r.records("formula")...) {
		mean, vr := bits(c[3]), bits(c[4])
		if c[0] == "formula" {
			mean, vr = bits(c[6]), bits(c[7])
		}
		m := NewMoments()
		if err := m.AddSlice(r.data[c[1]]); err != nil {
			t.Fatal(err)
		}
		if relErr(m.Mean(), mean) > 1e-15 || relErr(m.Var(), vr) > 1e-13 {
			t.Errorf("%s: mean %g vs %g, var %g vs %g", c[1], m.Mean(), mean, m.Var(), vr)
		}
		n++
	}
	if n != 26 {
		t.Fatalf("%d data sets", n)
	}
}

func TestMomentsMergeBinaryAndErrors(t *testing.T) {
	r := loadRef(t)
	x := r.data["lew"]
	a, b, all := NewMoments(), NewMoments(), NewMoments()
	_ = a.AddSlice(x[:77])
	_ = b.AddSlice(x[77:])
	_ = all.AddSlice(x)
	if err := a.Merge(b); err != nil {
		t.Fatal(err)
	}
	if a.N() != 200 || relErr(a.Mean(), all.Mean()) > 1e-15 || relErr(a.Var(), all.Var()) > 1e-14 {
		t.Errorf("merge: n %d mean %g var %g", a.N(), a.Mean(), a.Var())
	}
	blob, err := a.MarshalBinary()
	if err != nil || len(blob) != 96 {
		t.Fatalf("MarshalBinary: %v %d", err, len(blob))
	}
	back := NewMoments()
	if err := back.UnmarshalBinary(blob); err != nil || back.Mean() != a.Mean() || back.N() != 200 {
		t.Errorf("UnmarshalBinary: %v", err)
	}
	blob[40] ^= 0x10
	if err := back.UnmarshalBinary(blob); !errors.Is(err, ErrCorrupt) {
		t.Errorf("corrupt bytes: %v", err)
	}
	if err := a.Add(math.NaN()); !errors.Is(err, ErrNonFinite) || a.N() != 200 {
		t.Errorf("NaN: %v", err)
	}
	_, err = TTest1([]float64{2, 2, 2}, 1, TwoSided, 0.05)
	var e *Error
	if !errors.Is(err, ErrDegenerate) || !errors.As(err, &e) || e.Status != 4 || e.Message == "" {
		t.Errorf("constant data: %v", err)
	}
	if !strings.Contains(err.Error(), "status 4") {
		t.Errorf("error text %q", err.Error())
	}
	if _, err = TTest1([]float64{1}, 0, TwoSided, 0.05); !errors.Is(err, ErrTooFew) {
		t.Errorf("one value: %v", err)
	}
	if _, err = TTest1([]float64{1, 2}, 0, TwoSided, 1.5); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("alpha 1.5: %v", err)
	}
	if _, err = TTest1(nil, 0, TwoSided, 0.05); err == nil {
		t.Error("empty slice accepted")
	}
	if _, err := ParseAlternative("sideways"); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("ParseAlternative: %v", err)
	}
	if Version() != headerVersion(t) || TwoSided.String() != "two-sided" || DecisionGreater.String() != "greater" {
		t.Errorf("names: %s %s %s", Version(), TwoSided, DecisionGreater)
	}
}

// headerVersion is MAJOR.MINOR.PATCH of the repository's mcstat/version.h, the one
// source of the version.
func headerVersion(t *testing.T) string {
	text, err := os.ReadFile("../../libmcstat/include/mcstat/version.h")
	if err != nil {
		t.Fatal(err)
	}
	var parts []string
	for _, name := range []string{"MAJOR", "MINOR", "PATCH"} {
		m := regexp.MustCompile(`(?m)^#define MCSTAT_VERSION_` + name + ` +([0-9]+)$`).FindSubmatch(text)
		if m == nil {
			t.Fatalf("MCSTAT_VERSION_%s not in mcstat/version.h", name)
		}
		parts = append(parts, string(m[1]))
	}
	return strings.Join(parts, ".")
}

func TestVersionIsTheHeaderVersion(t *testing.T) {
	if v := headerVersion(t); Version() != v {
		t.Errorf("linked libmcstat %s, mcstat.h %s", Version(), v)
	}
}

func TestDefaultKSOptionsStartNoThread(t *testing.T) {
	if o := DefaultKSOptions(); o.Threads != 1 || o.NSim != 10000 || !o.Critical {
		t.Errorf("defaults %+v", o)
	}
}

func TestDistributions(t *testing.T) {
	r := loadRef(t)
	n := 0
	for _, c := range r.records("quantile") {
		p, d1, d2, upper, want := bits(c[2]), bits(c[3]), bits(c[4]), c[5] == "1", bits(c[6])
		var got float64
		var err error
		switch c[1] {
		case "t":
			got, err = TQuantile(p, d1, upper)
		case "c":
			got, err = ChisqQuantile(p, d1, upper)
		default:
			got, err = FQuantile(p, d1, d2, upper)
		}
		if err != nil || relErr(got, want) > 1e-12 {
			t.Errorf("%s quantile p=%g df=%g: %g vs %g (%v)", c[1], p, d1, got, want, err)
		}
		n++
	}
	for _, c := range r.records("logcdf") {
		x, d1, d2, upper, want := bits(c[2]), bits(c[3]), bits(c[4]), c[5] == "1", bits(c[6])
		var lp, p float64
		var err error
		switch c[1] {
		case "t":
			lp, err = TLogCDF(x, d1, upper)
			p, _ = TCDF(x, d1, upper)
		case "c":
			lp, err = ChisqLogCDF(x, d1, upper)
			p, _ = ChisqCDF(x, d1, upper)
		default:
			lp, err = FLogCDF(x, d1, d2, upper)
			p, _ = FCDF(x, d1, d2, upper)
		}
		e := math.Abs(lp - want)
		if math.Abs(want) > 700 {
			e /= math.Abs(want)
		}
		if err != nil || e > 1e-11 || (want > -700 && relErr(p, math.Exp(want)) > 1e-11) {
			t.Errorf("%s logcdf x=%g df=%g: %g vs %g (%v)", c[1], x, d1, lp, want, err)
		}
		n++
	}
	if n < 400 {
		t.Fatalf("%d distribution values", n)
	}
	if _, err := TCDF(math.NaN(), 3, false); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("NaN: %v", err)
	}
}

func ksCase(c []string) (Alternative, float64, float64, float64, []float64, []float64) {
	nx, _ := strconv.Atoi(c[6])
	return alt(c[2]), bits(c[3]), bits(c[4]), bits(c[5]), floats(c[7 : 7+nx]), floats(c[8+nx:])
}

func TestKSExactAgainstExactFractionsAndR(t *testing.T) {
	r := loadRef(t)
	blocks := map[string]string{}
	for _, c := range r.records("ksblock") {
		blocks[c[1]] = text(c[2])
	}
	nBlocks := 0
	for _, c := range r.records("ks") {
		a, stat, pNone, pCanner, x, y := ksCase(c)
		o := DefaultKSOptions()
		o.Weight, o.Method = KSWeightNone, MethodExact
		res, err := KSTest2(x, y, a, 0.05, &o)
		if err != nil {
			t.Fatalf("ks %s: %v", c[1], err)
		}
		if res.Test != TestKS2 || res.Method != MethodExact || math.Abs(res.Statistic-stat) > 1e-13*math.Max(math.Abs(stat), 1) {
			t.Errorf("ks %s: statistic %g vs %g", c[1], res.Statistic, stat)
		}
		if relErr(res.PValue, pNone) > 1e-12 {
			t.Errorf("ks %s: p %g vs %g", c[1], res.PValue, pNone)
		}
		o.Weight = KSWeightCanner
		rc, err := KSTest2(x, y, a, 0.05, &o)
		if err != nil || relErr(rc.PValue, pCanner) > 1e-12 {
			t.Errorf("ks %s Canner: p %v vs %g (%v)", c[1], rc, pCanner, err)
		}
		if b, ok := blocks[c[1]]; ok {
			if got := stripDecision(res.String()); got != b {
				t.Errorf("ks %s block:\n%s---\n%s", c[1], got, b)
			}
			nBlocks++
		}
	}
	if nBlocks != 56 {
		t.Fatalf("%d K-S blocks", nBlocks)
	}
}

func TestKSSimulatedWithCache(t *testing.T) {
	r := loadRef(t)
	_, _, _, pCanner, x, y := ksCase(r.records("ks")[11])
	cache, err := NewKSCache(16 << 20)
	if err != nil {
		t.Fatal(err)
	}
	defer cache.Close()
	o := DefaultKSOptions()
	o.Method, o.NSim, o.Seed, o.Cache = MethodSimulate, 4000, 7, cache
	a, err1 := KSTest2(x, y, TwoSided, 0.05, &o)
	b, err2 := KSTest2(x, y, TwoSided, 0.05, &o)
	if err1 != nil || err2 != nil {
		t.Fatal(err1, err2)
	}
	if a.Method != MethodSimulate || a.PValueSE <= 0 || math.Abs(a.PValue-pCanner) > 5*a.PValueSE+1e-3 || a.PValue != b.PValue {
		t.Errorf("simulated: p %g +- %g (exact %g), again %g", a.PValue, a.PValueSE, pCanner, b.PValue)
	}
	if a.KS == nil || a.KS.NSim != 4000 || !(a.KS.CriticalSE >= 0) || a.KS.Weight != KSWeightCanner {
		t.Errorf("simulated K-S details %+v", a.KS)
	}
	if h, m, e := cache.Stats(); h < 1 || m < 1 || e < 1 {
		t.Errorf("cache stats %d %d %d", h, m, e)
	}
	o = DefaultKSOptions()
	o.Method = MethodAsymptotic // Canner's statistic has no limit law
	if _, err := KSTest2(x, y, TwoSided, 0.05, &o); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("asymptotic Canner: %v", err)
	}
	if _, err := KSTest2(x, y, TwoSided, 0.05, nil); err != nil {
		t.Errorf("default options: %v", err)
	}
}

func TestStringIsRBlock(t *testing.T) {
	r := loadRef(t)
	n := 0
	for _, c := range r.records("block") {
		nx, _ := strconv.Atoi(c[8])
		x := floats(c[9 : 9+nx])
		rest := c[9+nx:]
		var y []float64
		if rest[0] != "-" {
			y = floats(rest[1:])
		}
		null, a, alpha := bits(c[4]), alt(c[5]), bits(c[6])
		var res *Result
		var err error
		switch {
		case c[1] == "t_test" && y == nil:
			res, err = TTest1(x, null, a, alpha)
		case c[1] == "t_test":
			res, err = TTest2(x, y, null, a, alpha)
		default:
			res, err = VarTest2(x, y, null, a, alpha)
		}
		if err != nil {
			t.Fatal(err)
		}
		yname := c[3]
		if yname == "-" {
			yname = "y"
		}
		got := res.Format(c[2], yname)
		if stripDecision(got) != text(c[7]) {
			t.Errorf("block %s %s %s:\n%s---\n%s", c[1], c[2], c[5], got, text(c[7]))
		}
		if !strings.HasSuffix(got, ": "+res.Decision.String()+"\n\n") {
			t.Errorf("decision line: %q", got)
		}
		n++
	}
	if n != 19 {
		t.Fatalf("%d blocks", n)
	}
}
