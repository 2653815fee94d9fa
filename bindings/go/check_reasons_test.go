package mcstat

// Every refusal of the renderer checks says why, in libmcstat's words: the
// package converts its arguments and passes C's reason on verbatim
// (mcstat_last_error(), read on the OS thread of the call), so each range
// is written once, in C.  The cases are tests/python/test_check_reasons.py's
// with C's "options."/"model." prefix kept; each compares the whole
// message, so a reason that drifts from the field's name or value fails;
// and the package's source holds none of the ranges.

import (
	"errors"
	"fmt"
	"math"
	"os"
	"regexp"
	"runtime"
	"strings"
	"sync"
	"testing"
)

var reasonWI = [3]float64{0, 0, 1}

// lambert is a Lambertian BSDF sampled by its cosine.
func lambert(domain Domain, nu int) *Model {
	cosine := func(x, out []float64) error {
		for k := range out {
			out[k] = math.Max(x[3*k+2], 0) / math.Pi
		}
		return nil
	}
	return &Model{
		Domain: domain, NUniforms: nu, Weight: WeightOverPDF, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := range weight {
				r, phi := math.Sqrt(u[nu*k]), 2*math.Pi*u[nu*k+1]
				z := math.Sqrt(math.Max(0, 1-u[nu*k]))
				x[3*k], x[3*k+1], x[3*k+2] = r*math.Cos(phi), r*math.Sin(phi), z
				weight[k], pdf[k] = 1, z/math.Pi
			}
			return nil
		},
		PDF:  func(wi, x, out []float64) error { return cosine(x, out) },
		Eval: func(wi, x, out []float64) error { return cosine(x, out) },
	}
}

// wantReason: err is an *Error matching sentinel whose Message is reason,
// the whole of it.
func wantReason(t *testing.T, what string, err error, sentinel *Error, reason string) {
	t.Helper()
	var e *Error
	if !errors.Is(err, sentinel) || !errors.As(err, &e) {
		t.Errorf("%s: %v, want %v", what, err, sentinel)
		return
	}
	if e.Message != reason {
		t.Errorf("%s:\n got %q\nwant %q", what, e.Message, reason)
	}
	if want := fmt.Sprintf("mcstat: %s (status %d)", reason, e.Status); err.Error() != want {
		t.Errorf("%s: Error() %q, want %q", what, err.Error(), want)
	}
}

func withOpt(f func(o *CheckOptions)) *CheckOptions {
	o := DefaultCheckOptions()
	f(&o)
	return &o
}

func TestCheckRefusalIsCsReason(t *testing.T) {
	bsdf := func() *Model { return lambert(DomainHemisphere, 2) }
	for _, c := range []struct {
		name   string
		m      *Model
		wi     [3]float64
		n      int
		alpha  float64
		opt    *CheckOptions
		reason string
	}{
		{"n", bsdf(), reasonWI, 10, 0.01, nil, "n must be at least 1000, got 10"},
		{"alpha", bsdf(), reasonWI, 5000, 1.5, nil, "alpha must be in (0, 1), got 1.5"},
		{"cells", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.Cells = 1 }),
			"options.cells must be 0 (automatic) or 2..1048576, got 1"},
		{"batch", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.Batch = 3 }),
			"options.batch must be in 64..2^32, got 3"},
		{"rtol", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.RTol = 0 }),
			"options.rtol must be in (0, 1), got 0"},
		{"tolerated", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.Tolerated = 1 }),
			"options.tolerated must be in [0, 1), got 1"},
		{"resolution", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.Resolution = 0.5 }),
			"options.resolution must be 0 (derived from the values) or in (0, 0.01), got 0.5"},
		{"n_uniforms", lambert(DomainHemisphere, 9), reasonWI, 5000, 0.01, nil, "model.n_uniforms must be in 1..8, got 9"},
		{"n_pilot", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.NPilot = 10 }),
			"options.n_pilot must be 0 (automatic) or at least 64, got 10"},
		{"n_eval", bsdf(), reasonWI, 5000, 0.01, withOpt(func(o *CheckOptions) { o.NEval = 10 }),
			"options.n_eval must be 0 (n) or at least 1000, got 10"},
		{"domain", lambert(DomainDisk, 2), reasonWI, 5000, 0.01, nil,
			"model.domain of a BSDF must be sphere or hemisphere (directions), got disk"},
		{"wi", bsdf(), [3]float64{}, 5000, 0.01, nil, "wi must be a finite, non-zero direction, got (0, 0, 0)"},
	} {
		_, err := CheckBSDF(c.m, c.wi, c.n, 0, c.alpha, c.opt)
		wantReason(t, c.name, err, ErrInvalidArgument, c.reason)
	}
}

func TestCheckRefusalOtherChecks(t *testing.T) {
	_, err := CheckWarp(diskWarp(false), 10, 1, 0.05, nil)
	wantReason(t, "warp n", err, ErrInvalidArgument, "n must be at least 1000, got 10")
	_, err = CheckMedium(homogeneous(false), -1, 20000, 1, 0.01, nil)
	wantReason(t, "sigma_ref", err, ErrInvalidArgument, "sigma_ref must be finite and > 0, got -1")
	_, err = CheckWorkSize(lambert(DomainHemisphere, 2), 5000, withOpt(func(o *CheckOptions) { o.Cells = 1 }))
	wantReason(t, "CheckWorkSize", err, ErrInvalidArgument, "options.cells must be 0 (automatic) or 2..1048576, got 1")
	// ErrTooBig has a reason too (n past 2^48, which a 64-bit int holds;
	// int64 keeps the constants compiling where int has 32 bits)
	if big := int64(1)<<48 + 1; int64(math.MaxInt) > big {
		n := int(big)
		_, err = CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, n, 0, 0.01, nil)
		wantReason(t, "n too big", err, ErrTooBig, fmt.Sprintf("n must be at most 2^48, got %d", n))
	}
}

// Conversions stay the package's: C would see a wrapped value.
func TestCheckConversions(t *testing.T) {
	_, err := CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, -1, 0, 0.01, nil)
	wantReason(t, "n < 0", err, ErrInvalidArgument, "n must be >= 0 (a size_t), got -1")
	// values int32_t would wrap to valid ones (256 cells, 2 uniforms)
	if wide := int64(1) << 32; int64(math.MaxInt) > wide {
		cells, nu := int(wide+256), int(wide+2)
		_, err = CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, 5000, 0, 0.01,
			withOpt(func(o *CheckOptions) { o.Cells = cells }))
		wantReason(t, "Cells past int32", err, ErrInvalidArgument,
			fmt.Sprintf("CheckOptions.Cells %d does not fit C's int32_t", cells))
		_, err = CheckBSDF(lambert(DomainHemisphere, nu), reasonWI, 5000, 0, 0.01, nil)
		wantReason(t, "NUniforms past int32", err, ErrInvalidArgument,
			fmt.Sprintf("Model.NUniforms %d does not fit C's int32_t", nu))
	}
}

func TestCheckLaterSuccessLeavesNoReason(t *testing.T) {
	_, err := CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, 10, 0, 0.01, nil)
	wantReason(t, "n", err, ErrInvalidArgument, "n must be at least 1000, got 10")
	r, err := CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, 2000, 1, 0.01, nil)
	if err != nil || r.Reject {
		t.Fatalf("after a refusal: %v\n%v", err, r)
	}
	if b, err := CheckWorkSize(lambert(DomainHemisphere, 2), 2000, nil); err != nil || b <= 0 {
		t.Errorf("CheckWorkSize after a refusal: %d, %v", b, err)
	}
}

// Goroutines refusing at once each get their own reason, however the
// scheduler moves them between threads.
func TestCheckReasonPerGoroutine(t *testing.T) {
	var wg sync.WaitGroup
	errs := make(chan string, 64)
	for g := 0; g < 8; g++ {
		wg.Add(1)
		go func(batch uint64) {
			defer wg.Done()
			for i := 0; i < 50; i++ {
				_, err := CheckBSDF(lambert(DomainHemisphere, 2), reasonWI, 5000, 0, 0.01,
					withOpt(func(o *CheckOptions) { o.Batch = batch }))
				want := fmt.Sprintf("options.batch must be in 64..2^32, got %d", batch)
				var e *Error
				if !errors.As(err, &e) || e.Message != want {
					errs <- fmt.Sprintf("batch %d: %v", batch, err)
					return
				}
				runtime.Gosched()
			}
		}(uint64(3 + g))
	}
	wg.Wait()
	close(errs)
	for e := range errs {
		t.Error(e)
	}
}

// stripGoComments drops // comments (the docs may state the ranges).
func stripGoComments(src string) string {
	var b strings.Builder
	for _, line := range strings.Split(src, "\n") {
		if i := strings.Index(line, "//"); i >= 0 {
			line = line[:i]
		}
		b.WriteString(line + "\n")
	}
	return b.String()
}

// The checks' code neither says nor tests the ranges libmcstat checks.
func TestCheckBindingHoldsNoRange(t *testing.T) {
	raw, err := os.ReadFile("check.go")
	if err != nil {
		t.Fatal(err)
	}
	code := stripGoComments(string(raw))
	for _, literal := range []string{"1048576", "1 << 20", "1<<20", "2^32", "<< 32", "<<32", "(0, 0.01)", "at least",
		"must be in (0, 1)", "must be in 1..", "finite and > 0", "non-zero", "MAX_UNIFORMS", "sphere or hemisphere",
		"only CheckBSDF", "CheckMedium's only", "WeightOverPDF ("} {
		if strings.Contains(code, literal) {
			t.Errorf("check.go holds %q", literal)
		}
	}
	// no comparison of a field C checks (opt.RTol <= 0, m.NUniforms > 8, n < 1000, alpha >= 1, ...)
	fields := `(?:NUniforms|Cells|Batch|RTol|Tolerated|Resolution|NPilot|NEval|alpha|sigmaRef|Domain)`
	cmp := regexp.MustCompile(`\b` + fields + `\s*(?:[<>]=?|==|!=)|(?:[<>]=?|==|!=)\s*(?:\w+\.)?` + fields + `\b|\bn\s*<\s*[1-9]`)
	for _, m := range cmp.FindAllString(code, -1) {
		t.Errorf("check.go compares %q", m)
	}
}

// The t and variance tests give C's reason too.
func TestTestRefusalIsCsReason(t *testing.T) {
	x := []float64{1, 2.5, 3, 4.5, 2}
	_, err := TTest1(x, 0, TwoSided, 1.5)
	wantReason(t, "TTest1 alpha", err, ErrInvalidArgument, "alpha must be in (0, 1), got 1.5")
	_, err = VarTest1(x, -1, TwoSided, 0.05)
	wantReason(t, "VarTest1 sigma2", err, ErrInvalidArgument, "sigma2 must be finite and > 0, got -1")
	_, err = TTest2(x, x, math.Inf(1), Less, 0.05)
	wantReason(t, "TTest2 mu0", err, ErrInvalidArgument, "mu0 must be finite, got inf")
	if _, err := TTest1(x, 0, TwoSided, 0.05); err != nil {
		t.Fatal(err)
	}
}
