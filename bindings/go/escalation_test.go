package mcstat

// Escalation (the two-stage test instead of reruns): the design's numbers,
// the decisions at the bounds, the refusals, the struct's layout.

import (
	"errors"
	"fmt"
	"math"
	"testing"
	"unsafe"
)

func escalationDesign(t *testing.T) Escalation {
	t.Helper()
	d, err := NewEscalation(0.05, 0.5, 0.5)
	if err != nil {
		t.Fatal(err)
	}
	return d
}

func wantDecision(t *testing.T, what string, got EscalationDecision, err error, want EscalationDecision) {
	t.Helper()
	if err != nil || got != want {
		t.Errorf("%s: %v, %v; want %v", what, got, err, want)
	}
}

func wantInvalid(t *testing.T, what string, err error) {
	t.Helper()
	if !errors.Is(err, ErrInvalidArgument) {
		t.Errorf("%s: error %v, want ErrInvalidArgument", what, err)
	}
}

func TestEscalationDesign(t *testing.T) {
	d := escalationDesign(t)
	if d.Alpha() != 0.05 || d.Alpha1() != 0.025 || d.Alpha0() != 0.5 {
		t.Fatalf("alpha %g alpha1 %g alpha0 %g", d.Alpha(), d.Alpha1(), d.Alpha0())
	}
	c := 0.025 / math.Log(20)
	if math.Abs(d.C()-c) > 1e-15*c || d.C() > d.Alpha1() {
		t.Fatalf("c = %g, want %g", d.C(), c)
	}
	// plain data: a copy is the same design
	e := d
	if e != d {
		t.Fatal("a copy differs")
	}
	// alpha0 = 1: stage 1 never passes
	all, err := NewEscalation(0.05, 0.5, 1)
	if err != nil {
		t.Fatal(err)
	}
	dec, err := all.Decide(1)
	wantDecision(t, "alpha0 1, p1 1", dec, err, EscalationContinue)
	if s := fmt.Sprint(EscalationPass, EscalationReject, EscalationContinue, EscalationDecision(7)); s != "pass reject continue EscalationDecision(7)" {
		t.Errorf("String: %q", s)
	}
}

func TestEscalationStage1Bounds(t *testing.T) {
	d := escalationDesign(t)
	for _, c := range []struct {
		p1   float64
		want EscalationDecision
	}{
		{d.Alpha1(), EscalationReject},
		{math.Nextafter(d.Alpha1(), 1), EscalationContinue},
		{d.Alpha0(), EscalationContinue},
		{math.Nextafter(d.Alpha0(), 1), EscalationPass},
		{0, EscalationReject},
		{1, EscalationPass},
	} {
		dec, err := d.Decide(c.p1)
		wantDecision(t, fmt.Sprintf("Decide(%v)", c.p1), dec, err, c.want)
	}
}

func TestEscalationStage2Bound(t *testing.T) {
	d := escalationDesign(t)
	// p1 a power of two: p1 * (c / p1) is c exactly
	p1 := 0.25
	p2 := d.C() / p1
	if p1*p2 != d.C() {
		t.Fatalf("p1 p2 = %v, c = %v", p1*p2, d.C())
	}
	dec, err := d.Decide(p1)
	wantDecision(t, "Decide(0.25)", dec, err, EscalationContinue)
	for _, c := range []struct {
		p1, p2 float64
		want   EscalationDecision
	}{
		{p1, p2, EscalationReject},
		{p1, math.Nextafter(p2, 1), EscalationPass},
		{p1, 0, EscalationReject},
		{p1, 1, EscalationPass},
		// at the band's ends
		{d.Alpha0(), 0, EscalationReject},
		{math.Nextafter(d.Alpha1(), 1), 1, EscalationPass},
	} {
		dec, err := d.Decide2(c.p1, c.p2)
		wantDecision(t, fmt.Sprintf("Decide2(%v, %v)", c.p1, c.p2), dec, err, c.want)
	}
}

func TestEscalationRefusedDesigns(t *testing.T) {
	nan := math.NaN()
	for _, a := range [][3]float64{
		{0, 0.5, 0.5},
		{1, 0.5, 0.5},
		{-0.1, 0.5, 0.5},
		{math.Inf(1), 0.5, 0.5},
		{nan, 0.5, 0.5},
		{0.05, 0, 0.5},
		{0.05, 1, 0.5},
		{0.05, nan, 0.5},
		{0.05, 0.5, 0.025}, // alpha0 = alpha1
		{0.05, 0.5, 0.01},  // alpha0 < alpha1
		{0.05, 0.5, 1.5},
		{0.05, 0.5, nan},
		{0.5, 0.5, 0.3}, // c would exceed alpha1
	} {
		d, err := NewEscalation(a[0], a[1], a[2])
		wantInvalid(t, fmt.Sprintf("NewEscalation(%v, %v, %v)", a[0], a[1], a[2]), err)
		if d != (Escalation{}) {
			t.Errorf("NewEscalation(%v, %v, %v) returned %+v with its error", a[0], a[1], a[2], d)
		}
	}
}

func TestEscalationRefusedDecisions(t *testing.T) {
	d := escalationDesign(t)
	nan := math.NaN()
	for _, p1 := range []float64{nan, -0.1, 1.1, math.Inf(1), -1e-300} {
		_, err := d.Decide(p1)
		wantInvalid(t, fmt.Sprintf("Decide(%v)", p1), err)
		_, err = d.Decide2(p1, 0.1)
		wantInvalid(t, fmt.Sprintf("Decide2(%v, 0.1)", p1), err)
	}
	// stage 2's p-value outside [0, 1], NaN included
	for _, p2 := range []float64{nan, -0.1, 1.5, math.Inf(1)} {
		_, err := d.Decide2(0.25, p2)
		wantInvalid(t, fmt.Sprintf("Decide2(0.25, %v)", p2), err)
	}
	// stage 2 after stage 1 passed or rejected
	dec, err := d.Decide(0.9)
	wantDecision(t, "Decide(0.9)", dec, err, EscalationPass)
	_, err = d.Decide2(0.9, 0.1)
	wantInvalid(t, "Decide2 after a stage-1 pass", err)
	_, err = d.Decide2(math.Nextafter(d.Alpha0(), 1), 0)
	wantInvalid(t, "Decide2 just above alpha0", err)
	dec, err = d.Decide(0.001)
	wantDecision(t, "Decide(0.001)", dec, err, EscalationReject)
	_, err = d.Decide2(0.001, 0.1)
	wantInvalid(t, "Decide2 after a stage-1 rejection", err)
	// the zero value is no design
	_, err = Escalation{}.Decide(0.5)
	wantInvalid(t, "Decide on the zero Escalation", err)
}

// The C struct as cgo sees mcstat.h: four doubles, in the header's order.
func TestEscalationLayout(t *testing.T) {
	var e Escalation
	r := e.raw
	if s := unsafe.Sizeof(r); s != 32 {
		t.Errorf("sizeof(mcstat_escalation) = %d", s)
	}
	offsets := [4]uintptr{unsafe.Offsetof(r.alpha), unsafe.Offsetof(r.alpha1), unsafe.Offsetof(r.alpha0), unsafe.Offsetof(r.c)}
	if offsets != [4]uintptr{0, 8, 16, 24} {
		t.Errorf("offsets %v", offsets)
	}
}
