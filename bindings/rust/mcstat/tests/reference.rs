//! The safe API against the C tests' reference numbers (tests/data/ffi_ref.txt,
//! written by tools/refgen/make_ffi_ref.py from 50-digit mpmath values,
//! exact K-S fractions and R's printed blocks).
use mcstat::*;
use std::collections::HashMap;

fn f64_bits(t: &str) -> f64 {
    f64::from_bits(u64::from_str_radix(t, 16).expect("hex bits"))
}

fn text(t: &str) -> String {
    let bytes: Vec<u8> = (0..t.len()).step_by(2).map(|i| u8::from_str_radix(&t[i..i + 2], 16).unwrap()).collect();
    String::from_utf8(bytes).unwrap()
}

fn rel_err(got: f64, want: f64) -> f64 {
    if got == want || (got.is_nan() && want.is_nan()) {
        0.0
    } else if !got.is_finite() || !want.is_finite() {
        f64::INFINITY
    } else if want == 0.0 {
        got.abs()
    } else {
        ((got - want) / want).abs()
    }
}

fn alt(code: &str) -> Alternative {
    match code {
        "0" => Alternative::TwoSided,
        "1" => Alternative::Less,
        "2" => Alternative::Greater,
        name => name.parse().expect("alternative"),
    }
}

fn strip_decision(s: &str) -> String {
    s.split('\n').filter(|l| !l.starts_with("decision at alpha = ")).collect::<Vec<_>>().join("\n")
}

struct Ref {
    lines: Vec<Vec<String>>,
    data: HashMap<String, Vec<f64>>,
}

fn load() -> Ref {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../tests/data/ffi_ref.txt");
    let body = std::fs::read_to_string(path).expect("tests/data/ffi_ref.txt");
    let lines: Vec<Vec<String>> = body
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(' ').map(String::from).collect())
        .collect();
    let mut data = HashMap::new();
    for t in &lines {
        match t[0].as_str() {
            "data" => {
                let n: usize = t[2].parse().unwrap();
                data.insert(t[1].clone(), t[5..5 + n].iter().map(|v| f64_bits(v)).collect());
            }
            "formula" => {
                let n: u64 = t[2].parse().unwrap();
                let (base, mult, modulo) = (f64_bits(&t[3]), t[4].parse::<u64>().unwrap(), t[5].parse::<u64>().unwrap());
                let v = (0..n).map(|i| base + ((i * mult) % modulo) as f64 * (2f64).powi(-20)).collect();
                data.insert(t[1].clone(), v);
            }
            _ => {}
        }
    }
    assert!(data.len() >= 20);
    Ref { lines, data }
}

fn records<'a>(r: &'a Ref, kind: &'a str) -> impl Iterator<Item = &'a Vec<String>> + 'a {
    r.lines.iter().filter(move |t| t[0] == kind)
}

#[test]
fn four_tests_on_slices_and_accumulators() {
    let r = load();
    let mut count = 0;
    for t in records(&r, "case") {
        let (kind, x, y) = (t[1].as_str(), &r.data[&t[2]], r.data.get(&t[3]));
        let null = f64_bits(&t[4]);
        let a = alt(&t[5]);
        let want: Vec<f64> = t[6..].iter().map(|v| f64_bits(v)).collect();
        let alpha = want[0];
        // slices
        let on_slices = match kind {
            "T_1" => t_test_1(x, null, a, alpha),
            "T_2" => t_test_2(x, y.unwrap(), null, a, alpha),
            "VAR_1" => var_test_1(x, null, a, alpha),
            _ => var_test_2(x, y.unwrap(), null, a, alpha),
        }
        .unwrap();
        // accumulators: a third one value at a time, the rest as a slice, merged
        let mut mx = Moments::new();
        let cut = x.len() / 3;
        for &v in &x[..cut] {
            mx.add(v).unwrap();
        }
        let mut rest = Moments::new();
        rest.add_slice(&x[cut..]).unwrap();
        mx.merge(&rest).unwrap();
        let my = y.map(|y| {
            let mut m = Moments::new();
            m.add_slice(y).unwrap();
            m
        });
        let on_moments = match kind {
            "T_1" => t_test_1_moments(&mx, null, a, alpha),
            "T_2" => t_test_2_moments(&mx, my.as_ref().unwrap(), null, a, alpha),
            "VAR_1" => var_test_1_moments(&mx, null, a, alpha),
            _ => var_test_2_moments(&mx, my.as_ref().unwrap(), null, a, alpha),
        }
        .unwrap();
        for (how, res) in [("slices", on_slices), ("moments", on_moments)] {
            // fields that do not apply are left out, not NaN
            let df = res.df();
            assert_eq!(df.len(), if kind == "VAR_2" { 2 } else { 1 }, "{kind} df {df:?}");
            let (crit, ci) = (res.critical().unwrap(), res.conf_int().unwrap());
            let est = res.estimate();
            assert_eq!(est.len(), if kind == "T_2" { 2 } else { 1 }, "{kind} estimate {est:?}");
            assert_eq!(res.n().len(), if y.is_some() { 2 } else { 1 });
            let nan = f64::NAN;
            let got = [
                res.statistic(),
                df[0],
                *df.get(1).unwrap_or(&nan),
                res.p_value(),
                crit.0,
                crit.1,
                ci.0,
                ci.1,
                est[0],
                *est.get(1).unwrap_or(&nan),
            ];
            for (k, (g, w)) in got.iter().zip(&want[1..]).enumerate() {
                assert!(rel_err(*g, *w) <= 1e-9, "{kind} {} {} ({how}) field {k}: {g:e} vs {w:e}", t[2], t[3]);
            }
            assert_eq!(res.reject(), want[4] <= alpha, "{kind} {} reject", t[2]);
            assert_eq!(res.decision() == Decision::Equal, !res.reject());
        }
        count += 1;
    }
    assert_eq!(count, 38);
}

#[test]
fn moments_against_50_digit_references() {
    let r = load();
    for t in records(&r, "data").chain(records(&r, "formula")) {
        let x = &r.data[&t[1]];
        let (mean, var) = if t[0] == "data" { (f64_bits(&t[3]), f64_bits(&t[4])) } else { (f64_bits(&t[6]), f64_bits(&t[7])) };
        let mut m = Moments::new();
        m.add_slice(x).unwrap();
        assert_eq!(m.n(), x.len() as u64);
        assert!(rel_err(m.mean(), mean) <= 1e-15, "mean of {}", t[1]);
        assert!(rel_err(m.var(), var) <= 1e-13, "var of {}", t[1]);
    }
}

#[test]
fn moments_merge_bytes_and_errors() {
    let r = load();
    let x = &r.data["lew"];
    let mut a = Moments::new();
    let mut b = Moments::new();
    a.add_slice(&x[..77]).unwrap();
    b.add_slice(&x[77..]).unwrap();
    a.merge(&b).unwrap();
    let mut all = Moments::new();
    all.add_slice(x).unwrap();
    assert_eq!(a.n(), 200);
    assert!(rel_err(a.mean(), all.mean()) < 1e-15 && rel_err(a.var(), all.var()) < 1e-14);
    let bytes = a.to_bytes();
    let back = Moments::from_bytes(&bytes).unwrap();
    assert_eq!(back.to_bytes(), bytes);
    assert_eq!(back.mean(), a.mean());
    let mut bad = bytes;
    bad[40] ^= 0x10;
    assert_eq!(Moments::from_bytes(&bad).unwrap_err().kind(), ErrorKind::Corrupt);
    assert_eq!(Moments::from_bytes(&bytes[..50]).unwrap_err().kind(), ErrorKind::Corrupt);
    assert_eq!(a.add(f64::NAN).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(a.n(), 200); // unchanged
    let e = t_test_1(&[2.0, 2.0, 2.0], 1.0, Alternative::TwoSided, 0.05).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::DegenerateData);
    assert_eq!(e.status(), 4);
    assert!(!e.message().is_empty() && e.to_string().contains("status 4"));
    assert_eq!(t_test_1(&[1.0], 0.0, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(t_test_1(&[1.0, 2.0], 0.0, Alternative::TwoSided, 1.5).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert!("sideways".parse::<Alternative>().is_err());
    assert_eq!("two.sided".parse::<Alternative>().unwrap(), Alternative::TwoSided);
}

#[test]
fn distributions() {
    let r = load();
    let mut n = 0;
    for t in records(&r, "quantile") {
        let (p, d1, d2, upper, want) = (f64_bits(&t[2]), f64_bits(&t[3]), f64_bits(&t[4]), t[5] == "1", f64_bits(&t[6]));
        let got = match t[1].as_str() {
            "t" => dist::t_quantile(p, d1, upper),
            "c" => dist::chisq_quantile(p, d1, upper),
            _ => dist::f_quantile(p, d1, d2, upper),
        }
        .unwrap();
        assert!(rel_err(got, want) <= 1e-12, "{} quantile p={p:e} df={d1}: {got:e} vs {want:e}", t[1]);
        n += 1;
    }
    for t in records(&r, "logcdf") {
        let (x, d1, d2, upper, want) = (f64_bits(&t[2]), f64_bits(&t[3]), f64_bits(&t[4]), t[5] == "1", f64_bits(&t[6]));
        let (lp, p) = match t[1].as_str() {
            "t" => (dist::t_logcdf(x, d1, upper), dist::t_cdf(x, d1, upper)),
            "c" => (dist::chisq_logcdf(x, d1, upper), dist::chisq_cdf(x, d1, upper)),
            _ => (dist::f_logcdf(x, d1, d2, upper), dist::f_cdf(x, d1, d2, upper)),
        };
        let lp = lp.unwrap();
        let e = (lp - want).abs() / if want.abs() > 700.0 { want.abs() } else { 1.0 };
        assert!(e <= 1e-11, "{} logcdf x={x:e}: {lp:e} vs {want:e}", t[1]);
        if want > -700.0 {
            assert!(rel_err(p.unwrap(), want.exp()) <= 1e-11);
        }
        n += 1;
    }
    assert!(n > 400);
    assert_eq!(dist::t_cdf(f64::NAN, 3.0, false).unwrap_err().kind(), ErrorKind::InvalidArgument);
}

#[test]
fn ks_exact_against_exact_fractions_and_r() {
    let r = load();
    let blocks: HashMap<String, String> = records(&r, "ksblock").map(|t| (t[1].clone(), text(&t[2]))).collect();
    let mut n_blocks = 0;
    for t in records(&r, "ks") {
        let a = alt(&t[2]);
        let (stat, p_none, p_canner) = (f64_bits(&t[3]), f64_bits(&t[4]), f64_bits(&t[5]));
        let nx: usize = t[6].parse().unwrap();
        let x: Vec<f64> = t[7..7 + nx].iter().map(|v| f64_bits(v)).collect();
        let y: Vec<f64> = t[8 + nx..].iter().map(|v| f64_bits(v)).collect();
        let none = KsOptions { weight: KsWeight::None, method: Method::Exact, ..Default::default() };
        let res = ks_test_2(&x, &y, a, 0.05, &none).unwrap();
        assert_eq!(res.test(), Test::Ks2);
        assert_eq!(res.method(), Method::Exact);
        assert!((res.statistic() - stat).abs() <= 1e-13 * stat.abs().max(1.0), "ks {}", t[1]);
        assert!(rel_err(res.p_value(), p_none) <= 1e-12, "ks {} p {} vs {}", t[1], res.p_value(), p_none);
        assert_eq!(res.reject(), res.p_value() <= 0.05);
        let canner = KsOptions { method: Method::Exact, ..Default::default() };
        let rc = ks_test_2(&x, &y, a, 0.05, &canner).unwrap();
        assert!(rel_err(rc.p_value(), p_canner) <= 1e-12, "ks {} Canner p", t[1]);
        if let Some(b) = blocks.get(&t[1]) {
            assert_eq!(&strip_decision(&res.to_string()), b, "ks {} block", t[1]);
            n_blocks += 1;
        }
    }
    assert_eq!(n_blocks, 56);
}

#[test]
fn ks_simulated_with_a_shared_cache() {
    let r = load();
    let t = records(&r, "ks").nth(11).unwrap().clone();
    let nx: usize = t[6].parse().unwrap();
    let x: Vec<f64> = t[7..7 + nx].iter().map(|v| f64_bits(v)).collect();
    let y: Vec<f64> = t[8 + nx..].iter().map(|v| f64_bits(v)).collect();
    let p_canner = f64_bits(&t[5]);
    let cache = KsCache::new(16 << 20).unwrap();
    let o = KsOptions { method: Method::Simulate, n_sim: 4000, seed: 7, cache: Some(&cache), ..Default::default() };
    let a = ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &o).unwrap();
    let b = ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &o).unwrap();
    assert_eq!(a.method(), Method::Simulate);
    assert!(a.p_value_se() > 0.0);
    assert!((a.p_value() - p_canner).abs() < 5.0 * a.p_value_se() + 1e-3);
    assert_eq!(a.p_value(), b.p_value()); // same seed, from the cache
    let (hits, misses, entries) = cache.stats();
    assert!(hits >= 1 && misses >= 1 && entries >= 1, "{hits} {misses} {entries}");
    // asymptotic with Canner's weight has no limit law: an error, not a number
    let bad = KsOptions { method: Method::Asymptotic, ..Default::default() };
    assert_eq!(ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &bad).unwrap_err().kind(), ErrorKind::InvalidArgument);
}

#[test]
fn display_is_r_block() {
    let r = load();
    let mut n = 0;
    for t in records(&r, "block") {
        let nx: usize = t[8].parse().unwrap();
        let x: Vec<f64> = t[9..9 + nx].iter().map(|v| f64_bits(v)).collect();
        let rest = &t[9 + nx..];
        let y: Option<Vec<f64>> = if rest[0] == "-" { None } else { Some(rest[1..].iter().map(|v| f64_bits(v)).collect()) };
        let (null, a, alpha) = (f64_bits(&t[4]), alt(&t[5]), f64_bits(&t[6]));
        let res = match (t[1].as_str(), &y) {
            ("t_test", None) => t_test_1(&x, null, a, alpha),
            ("t_test", Some(y)) => t_test_2(&x, y, null, a, alpha),
            (_, Some(y)) => var_test_2(&x, y, null, a, alpha),
            _ => unreachable!(),
        }
        .unwrap();
        let yname = if t[3] == "-" { "y" } else { t[3].as_str() };
        let got = res.format(&t[2], yname);
        assert_eq!(strip_decision(&got), text(&t[7]), "block {} {} {}", t[1], t[2], t[5]);
        let decision = match res.decision() {
            Decision::Less => "less",
            Decision::Equal => "equal",
            Decision::Greater => "greater",
        };
        assert!(got.ends_with(&format!(": {decision}\n\n")), "{got}");
        n += 1;
    }
    assert_eq!(n, 19);
    let one = t_test_1(&[1.0, 2.0, 4.0], 0.0, Alternative::TwoSided, 0.05).unwrap();
    assert!(one.to_string().contains("data:  x\n"));
}
