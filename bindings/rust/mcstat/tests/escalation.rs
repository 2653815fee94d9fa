//! Escalation (the two-stage test instead of reruns): the design's numbers,
//! the decisions at the bounds, the refusals.  The struct's layout is
//! checked in mcstat-sys (its size at compile time, its offsets in tests).
use mcstat::*;

/// The next double above a positive x (f64::next_up needs Rust 1.86).
fn next_up(x: f64) -> f64 {
    assert!(x > 0.0 && x.is_finite());
    f64::from_bits(x.to_bits() + 1)
}

fn design() -> Escalation {
    Escalation::new(0.05, 0.5, 0.5).expect("a valid design")
}

fn assert_invalid<T: std::fmt::Debug>(r: Result<T>, what: &str) {
    match r {
        Err(e) => {
            assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{what}: {e}");
            assert_eq!(e.status(), sys::MCSTAT_EINVAL, "{what}");
        }
        Ok(v) => panic!("{what}: accepted, gave {v:?}"),
    }
}

#[test]
fn design_numbers() {
    let d = design();
    assert_eq!(d.alpha(), 0.05);
    assert_eq!(d.alpha1(), 0.025);
    assert_eq!(d.alpha0(), 0.5);
    let c = 0.025 / 20f64.ln();
    assert!((d.c() - c).abs() <= 1e-15 * c, "c = {} want {c}", d.c());
    assert!(d.c() <= d.alpha1());
    // the accessors are the C struct's fields
    let r = d.raw();
    assert_eq!((r.alpha, r.alpha1, r.alpha0, r.c), (d.alpha(), d.alpha1(), d.alpha0(), d.c()));
    // Copy: a design is plain data
    let e = d;
    assert_eq!(e, d);
    // alpha0 = 1: stage 1 never passes
    let all = Escalation::new(0.05, 0.5, 1.0).unwrap();
    assert_eq!(all.decide(1.0).unwrap(), EscalationDecision::Continue);
}

#[test]
fn stage_1_bounds() {
    let d = design();
    assert_eq!(d.decide(d.alpha1()).unwrap(), EscalationDecision::Reject);
    assert_eq!(d.decide(next_up(d.alpha1())).unwrap(), EscalationDecision::Continue);
    assert_eq!(d.decide(d.alpha0()).unwrap(), EscalationDecision::Continue);
    assert_eq!(d.decide(next_up(d.alpha0())).unwrap(), EscalationDecision::Pass);
    assert_eq!(d.decide(0.0).unwrap(), EscalationDecision::Reject);
    assert_eq!(d.decide(1.0).unwrap(), EscalationDecision::Pass);
}

#[test]
fn stage_2_bound() {
    let d = design();
    // p1 a power of two: p1 * (c / p1) is c exactly
    let p1 = 0.25;
    let p2 = d.c() / p1;
    assert_eq!(p1 * p2, d.c());
    assert_eq!(d.decide(p1).unwrap(), EscalationDecision::Continue);
    assert_eq!(d.decide2(p1, p2).unwrap(), EscalationDecision::Reject);
    assert_eq!(d.decide2(p1, next_up(p2)).unwrap(), EscalationDecision::Pass);
    assert_eq!(d.decide2(p1, 0.0).unwrap(), EscalationDecision::Reject);
    assert_eq!(d.decide2(p1, 1.0).unwrap(), EscalationDecision::Pass);
    // at the band's ends
    assert_eq!(d.decide2(d.alpha0(), 0.0).unwrap(), EscalationDecision::Reject);
    assert_eq!(d.decide2(next_up(d.alpha1()), 1.0).unwrap(), EscalationDecision::Pass);
}

#[test]
fn refused_designs() {
    let nan = f64::NAN;
    let bad = [
        (0.0, 0.5, 0.5),
        (1.0, 0.5, 0.5),
        (-0.1, 0.5, 0.5),
        (f64::INFINITY, 0.5, 0.5),
        (nan, 0.5, 0.5),
        (0.05, 0.0, 0.5),
        (0.05, 1.0, 0.5),
        (0.05, nan, 0.5),
        (0.05, 0.5, 0.025), // alpha0 = alpha1
        (0.05, 0.5, 0.01),  // alpha0 < alpha1
        (0.05, 0.5, 1.5),
        (0.05, 0.5, nan),
        (0.5, 0.5, 0.3), // c would exceed alpha1
    ];
    for (alpha, share1, alpha0) in bad {
        assert_invalid(Escalation::new(alpha, share1, alpha0), &format!("new({alpha}, {share1}, {alpha0})"));
    }
}

#[test]
fn refused_decisions() {
    let d = design();
    let nan = f64::NAN;
    for p1 in [nan, -0.1, 1.1, f64::INFINITY, -0.0 - 1e-300] {
        assert_invalid(d.decide(p1), &format!("decide({p1})"));
        assert_invalid(d.decide2(p1, 0.1), &format!("decide2({p1}, 0.1)"));
    }
    // stage 2's p-value outside [0, 1], NaN included
    for p2 in [nan, -0.1, 1.5, f64::INFINITY] {
        assert_invalid(d.decide2(0.25, p2), &format!("decide2(0.25, {p2})"));
    }
    // stage 2 after stage 1 passed or rejected
    assert_eq!(d.decide(0.9).unwrap(), EscalationDecision::Pass);
    assert_invalid(d.decide2(0.9, 0.1), "decide2 after a stage-1 pass");
    assert_invalid(d.decide2(next_up(d.alpha0()), 0.0), "decide2 just above alpha0");
    assert_eq!(d.decide(0.001).unwrap(), EscalationDecision::Reject);
    assert_invalid(d.decide2(0.001, 0.1), "decide2 after a stage-1 rejection");
}
