package mcstat

// #include <mcstat.h>
import "C"

import (
	"fmt"
	"math"
)

// ---- escalation instead of reruns -------------------------------------------------

// EscalationDecision is what an Escalation design says about the p-values
// it was given.
type EscalationDecision int

const (
	EscalationPass     EscalationDecision = C.MCSTAT_ESCALATION_PASS     // no evidence against H0 at the design's level
	EscalationReject   EscalationDecision = C.MCSTAT_ESCALATION_REJECT   // H0 rejected at the design's level
	EscalationContinue EscalationDecision = C.MCSTAT_ESCALATION_CONTINUE // stage 1 was inconclusive: run stage 2
)

// String is "pass", "reject" or "continue".
func (d EscalationDecision) String() string {
	switch d {
	case EscalationPass:
		return "pass"
	case EscalationReject:
		return "reject"
	case EscalationContinue:
		return "continue"
	}
	return fmt.Sprintf("EscalationDecision(%d)", int(d))
}

// Escalation is a two-stage test design of level Alpha (Bauer & Koehne
// 1994), for a test suite that would otherwise rerun a failed statistical
// test until it passes and so lose its error rate.
//
// Stage 1 tests n1 samples and gives p1: p1 <= Alpha1 rejects, p1 > Alpha0
// passes, and in between the test continues (EscalationContinue) on fresh
// samples, an independent stage 2 of any size chosen after seeing stage 1,
// that give p2; stage 2 rejects when Fisher's product p1 p2 <= C.  C spends
// what stage 1 left of Alpha over the escalation band, so the whole test
// has level Alpha for uniform p-values and at most Alpha for valid
// (super-uniform) ones, discrete tests' included, provided the two stages
// use independent random numbers.  A correct test escalates with
// probability Alpha0 - Alpha1; a borderline error is judged on the samples
// of both stages.  mcstat.h derives the numbers.
//
// An Escalation is plain data, made by NewEscalation and read through its
// methods; the zero value is no design (its Decide returns
// ErrInvalidArgument).
type Escalation struct{ raw C.struct_mcstat_escalation }

// NewEscalation returns the design of level alpha in (0, 1) that spends
// Alpha1 = share1 alpha at stage 1 (share1 in (0, 1)) and escalates up to
// alpha0 in (Alpha1, 1].  ErrInvalidArgument for arguments outside those
// ranges, NaN included, and where alpha0 is so close to Alpha1 that stage
// 2 could not spend the rest (C would exceed Alpha1).
func NewEscalation(alpha, share1, alpha0 float64) (Escalation, error) {
	var e Escalation
	st := C.mcstat_escalation_design(C.double(alpha), C.double(share1), C.double(alpha0), &e.raw)
	if err := check(st); err != nil {
		return Escalation{}, err
	}
	return e, nil
}

// Alpha is the level of the whole two-stage test.
func (e Escalation) Alpha() float64 { return float64(e.raw.alpha) }

// Alpha1 is stage 1's bound: p1 <= Alpha1 rejects.
func (e Escalation) Alpha1() float64 { return float64(e.raw.alpha1) }

// Alpha0 is stage 1's other bound: p1 > Alpha0 passes, Alpha1 < p1 <=
// Alpha0 continues.
func (e Escalation) Alpha0() float64 { return float64(e.raw.alpha0) }

// C is stage 2's bound: p1 p2 <= C rejects (C <= Alpha1).
func (e Escalation) C() float64 { return float64(e.raw.c) }

func (e Escalation) decide(p1, p2 float64) (EscalationDecision, error) {
	var d C.int
	if err := check(C.mcstat_escalation_decide(&e.raw, C.double(p1), C.double(p2), &d)); err != nil {
		return EscalationPass, err
	}
	switch v := EscalationDecision(d); v {
	case EscalationPass, EscalationReject, EscalationContinue:
		return v, nil
	}
	return EscalationPass, invalid(fmt.Sprintf("libmcstat returned an unknown escalation decision %d", int(d)))
}

// Decide is stage 1's decision on its p-value p1 in [0, 1]:
// EscalationReject, EscalationPass, or EscalationContinue to stage 2.
// ErrInvalidArgument for p1 outside [0, 1], NaN included.
func (e Escalation) Decide(p1 float64) (EscalationDecision, error) {
	return e.decide(p1, math.NaN())
}

// Decide2 is the final decision, EscalationReject or EscalationPass, on
// stage 1's p1 and stage 2's p2 (both in [0, 1]; stage 2 on fresh samples).
// It is valid only when stage 1 said EscalationContinue: ErrInvalidArgument
// when Decide(p1) rejects or passes, and for either p-value outside [0, 1],
// NaN included.
func (e Escalation) Decide2(p1, p2 float64) (EscalationDecision, error) {
	// libmcstat reads a NaN p2 as "stage 1 only"; here that is Decide's
	if math.IsNaN(p2) {
		return EscalationPass, invalid("escalation: stage 2's p-value is NaN")
	}
	return e.decide(p1, p2)
}
