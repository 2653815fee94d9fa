package mcstat

import (
	"math"
	"strings"
	"testing"
)

// isotropicF32 is isotropic(1) as a float32 renderer computes it: eval and
// pdf the float32 1/(4 pi), which integrates to 0.99999996.
func isotropicF32() *Model {
	p := float64(float32(1) / float32(4*math.Pi))
	m := isotropic(1)
	m.PDF = func(wi, x, out []float64) error {
		for k := range out {
			out[k] = p
		}
		return nil
	}
	m.Eval = m.PDF
	sample := m.Sample
	m.Sample = func(wi, u, x, weight, pdf []float64) error {
		if err := sample(wi, u, x, weight, pdf); err != nil {
			return err
		}
		for k := range pdf {
			pdf[k] = p
		}
		return nil
	}
	return m
}

func TestCheckResolution(t *testing.T) {
	wi := [3]float64{0, 0, 1}
	r, err := CheckPhase(isotropicF32(), wi, 100000, 0, 0.01, nil)
	if err != nil {
		t.Fatal(err)
	}
	res := r.Routes[RouteIntegrals].Resolution
	if r.Reject || res == nil || *res != math.Ldexp(1, -18) || r.Routes[RoutePDFValue].Resolution != nil {
		t.Errorf("derived float32 floor: %v", r)
	}
	opt := DefaultCheckOptions()
	opt.Resolution = math.Ldexp(1, -47)
	low, err := CheckPhase(isotropicF32(), wi, 100000, 0, 0.01, &opt)
	if err != nil || !low.Routes[RouteIntegrals].Reject {
		t.Errorf("without the floor the rounding is significant: %v %v", err, low)
	}
	opt.Resolution = 0.5
	if _, err := CheckPhase(isotropicF32(), wi, 100000, 0, 0.01, &opt); err == nil {
		t.Error("Resolution 0.5 accepted")
	}
}

// cosineBSDF: f |cos| = rho 3 cos^2/(2 pi) sampled exactly; wrong: eval
// without the cos^2, which sample() reuses (weights rho/cos^2, heavy-tailed).
func cosineBSDF(wrong bool) *Model {
	const rho = 0.8
	eval := func(c float64) float64 {
		if c <= 0 {
			return 0
		}
		if wrong {
			return rho * 3 / (2 * math.Pi)
		}
		return rho * 3 / (2 * math.Pi) * c * c
	}
	pdf := func(c float64) float64 {
		if c <= 0 {
			return 0
		}
		return 3 * c * c / (2 * math.Pi)
	}
	return &Model{
		Domain: DomainHemisphere, NUniforms: 3, SampleReports: true,
		Sample: func(wi, u, x, weight, p []float64) error {
			for k := range p {
				c := math.Min(math.Max(math.Cbrt(1-u[3*k]), 1e-12), 1)
				s := math.Sqrt(math.Max(0, 1-c*c))
				phi := 2 * math.Pi * u[3*k+1]
				x[3*k], x[3*k+1], x[3*k+2] = s*math.Cos(phi), s*math.Sin(phi), c
				p[k] = pdf(c)
				weight[k] = eval(c) / p[k]
			}
			return nil
		},
		PDF: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = pdf(x[3*k+2])
			}
			return nil
		},
		Eval: func(wi, x, out []float64) error {
			for k := range out {
				out[k] = eval(x[3*k+2])
			}
			return nil
		},
	}
}

func TestCheckVerdict(t *testing.T) {
	wi := [3]float64{0, 0, 1}
	ok, err := CheckBSDF(cosineBSDF(false), wi, 20000, 1, 0.01, nil)
	if err != nil || ok.Verdict != Consistent || len(ok.Unanswered) != 0 {
		t.Fatalf("correct model: %v %v", err, ok)
	}
	r, err := CheckBSDF(cosineBSDF(true), wi, 20000, 1, 0.01, nil)
	if err != nil {
		t.Fatal(err)
	}
	open := map[Route]bool{}
	for _, q := range r.Unanswered {
		open[q] = true
	}
	if r.Reject || r.Verdict != Inconclusive || r.Verdict.String() != "inconclusive" ||
		!open[RouteIntegrals] || !open[RouteEnergy] {
		t.Errorf("heavy tails: %v (unanswered %v)", r, r.Unanswered)
	}
	if !strings.Contains(r.Routes[RouteEnergy].Why, "heavy-tailed") || r.Routes[RouteCells].Why != "" {
		t.Errorf("why: %q, %q", r.Routes[RouteEnergy].Why, r.Routes[RouteCells].Why)
	}
	if !strings.Contains(r.String(), "INCONCLUSIVE") {
		t.Errorf("text: %s", r)
	}
}
