//! Sequential, anytime-valid tests (SequentialTest) on deterministic data:
//! decisions, holds, errors, and the numbers of the C library itself.
use mcstat::*;
use std::f64::consts::PI;
use std::mem::MaybeUninit;

/// Deterministic uniform numbers in [0, 1) (xorshift; fixed seeds).
struct Rng(u64);
impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.next(), self.next());
        (-2.0 * (1.0 - u).ln()).sqrt() * (2.0 * PI * v).cos()
    }
    fn normals(&mut self, n: usize, mean: f64) -> Vec<f64> {
        (0..n).map(|_| mean + self.normal()).collect()
    }
    /// 99% exact zeros, 1% exponential values of mean 100 (mean 1).
    fn sparse(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| if self.next() < 0.01 { -100.0 * (1.0 - self.next()).ln() } else { 0.0 }).collect()
    }
}

/// outcome, hold, looks, n_decided, z, log_e, n_gate
type SeqFields = (SeqOutcome, SeqHold, u64, Option<u64>, Option<f64>, Option<f64>, Option<f64>);

fn sequential(d: &Details) -> SeqFields {
    match *d {
        Details::Sequential { outcome, hold, looks, n_decided, z, log_e, n_gate, .. } => {
            (outcome, hold, looks, n_decided, z, log_e, n_gate)
        }
        ref other => panic!("not a sequential result: {other:?}"),
    }
}

#[test]
fn a_shifted_mean_decides_greater() {
    let mut rng = Rng::new(1);
    let mut t = SequentialTest::mean(0.0, &SeqOptions::default()).unwrap();
    assert_eq!((t.kind(), t.outcome(), t.looks()), (SeqKind::Mean, SeqOutcome::Continue, 0));
    while !t.is_decided() && t.n() < 5000 {
        t.push(&rng.normals(100, 0.5)).unwrap();
    }
    assert_eq!(t.outcome(), SeqOutcome::Greater);
    assert_eq!(t.outcome().decision(), Some(Decision::Greater));
    let n = t.n_decided().unwrap();
    assert!((200..=5000).contains(&n), "decided at n = {n}");
    let r = t.result();
    assert_eq!((r.test(), r.method(), r.alternative()), (Test::SeqMean1, Method::Asymptotic, Alternative::TwoSided));
    assert!(r.reject() && r.decision() == Decision::Greater);
    assert!(r.p_value() <= 0.05);
    let (lo, hi) = r.conf_int().unwrap();
    assert!(lo > 0.0 && hi > lo && hi.is_finite(), "sequence ({lo}, {hi})");
    assert_eq!(r.df(), &[] as &[f64]);
    assert_eq!(r.n(), &[n]);
    let (outcome, hold, looks, n_decided, z, log_e, n_gate) = sequential(&r.details());
    assert_eq!((outcome, hold.is_empty(), looks, n_decided, n_gate), (SeqOutcome::Greater, true, n / 100, Some(n), None));
    assert!(z.unwrap() > 0.0 && log_e.unwrap() >= -(0.05f64.ln()));
    // a decision is final; more data keep narrowing the sequence
    t.push(&rng.normals(100, 0.5)).unwrap();
    assert_eq!((t.outcome(), t.n_decided()), (SeqOutcome::Greater, Some(n)));
    assert_eq!(t.finish().unwrap().decision(), Decision::Greater);
    // Display is the C library's block
    let text = t.to_string();
    assert!(text.contains("Anytime-valid sequential test of the mean"), "{text}");
    assert!(text.contains(&format!("decision at alpha = 0.05: greater (at n = {n})")), "{text}");
    assert_eq!(text, t.result().format("x", "y"));
}

#[test]
fn true_null_continues() {
    let mut rng = Rng::new(2);
    let mut t = SequentialTest::mean(0.0, &SeqOptions::default()).unwrap();
    for _ in 0..50 {
        t.push(&rng.normals(100, 0.0)).unwrap();
    }
    assert_eq!((t.outcome(), t.looks(), t.n()), (SeqOutcome::Continue, 50, 5000));
    assert!(t.hold().is_empty());
    let r = t.finish().unwrap();
    assert!(!r.reject() && r.p_value() > 0.05);
    let (lo, hi) = r.conf_int().unwrap();
    assert!(lo < 0.0 && hi > 0.0);
    assert!(t.to_string().contains("decision at alpha = 0.05: continue"));
}

#[test]
fn an_all_zero_batch_holds() {
    let mut t = SequentialTest::mean(1.0, &SeqOptions::default()).unwrap();
    t.push(&[0.0; 1000]).unwrap();
    assert_eq!(t.outcome(), SeqOutcome::Continue);
    assert!(t.hold().degenerate() && !t.hold().few() && !t.hold().kurtosis());
    let r = t.result();
    assert_eq!(r.p_value(), 1.0);
    assert_eq!(r.conf_int(), Some((f64::NEG_INFINITY, f64::INFINITY)));
    assert_eq!(r.std_error(), None);
    let (outcome, hold, looks, n_decided, z, log_e, n_gate) = sequential(&r.details());
    assert_eq!((outcome, hold.bits(), looks, n_decided, z, log_e, n_gate), (SeqOutcome::Continue, 2, 1, None, None, None, None));
    // held for want of spread, not for the tails: finish says "not decided"
    assert!(!t.finish().unwrap().reject());
}

#[test]
fn mostly_zeros_hold_for_the_tails_and_finish_says_heavy_tail() {
    let mut rng = Rng::new(3);
    let mut t = SequentialTest::mean(0.0, &SeqOptions::default()).unwrap();
    let mut frame = Stream::new();
    for _ in 0..6 {
        frame.add_slice(&rng.sparse(100));
        t.push_stream(&frame).unwrap();
        frame.clear();
    }
    assert_eq!((t.n(), t.looks()), (600, 6));
    let hold = t.hold();
    assert!(hold.kurtosis() && !hold.degenerate() && !hold.few(), "hold bits {}", hold.bits());
    assert_eq!(t.outcome(), SeqOutcome::Continue);
    let r = t.result();
    let (_, _, _, _, _, log_e, n_gate) = sequential(&r.details());
    assert_eq!(log_e, None);
    assert!(n_gate.unwrap() > 600.0);
    let e = t.finish().unwrap_err();
    assert_eq!((e.kind(), e.status()), (ErrorKind::HeavyTail, sys::MCSTAT_EHEAVYTAIL));
    assert!(matches!(e, Error::HeavyTail(_)));
    assert!(e.message().contains("600 values"), "{e}");
    assert!(t.to_string().contains("continue"));
}

#[test]
fn bad_arguments_are_errors() {
    let d = SeqOptions::default();
    let bad = |o: SeqOptions, kind: SeqKind, null: f64, word: &str| {
        let e = SequentialTest::new(kind, null, &o).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument);
        assert!(e.message().contains(word), "{word}: {e}");
    };
    bad(SeqOptions { alpha: 1.0, ..d }, SeqKind::Mean, 0.0, "alpha");
    bad(SeqOptions { alpha: f64::NAN, ..d }, SeqKind::Mean, 0.0, "alpha");
    bad(SeqOptions { eps: -1.0, ..d }, SeqKind::Mean, 0.0, "eps");
    bad(SeqOptions { eps: 0.1, ..d }, SeqKind::Var, 1.0, "eps");
    bad(SeqOptions { eps: 0.1, alternative: Alternative::Less, ..d }, SeqKind::Mean, 0.0, "eps");
    bad(SeqOptions { t_opt: 0.0, ..d }, SeqKind::Mean, 0.0, "t_opt");
    bad(SeqOptions { kurtosis_gate: -1.0, ..d }, SeqKind::Mean, 0.0, "kurtosis_gate");
    bad(SeqOptions { var_ucb_z: f64::INFINITY, ..d }, SeqKind::Mean, 0.0, "var_ucb_z");
    bad(SeqOptions { min_n: 1, ..d }, SeqKind::Mean, 0.0, "min_n");
    bad(d, SeqKind::Var, 0.0, "null_value");
    bad(d, SeqKind::Mean2, f64::NAN, "null_value");

    let mut t = SequentialTest::mean(0.0, &d).unwrap();
    t.push(&[1.0, 2.0]).unwrap();
    let before = *t.raw();
    assert_eq!(t.push(&[1.0, f64::NAN]).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(t.push2(&[1.0], &[2.0]).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(t.push_moments2(&Moments::new(), &Moments::new()).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let mut s = Stream::new();
    s.add(f64::INFINITY);
    assert_eq!(t.push_stream(&s).unwrap_err().kind(), ErrorKind::NonFinite);
    // an error leaves the test as it was
    assert_eq!((t.looks(), t.n(), t.raw().x.mean), (before.looks, before.x.n, before.x.mean));
    let mut u = SequentialTest::var2(1.0, &d).unwrap();
    let e = u.push(&[1.0]).unwrap_err();
    assert!(e.message().contains("one-sample"), "{e}");
    assert_eq!(u.push_stream(&s).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(u.push_moments(&Moments::new()).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(Error::from_status(sys::MCSTAT_EHEAVYTAIL).kind(), ErrorKind::HeavyTail);
}

#[test]
fn two_samples_and_variances() {
    let mut rng = Rng::new(4);
    let opt = SeqOptions { alternative: Alternative::Less, ..SeqOptions::default() };
    // mean(x) - mean(y) = -0.5 against 0, one-sided "less"; arrays and
    // accumulators give the same looks
    let mut a = SequentialTest::mean2(0.0, &opt).unwrap();
    let mut b = a;
    while !a.is_decided() && a.n() < 10_000 {
        let (x, y) = (rng.normals(100, 0.0), rng.normals(150, 0.5));
        a.push2(&x, &y).unwrap();
        let (mut mx, mut my) = (Moments::new(), Moments::new());
        mx.add_slice(&x).unwrap();
        my.add_slice(&y).unwrap();
        b.push_moments2(&mx, &my).unwrap();
    }
    assert_eq!(a.outcome(), SeqOutcome::Less);
    assert_eq!((a.n_y() * 2, a.result().n()), (a.n() * 3, &[a.n(), a.n_y()][..]));
    assert_eq!(a.result().p_value().to_bits(), b.result().p_value().to_bits());
    assert_eq!(a.result().test(), Test::SeqMean2);

    // variance 4 against 1: "greater"; the ratio of equal variances continues
    let mut v = SequentialTest::var(1.0, &SeqOptions::default()).unwrap();
    let mut r = SequentialTest::var2(1.0, &SeqOptions::default()).unwrap();
    for _ in 0..30 {
        let x: Vec<f64> = rng.normals(100, 0.0).iter().map(|z| 2.0 * z).collect();
        v.push(&x).unwrap();
        r.push2(&rng.normals(100, 0.0), &rng.normals(100, 0.0)).unwrap();
    }
    assert_eq!((v.outcome(), v.result().test()), (SeqOutcome::Greater, Test::SeqVar1));
    assert_eq!((r.outcome(), r.result().test()), (SeqOutcome::Continue, Test::SeqVar2));
    assert_eq!(r.result().estimate().len(), 1);

    // equivalence: a mean within 0.2 of 0 shown "equal"
    let mut e = SequentialTest::mean(0.0, &SeqOptions { eps: 0.2, ..SeqOptions::default() }).unwrap();
    while !e.is_decided() && e.n() < 100_000 {
        e.push(&rng.normals(500, 0.0)).unwrap();
    }
    assert_eq!(e.outcome(), SeqOutcome::Equal);
    assert!(!e.result().reject());
    let eps = match e.result().details() {
        Details::Sequential { eps, .. } => eps,
        _ => unreachable!(),
    };
    assert_eq!(eps, Some(0.2));
    assert_eq!(SeqKind::Var2.to_string(), "var2");
    assert_eq!(SeqOutcome::Continue.to_string(), "continue");
    assert_eq!(SeqOutcome::Equal.to_string(), "equal");
}

/// The safe type is the C library's test: the same calls through mcstat-sys
/// give the same bits.
#[test]
fn values_equal_the_c_library() {
    let mut rng = Rng::new(5);
    let opt = SeqOptions { t_opt: 2000.0, kurtosis_gate: 5.0, ..SeqOptions::default() };
    let mut t = SequentialTest::mean(0.1, &opt).unwrap();
    let mut raw = unsafe {
        let mut o = MaybeUninit::<sys::mcstat_seq_options>::zeroed().assume_init();
        assert_eq!(sys::mcstat_seq_options_init_size(&mut o, std::mem::size_of::<sys::mcstat_seq_options>()), 0);
        o.t_opt = 2000.0;
        o.kurtosis_gate = 5.0;
        let mut s = MaybeUninit::<sys::mcstat_seq>::zeroed().assume_init();
        assert_eq!(sys::mcstat_seq_init(&mut s, sys::MCSTAT_SEQ_MEAN_1, 0.1, &o), 0);
        s
    };
    for _ in 0..12 {
        let x = rng.normals(100, 0.3);
        t.push(&x).unwrap();
        assert_eq!(unsafe { sys::mcstat_seq_push_array(&mut raw, x.as_ptr(), x.len()) }, 0);
        let mut c = unsafe { MaybeUninit::<sys::mcstat_result>::zeroed().assume_init() };
        assert_eq!(unsafe { sys::mcstat_seq_result(&raw, &mut c) }, 0);
        let r = t.result();
        let ours = r.raw();
        for (a, b) in [
            (ours.statistic, c.statistic),
            (ours.p_value, c.p_value),
            (ours.conf_int[0], c.conf_int[0]),
            (ours.conf_int[1], c.conf_int[1]),
            (ours.critical[1], c.critical[1]),
            (ours.std_error, c.std_error),
            (ours.seq().seq_log_e, c.seq().seq_log_e),
            (ours.seq().seq_log_e_max, c.seq().seq_log_e_max),
        ] {
            assert_eq!(a.to_bits(), b.to_bits());
        }
        assert_eq!((ours.decision, ours.ints_seq().seq_state), (c.decision, c.ints_seq().seq_state));
        let (outcome, hold, looks, _, z, log_e, _) = sequential(&r.details());
        let want = match (c.ints_seq().seq_state, c.decision) {
            (sys::MCSTAT_SEQ_CONTINUE, _) => SeqOutcome::Continue,
            (_, sys::MCSTAT_DECISION_LESS) => SeqOutcome::Less,
            (_, sys::MCSTAT_DECISION_EQUAL) => SeqOutcome::Equal,
            _ => SeqOutcome::Greater,
        };
        assert_eq!(outcome, want);
        assert_eq!((hold.bits(), looks), (c.ints_seq().seq_hold as u32, c.seq().seq_looks as u64));
        assert_eq!(z.map(f64::to_bits), if c.statistic.is_nan() { None } else { Some(c.statistic.to_bits()) });
        assert_eq!(log_e, if c.seq().seq_log_e.is_finite() { Some(c.seq().seq_log_e) } else { None });
        assert_eq!(r.critical(), Some((c.critical[0], c.critical[1])));
    }
    assert_eq!(t.raw().looks, raw.looks);
}
