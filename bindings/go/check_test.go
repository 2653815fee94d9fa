package mcstat

// The renderer checks with Go callbacks: the C tests' models (a disk warp
// and a Phong-like lobe, tests/c/test_check.c; a coated diffuse BSDF with a
// discrete lobe, tests/c/test_check_lobes.c; free flights whose escapes
// carry a weight, tests/c/test_check_phase.c), correct ones passing and
// planted bugs caught by the route that must catch them; callback errors,
// panics and invalid values reported as ErrCallback, never a crash.

import (
	"errors"
	"fmt"
	"io"
	"math"
	"strings"
	"testing"
)

// diskWarp maps the square to the disk by r = sqrt(u1) (the bug: r = u1^0.45).
func diskWarp(bug bool) *Model {
	return &Model{
		Domain: DomainDisk, NUniforms: 2,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := 0; k < len(x)/2; k++ {
				r := math.Sqrt(u[2*k])
				if bug {
					r = math.Pow(u[2*k], 0.45)
				}
				phi := 2 * math.Pi * u[2*k+1]
				x[2*k], x[2*k+1] = r*math.Cos(phi), r*math.Sin(phi)
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = 0
				if x[2*k]*x[2*k]+x[2*k+1]*x[2*k+1] <= 1 {
					out[k] = 1 / math.Pi
				}
			}
			return nil
		},
	}
}

// lobe is a cosine-power lobe around the mirror direction of wi, with albedo
// rho; pdfScale != 1 plants a pdf() that disagrees with the sampler.
type lobe struct {
	e, rho, pdfScale float64
	r                [3]float64
}

func newLobe(e float64, wi [3]float64) *lobe {
	L := &lobe{e: e, rho: 0.8, pdfScale: 1, r: [3]float64{-wi[0], -wi[1], wi[2]}}
	n := math.Sqrt(L.r[0]*L.r[0] + L.r[1]*L.r[1] + L.r[2]*L.r[2])
	for i := range L.r {
		L.r[i] /= n
	}
	return L
}

func (L *lobe) density(e float64, x []float64) float64 {
	c := L.r[0]*x[0] + L.r[1]*x[1] + L.r[2]*x[2]
	if x[2] > 0 && c > 0 {
		return (e + 1) / (2 * math.Pi) * math.Pow(c, e)
	}
	return 0
}

func (L *lobe) model() *Model {
	// an orthonormal frame around r
	a := [3]float64{1, 0, 0}
	if math.Abs(L.r[0]) > 0.9 {
		a = [3]float64{0, 1, 0}
	}
	cross := func(p, q [3]float64) [3]float64 {
		return [3]float64{p[1]*q[2] - p[2]*q[1], p[2]*q[0] - p[0]*q[2], p[0]*q[1] - p[1]*q[0]}
	}
	t1 := cross(L.r, a)
	n := math.Sqrt(t1[0]*t1[0] + t1[1]*t1[1] + t1[2]*t1[2])
	for i := range t1 {
		t1[i] /= n
	}
	t2 := cross(L.r, t1)
	return &Model{
		Domain: DomainSphere, NUniforms: 3, Weight: WeightOverPDF, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := range weight {
				c := math.Pow(u[3*k], 1/(L.e+1))
				s := math.Sqrt(math.Max(0, 1-c*c))
				phi := 2 * math.Pi * u[3*k+1]
				w := x[3*k : 3*k+3]
				for i := range w {
					w[i] = c*L.r[i] + s*(math.Cos(phi)*t1[i]+math.Sin(phi)*t2[i])
				}
				pdf[k] = L.density(L.e, w)
				weight[k] = 0
				if pdf[k] > 0 {
					weight[k] = L.rho
				}
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = L.density(L.e*L.pdfScale, x[3*k:3*k+3])
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = L.rho * L.density(L.e, x[3*k:3*k+3])
			}
			return nil
		},
	}
}

func TestCheckWarp(t *testing.T) {
	for _, bug := range []bool{false, true} {
		r, err := CheckWarp(diskWarp(bug), 20000, 3, 0.01, nil)
		if err != nil {
			t.Fatalf("bug %v: %v", bug, err)
		}
		if r.Reject != bug || r.Routes[RouteCells].Reject != bug || r.Kind != KindWarp || r.Domain != DomainDisk ||
			r.WI != nil || r.N != 20000 || r.Calls == 0 {
			t.Errorf("bug %v: %+v", bug, r)
		}
		if !bug && math.Abs(r.Mass-1) > 1e-9 {
			t.Errorf("disk mass %.15g", r.Mass)
		}
		if text := r.String(); !strings.Contains(text, "cells") || strings.HasPrefix(text, "<mcstat") {
			t.Errorf("report:\n%s", text)
		}
	}
	bytes, err := CheckWorkSize(diskWarp(false), 20000, nil)
	if err != nil || bytes <= 0 {
		t.Errorf("work size %d %v", bytes, err)
	}
}

func TestCheckBSDF(t *testing.T) {
	wi := [3]float64{0.5, 0.1, 0.86}
	ok := newLobe(40, wi)
	r, err := CheckBSDF(ok.model(), wi, 20000, 1, 0.01, nil)
	if err != nil {
		t.Fatal(err)
	}
	if r.Reject || r.Kind != KindBSDF || len(r.WI) != 3 || r.Routes[RouteWeight].State != RouteRan ||
		r.Routes[RouteReciprocity].State != RouteSkipped || math.Abs(r.Albedo-0.8) > 0.05 {
		t.Errorf("a correct lobe: %+v\n%s", r, r)
	}
	// what each route produces, and nothing else
	cells, pv, rec := r.Routes[RouteCells], r.Routes[RoutePDFValue], r.Routes[RouteReciprocity]
	if cells.Statistic == nil || cells.DF == nil || *cells.DF < 8 || cells.PAdjusted == nil || cells.Where != nil ||
		cells.Deterministic {
		t.Errorf("cells route %+v", cells)
	}
	if pv.PValue != nil || pv.Statistic != nil || len(pv.Where) != 3 || len(pv.Value) != 2 || !pv.Deterministic ||
		pv.Detectable == nil || pv.Checked != 20000 {
		t.Errorf("pdf_value route %+v", pv)
	}
	if rec.Statistic != nil || rec.Effect != nil || rec.NFor1Pct != nil || rec.Where != nil || rec.Value != nil {
		t.Errorf("skipped route %+v", rec)
	}
	bad := newLobe(40, wi)
	bad.pdfScale = 1.1
	r, err = CheckBSDF(bad.model(), wi, 20000, 1, 0.01, nil)
	if err != nil || !r.Reject || !r.Routes[RoutePDFValue].Reject {
		t.Errorf("pdf() of the wrong lobe not caught: %v\n%s", err, r)
	}
	// options reach the library: only the cells route
	o := DefaultCheckOptions()
	o.Routes = Routes(RouteCells)
	r, err = CheckBSDF(bad.model(), wi, 20000, 1, 0.01, &o)
	if err != nil || r.Routes[RoutePDFValue].State != RouteSkipped || r.Routes[RouteCells].State != RouteRan {
		t.Errorf("routes option: %v %+v", err, r.Routes)
	}
	// an emitter: uniform directions, constant radiance
	em := &Model{Domain: DomainSphere, NUniforms: 2, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := range weight {
				z := 1 - 2*u[2*k]
				s, phi := math.Sqrt(math.Max(0, 1-z*z)), 2*math.Pi*u[2*k+1]
				x[3*k], x[3*k+1], x[3*k+2] = s*math.Cos(phi), s*math.Sin(phi), z
				pdf[k], weight[k] = 1/(4*math.Pi), 2*4*math.Pi
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = 1 / (4 * math.Pi)
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = 2
			}
			return nil
		},
	}
	r, err = CheckEmitter(em, 10000, 2, 0.01, nil)
	if err != nil || r.Reject || r.Kind != KindEmitter || r.Routes[RouteEnergy].State != RouteSkipped {
		t.Errorf("emitter: %v\n%s", err, r)
	}
}

// A fifth of the samples "fail" by weight 0 alone, their pdf kept: the
// weight route rejects and the report counts them and says how to mark one.
func TestCheckZeroWeight(t *testing.T) {
	wi := [3]float64{0.5, 0.1, 0.86}
	m := newLobe(40, wi).model()
	sample := m.Sample
	m.Sample = func(wi, u, x, weight, pdf []float64) error {
		err := sample(wi, u, x, weight, pdf)
		for k := range weight {
			if u[3*k+2] < 0.2 {
				weight[k] = 0
			}
		}
		return err
	}
	r, err := CheckBSDF(m, wi, 5000, 1, 0.01, nil)
	if err != nil || !r.Reject || !r.Routes[RouteWeight].Reject {
		t.Fatalf("weight-0 failures not caught: %v\n%s", err, r)
	}
	if f := float64(r.ZeroWeight) / float64(r.N); f < 0.17 || f > 0.23 || !strings.Contains(r.String(), "must return pdf 0") {
		t.Errorf("zero_weight %d of %d\n%s", r.ZeroWeight, r.N, r)
	}
	r, err = CheckBSDF(newLobe(40, wi).model(), wi, 5000, 1, 0.01, nil)
	if err != nil || r.ZeroWeight != 0 {
		t.Errorf("a correct lobe: %v zero_weight %d", err, r.ZeroWeight)
	}
}

func TestCheckCallbackFailures(t *testing.T) {
	sentinel := io.ErrUnexpectedEOF
	calls := 0
	m := diskWarp(false)
	m.PDF = func(wi, x, out []float64) error {
		calls++
		return fmt.Errorf("renderer lost its scene: %w", sentinel)
	}
	_, err := CheckWarp(m, 5000, 1, 0.05, nil)
	var ce *CallbackError
	if !errors.Is(err, ErrCallback) || !errors.Is(err, sentinel) || !errors.As(err, &ce) || ce.Callback != "pdf" ||
		calls != 1 {
		t.Errorf("an error from pdf(): %v (%d calls)", err, calls)
	}
	// a panic is recovered at the C boundary and reported
	m = diskWarp(false)
	m.Sample = func(wi, u, x, weight, pdf []float64) error {
		var table []float64
		x[0] = table[len(u)] // index out of range
		return nil
	}
	_, err = CheckWarp(m, 5000, 1, 0.05, nil)
	var pe *PanicError
	if !errors.Is(err, ErrCallback) || !errors.As(err, &pe) || !strings.Contains(err.Error(), "index out of range") {
		t.Errorf("a panic in sample(): %v", err)
	}
	b := newLobe(10, [3]float64{0, 0, 1}).model()
	b.Eval = func(wi, x, out []float64) error { panic("eval exploded") }
	if _, err = CheckBSDF(b, [3]float64{0, 0, 1}, 5000, 1, 0.05, nil); !errors.Is(err, ErrCallback) ||
		!errors.As(err, &ce) || ce.Callback != "eval" {
		t.Errorf("a panic in eval(): %v", err)
	}
	// invalid values: libmcstat's sentence, no Go error
	m = diskWarp(false)
	m.PDF = func(wi, x, out []float64) error {
		for k := range out {
			out[k] = math.NaN()
		}
		return nil
	}
	_, err = CheckWarp(m, 5000, 1, 0.05, nil)
	if !errors.Is(err, ErrCallback) || !errors.As(err, &ce) || ce.Err != nil || ce.Message == "" {
		t.Errorf("NaN densities: %v", err)
	}
	// the check still works after the failures (handles released, nothing left behind)
	if r, err := CheckWarp(diskWarp(false), 5000, 1, 0.05, nil); err != nil || r.Reject {
		t.Errorf("after failures: %v", err)
	}
}

func TestCheckBadInput(t *testing.T) {
	if _, err := CheckWarp(nil, 5000, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("nil model: %v", err)
	}
	if _, err := CheckWarp(&Model{Domain: DomainDisk, NUniforms: 2}, 5000, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("no callbacks: %v", err)
	}
	if _, err := CheckWarp(diskWarp(false), 10, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("n = 10: %v", err)
	}
	if _, err := CheckWarp(diskWarp(false), -1, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("n = -1: %v", err)
	}
	m := diskWarp(false)
	m.NUniforms = 9
	if _, err := CheckWarp(m, 5000, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("9 uniforms: %v", err)
	}
	m = diskWarp(false)
	m.Domain = Domain(12)
	if _, err := CheckWorkSize(m, 5000, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("domain 12: %v", err)
	}
	o := DefaultCheckOptions()
	o.Routes = 0
	if _, err := CheckWarp(diskWarp(false), 5000, 1, 0.05, &o); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("no routes: %v", err)
	}
	lobe := newLobe(10, [3]float64{0, 0, 1}).model()
	lobe.Eval = nil // a BSDF needs eval
	if _, err := CheckBSDF(lobe, [3]float64{0, 0, 1}, 5000, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("BSDF without eval: %v", err)
	}
	if _, err := CheckBSDF(newLobe(10, [3]float64{0, 0, 1}).model(), [3]float64{}, 5000, 1, 0.05, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("wi zero: %v", err)
	}
}

func TestCheckNames(t *testing.T) {
	for r := Route(0); int(r) < NumRoutes; r++ {
		p, err := ParseRoute(r.String())
		if err != nil || p != r || r.Meaning() == "" || r.BlindSpot() == "" {
			t.Errorf("route %d %q: %v", int(r), r, err)
		}
	}
	if Route(NumRoutes).Meaning() != "" || !strings.HasPrefix(Route(NumRoutes).String(), "Route(") {
		t.Error("an invalid route has a name")
	}
	if _, err := ParseRoute("colour"); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("route colour: %v", err)
	}
	dims := map[Domain]int{DomainSphere: 3, DomainHemisphere: 3, DomainSquare: 2, DomainDisk: 2, DomainInterval: 1}
	for d, n := range dims {
		p, err := ParseDomain(d.String())
		if err != nil || p != d || d.Dims() != n {
			t.Errorf("domain %v: %v %d", d, err, d.Dims())
		}
	}
	if Domain(9).Dims() != 0 {
		t.Error("domain 9 has dimensions")
	}
	if _, err := ParseDomain("cube"); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("cube: %v", err)
	}
	if o := DefaultCheckOptions(); o.Routes != AllRoutes || o.Batch != 65536 || o.RTol != 1e-3 {
		t.Errorf("defaults %+v", o)
	}
	if Routes(RouteCells, RouteKS) != 1|1<<8 {
		t.Error("Routes")
	}
}

// Checks on several goroutines at once: each call has its own handle, so
// callbacks reach their own model, and each report is the serial one.
func TestCheckConcurrent(t *testing.T) {
	serial := map[bool]*CheckReport{}
	for _, bug := range []bool{false, true} {
		r, err := CheckWarp(diskWarp(bug), 20000, 7, 0.01, nil)
		if err != nil || r.Reject != bug {
			t.Fatalf("bug %v: %v %v", bug, err, r)
		}
		serial[bug] = r
	}
	errs := make(chan error, 4)
	for g := 0; g < 4; g++ {
		go func(bug bool) {
			r, err := CheckWarp(diskWarp(bug), 20000, 7, 0.01, nil)
			if err == nil && (r.Reject != bug || r.PValue != serial[bug].PValue || r.String() != serial[bug].String()) {
				err = fmt.Errorf("bug %v: reject %v p %g, serially %g", bug, r.Reject, r.PValue, serial[bug].PValue)
			}
			errs <- err
		}(g%2 == 1)
	}
	for g := 0; g < 4; g++ {
		if err := <-errs; err != nil {
			t.Error(err)
		}
	}
}

// homogeneous free flights (sigma_t 2, sigma_s 1.5) up to a surface at t = 1;
// bug: pdf() with sigma_t 10% off
func homogeneous(bug bool) *Model {
	const st, ss, tmax = 2.0, 1.5, 1.0
	density := func(t, s float64) float64 {
		if t < tmax {
			return s * math.Exp(-s*t)
		}
		return 0
	}
	return &Model{
		Domain: DomainInterval, NUniforms: 1, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := range pdf {
				t := -math.Log1p(-u[k]) / st
				x[k], weight[k], pdf[k] = 0, 0, 0
				if t < tmax {
					x[k], pdf[k], weight[k] = t, density(t, st), ss/st
				}
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			s := st
			if bug {
				s *= 1.1
			}
			for k := range out {
				out[k] = density(x[k], s)
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = ss / st * density(x[k], st)
			}
			return nil
		},
	}
}

func TestCheckMedium(t *testing.T) {
	for _, bug := range []bool{false, true} {
		r, err := CheckMedium(homogeneous(bug), 2.0, 20000, 1, 0.01, nil)
		if err != nil {
			t.Fatalf("bug %v: %v", bug, err)
		}
		if r.Reject != bug || r.Routes[RoutePDFValue].Reject != bug || r.Kind != KindMedium || r.WI != nil {
			t.Errorf("bug %v: %+v", bug, r)
		}
		if !bug && math.Abs(r.Mass-(1-math.Exp(-2))) > 1e-3 {
			t.Errorf("mass %.15g", r.Mass)
		}
	}
	if _, err := CheckMedium(homogeneous(false), 0, 20000, 1, 0.01, nil); !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("sigmaRef 0: %v", err)
	}
}

// escaping is homogeneous(false) whose escapes (pdf 0) carry the weight
// escape on, as tests/c/test_check_phase.c's med_sample_esc (1 is right).
func escaping(escape float64) *Model {
	m := homogeneous(false)
	sample := m.Sample
	m.Sample = func(wi, u, x, weight, pdf []float64) error {
		if err := sample(wi, u, x, weight, pdf); err != nil {
			return err
		}
		for k := range pdf {
			if pdf[k] == 0 {
				weight[k] = escape
			}
		}
		return nil
	}
	return m
}

func withEscapes(t float64) *CheckOptions {
	o := DefaultCheckOptions()
	o.EscapeTransmittance = &t
	return &o
}

func TestCheckMediumEscapes(t *testing.T) {
	T := math.Exp(-2.0 * 1.0) // exp(-sigma_t tmax)
	r, err := CheckMedium(homogeneous(false), 2.0, 20000, 1, 0.01, nil)
	if err != nil {
		t.Fatal(err)
	}
	if !math.IsNaN(r.EscapeWeight) || !math.IsNaN(r.EscapeWeightSE) {
		t.Errorf("not checked: escape weight %v (se %v)", r.EscapeWeight, r.EscapeWeightSE)
	}
	// analog escapes of weight 1: their mean over the flights is the escape share
	r, err = CheckMedium(escaping(1), 2.0, 20000, 1, 0.01, withEscapes(T))
	if err != nil {
		t.Fatal(err)
	}
	share := float64(r.NFailed) / float64(r.N)
	if r.Reject || math.Abs(r.EscapeWeight-share) > 1e-12*share || !(r.EscapeWeightSE > 0) {
		t.Errorf("escapes of weight 1: escape weight %v (se %v), share %v\n%v", r.EscapeWeight, r.EscapeWeightSE,
			share, r)
	}
	if v := r.Routes[RouteMass].Value; len(v) != 2 || v[0] != r.EscapeWeight || v[1] != T {
		t.Errorf("mass route's values %v, want [%v %v]", v, r.EscapeWeight, T)
	}
	if !strings.Contains(r.String(), "escape weights") {
		t.Errorf("report without the escape weights:\n%v", r)
	}
	// escapes 10% light: the mass route sees it
	r, err = CheckMedium(escaping(0.9), 2.0, 20000, 1, 0.01, withEscapes(T))
	if err != nil {
		t.Fatal(err)
	}
	if !r.Reject || !r.Routes[RouteMass].Reject {
		t.Errorf("escapes of weight 0.9 pass:\n%v", r)
	}
}

func TestCheckMediumEscapesRefused(t *testing.T) {
	for _, bad := range []float64{math.NaN(), -0.5, 1.5, math.Inf(1)} {
		_, err := CheckMedium(escaping(1), 2.0, 20000, 1, 0.01, withEscapes(bad))
		if !errors.Is(err, ErrInvalidArgument) || !strings.Contains(err.Error(), "EscapeTransmittance") {
			t.Errorf("EscapeTransmittance %v: %v", bad, err)
		}
		if _, err := CheckWorkSize(escaping(1), 20000, withEscapes(bad)); !errors.Is(err, ErrInvalidArgument) {
			t.Errorf("CheckWorkSize, EscapeTransmittance %v: %v", bad, err)
		}
	}
	// where escapes are allowed is C's to say, in its words
	value := escaping(1)
	value.Weight = WeightValue
	_, err := CheckMedium(value, 2.0, 20000, 1, 0.01, withEscapes(0.5))
	wantReason(t, "WeightValue", err, ErrInvalidArgument, "options.escape_transmittance needs model.weight = "+
		"MCSTAT_CHECK_WEIGHT_OVER_PDF (an escape's weight is what it carries on)")
	_, err = CheckPhase(isotropic(1), [3]float64{0, 0.6, 0.8}, 5000, 1, 0.01, withEscapes(0.5))
	wantReason(t, "CheckPhase with EscapeTransmittance", err, ErrInvalidArgument,
		"options.escape_transmittance is 0.5 in the check of a phase function: it is a medium's")
}

// an isotropic phase function sampled uniformly; bug: eval and weight 0.9 p
func isotropic(scale float64) *Model {
	p := 1 / (4 * math.Pi)
	return &Model{
		Domain: DomainSphere, NUniforms: 2, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			for k := range pdf {
				z := 1 - 2*u[2*k]
				s := math.Sqrt(math.Max(0, 1-z*z))
				phi := 2 * math.Pi * u[2*k+1]
				x[3*k], x[3*k+1], x[3*k+2] = s*math.Cos(phi), s*math.Sin(phi), z
				weight[k], pdf[k] = scale, p
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = p
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = scale * p
			}
			return nil
		},
	}
}

func TestCheckPhase(t *testing.T) {
	wi := [3]float64{0, 0.6, 0.8}
	for _, scale := range []float64{1, 0.9} {
		r, err := CheckPhase(isotropic(scale), wi, 5000, 1, 0.01, nil)
		if err != nil {
			t.Fatal(err)
		}
		bad := scale != 1
		if r.Reject != bad || r.Routes[RouteEnergy].Reject != bad || r.Kind != KindPhase || len(r.WI) != 3 {
			t.Errorf("scale %v: %+v", scale, r)
		}
	}
}

// coated is the coated diffuse BSDF of tests/c/test_check_lobes.c: a
// specular reflection picked with probability coatQ (weight F/coatQ) over
// a Lambertian base of albedo coatRho; specWeight != 1 plants a specular
// weight that disagrees with the lobe.  Its Lobes is left to the tests.
const coatQ, coatRho = 0.3, 0.6

func fresnel(c float64) float64 { return 0.04 + 0.96*math.Pow(1-c, 5) }

func coated(specWeight float64) *Model {
	return &Model{
		Domain: DomainHemisphere, NUniforms: 3, Weight: WeightOverPDF, SampleReports: true,
		Sample: func(wi, u, x, weight, pdf []float64) error {
			f := fresnel(wi[2])
			for k := range weight {
				v, d := u[3*k:3*k+3], x[3*k:3*k+3]
				if v[0] < coatQ {
					d[0], d[1], d[2] = -wi[0], -wi[1], wi[2]
					pdf[k], weight[k] = coatQ, f/coatQ*specWeight
				} else {
					r, phi := math.Sqrt(v[1]), 2*math.Pi*v[2]
					d[0], d[1], d[2] = r*math.Cos(phi), r*math.Sin(phi), math.Sqrt(1-v[1])
					pdf[k], weight[k] = (1-coatQ)*d[2]/math.Pi, (1-f)*coatRho/(1-coatQ)
				}
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = (1 - coatQ) * math.Max(x[3*k+2], 0) / math.Pi
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = (1 - fresnel(wi[2])) * coatRho * math.Max(x[3*k+2], 0) / math.Pi
			}
			return nil
		},
	}
}

func coatedLobes(wi []float64) ([]Lobe, error) {
	return []Lobe{{Dir: [3]float64{-wi[0], -wi[1], wi[2]}, Mass: coatQ, Value: fresnel(wi[2])}}, nil
}

var coatedWI = [3]float64{0.4, 0.1, 0.9}

func TestCheckLobes(t *testing.T) {
	m := coated(1)
	calls := 0
	m.Lobes = func(wi []float64) ([]Lobe, error) {
		calls++
		return coatedLobes(wi)
	}
	r, err := CheckBSDF(m, coatedWI, 20000, 1, 0.01, nil)
	if err != nil || r.Reject {
		t.Fatalf("a correct coated BSDF: %v\n%s", err, r)
	}
	cos := coatedWI[2] / math.Sqrt(0.98) // lobes() sees the normalised wi
	if calls != 1 || r.Lobes != 1 || r.NLobe < 5000 || r.NLobe > 7000 || math.Abs(r.LobeMass-coatQ) > 1e-15 ||
		math.Abs(r.LobeAlbedo/fresnel(cos)-1) > 1e-12 || math.Abs(r.Albedo/((1-fresnel(cos))*coatRho)-1) > 0.02 {
		t.Errorf("%d calls, lobes %d, n_lobe %d, mass %v, albedo %v + %v", calls, r.Lobes, r.NLobe, r.LobeMass,
			r.LobeAlbedo, r.Albedo)
	}
	if r.Routes[RoutePDFValue].Checked != 20000 || !strings.Contains(r.String(), "discrete lobes: 1") {
		t.Errorf("pdf_value checked %d\n%s", r.Routes[RoutePDFValue].Checked, r)
	}
	// without Lobes the specular samples' pdf (a probability) disagrees with pdf()
	r, err = CheckBSDF(coated(1), coatedWI, 20000, 1, 0.01, nil)
	if err != nil || !r.Reject || !r.Routes[RoutePDFValue].Reject || r.Lobes != 0 || r.NLobe != 0 ||
		r.LobeMass != 0 || r.LobeAlbedo != 0 {
		t.Errorf("no lobes: %v\n%s", err, r)
	}
	// the specular weight 5% off: RouteWeight, not RoutePDFValue
	m = coated(1.05)
	m.Lobes = coatedLobes
	r, err = CheckBSDF(m, coatedWI, 20000, 1, 0.01, nil)
	if err != nil || !r.Reject || !r.Routes[RouteWeight].Reject || r.Routes[RoutePDFValue].Reject ||
		r.Routes[RouteWeight].Effect == nil || math.Abs(*r.Routes[RouteWeight].Effect-0.05/1.05) > 1e-9 {
		t.Errorf("a discrete weight error: %v\n%s", err, r)
	}
}

func TestCheckLobesFailures(t *testing.T) {
	sentinel := io.ErrUnexpectedEOF
	for _, c := range []struct {
		name  string
		lobes LobesFunc
		want  string // in the error's text
		goErr bool   // a Go error (else libmcstat's sentence)
	}{
		{"error", func(wi []float64) ([]Lobe, error) { return nil, fmt.Errorf("no lobes today: %w", sentinel) },
			"no lobes today", true},
		{"panic", func(wi []float64) ([]Lobe, error) { panic("lobes exploded") }, "lobes exploded", true},
		{"too many", func(wi []float64) ([]Lobe, error) {
			l, _ := coatedLobes(wi)
			for k := 0; k < MaxLobes; k++ {
				a := 0.3 * float64(k)
				l = append(l, Lobe{Dir: [3]float64{0.5 * math.Sin(a), 0.5 * math.Cos(a), math.Sqrt(0.75)}})
			}
			return l, nil
		}, fmt.Sprintf("gave %d lobes: at most %d", MaxLobes+1, MaxLobes), true},
		{"mass 1.5", func(wi []float64) ([]Lobe, error) {
			return []Lobe{{Dir: [3]float64{-wi[0], -wi[1], wi[2]}, Mass: 1.5, Value: 0.1}}, nil
		}, "mass 1.5", false},
	} {
		m := coated(1)
		m.Lobes = c.lobes
		_, err := CheckBSDF(m, coatedWI, 20000, 1, 0.01, nil)
		var ce *CallbackError
		if !errors.Is(err, ErrCallback) || !errors.As(err, &ce) || !strings.Contains(err.Error(), c.want) ||
			(ce.Err != nil) != c.goErr || (c.goErr && ce.Callback != "lobes") || !strings.Contains(ce.Message, "lobes()") {
			t.Errorf("%s: %v", c.name, err)
		}
		if c.name == "error" && !errors.Is(err, sentinel) {
			t.Errorf("the callback's error is not wrapped: %v", err)
		}
	}
	// lobes are a BSDF's (C's reason)
	m := isotropic(1)
	m.Lobes = coatedLobes
	_, err := CheckPhase(m, [3]float64{0, 0.6, 0.8}, 5000, 1, 0.01, nil)
	wantReason(t, "lobes in a phase check", err, ErrInvalidArgument,
		"model.lobes is set in the check of a phase function: discrete lobes are a BSDF's")
	// the check still works after the failures
	m = coated(1)
	m.Lobes = coatedLobes
	if r, err := CheckBSDF(m, coatedWI, 20000, 1, 0.01, nil); err != nil || r.Reject {
		t.Errorf("after failures: %v", err)
	}
}
