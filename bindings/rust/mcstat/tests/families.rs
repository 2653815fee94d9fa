//! Every family of the safe API against reference numbers (R's, in
//! tests/data, the files the C tests read) and with bad input (errors,
//! never panics).
use mcstat::check::{check_bsdf, check_emitter, check_warp, check_work_size, CheckModel, CheckOptions, Domain, Route, RouteSet, RouteState, Samples, WeightConvention};
use mcstat::diag::{self, DiagOptions};
use mcstat::gof::{self, Expected, GofOptions};
use mcstat::p_adjust::{p_adjust_in_place, PAdjustMethod, Workspace};
use mcstat::power::{Power, PowerTest};
use mcstat::rows::{self, Matrix, RowFlags};
use mcstat::*;
use std::f64::consts::PI;

fn data_path(name: &str) -> String {
    format!("{}/../../../tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn read(name: &str) -> String {
    std::fs::read_to_string(data_path(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn rel_err(got: f64, want: f64) -> f64 {
    if got == want {
        0.0
    } else if !got.is_finite() || !want.is_finite() {
        f64::INFINITY
    } else if want == 0.0 {
        got.abs()
    } else {
        ((got - want) / want).abs()
    }
}

/// C99 hex floats as R's sprintf("%a") writes them: [-]0x1.hhhp[+-]d.
fn hex_float(s: &str) -> f64 {
    let (neg, t) = match s.strip_prefix('-') {
        Some(t) => (true, t),
        None => (false, s),
    };
    let t = t.strip_prefix("0x").unwrap_or_else(|| panic!("not a hex float: {s}"));
    let (mant, exp) = t.split_once('p').unwrap_or((t, "0"));
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    let mut v = u64::from_str_radix(int, 16).unwrap() as f64;
    let mut scale = 1.0 / 16.0;
    for c in frac.chars() {
        v += c.to_digit(16).unwrap() as f64 * scale;
        scale /= 16.0;
    }
    let v = v * 2f64.powi(exp.parse::<i32>().unwrap());
    if neg {
        -v
    } else {
        v
    }
}

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
    fn vec(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.normal()).collect()
    }
}

// ---- errors, layout, names -----------------------------------------------------

#[test]
fn errors_carry_the_status_and_message() {
    let e = t_test_1(&[2.0, 2.0, 2.0], 1.0, Alternative::TwoSided, 0.05).unwrap_err();
    assert!(matches!(e, Error::DegenerateData(_)));
    assert_eq!((e.status(), e.kind()), (4, ErrorKind::DegenerateData));
    assert!(!e.message().is_empty());
    assert!(e.to_string().ends_with("(mcstat status 4)"));
    let boxed: Box<dyn std::error::Error> = Box::new(e.clone());
    assert_eq!(boxed.to_string(), e.to_string());
    assert_eq!(Error::from_status(99).kind(), ErrorKind::Other(99));
    assert_eq!(Error::from_status(sys::MCSTAT_ECALLBACK).kind(), ErrorKind::Callback);
    check_layout().unwrap();
    assert_eq!(version_number(), 100 * sys::MCSTAT_VERSION_MINOR + 10000 * sys::MCSTAT_VERSION_MAJOR + sys::MCSTAT_VERSION_PATCH);
    assert_eq!(Alternative::Less.to_string(), "less");
    assert_eq!("two.sided".parse::<Alternative>().unwrap(), Alternative::TwoSided);
    assert_eq!("sideways".parse::<Alternative>().unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!("less\0".parse::<Alternative>().unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(Decision::Greater.to_string(), "greater");
    // GSL: once turned off, the handler is no longer GSL's default
    gsl_handler_off_if_default();
    assert!(!gsl_handler_off_if_default());
    gsl_handler_off();
}

#[test]
fn welch_has_one_df_and_f_two_and_ks_none() {
    let mut rng = Rng::new(1);
    let (x, y) = (rng.vec(40), rng.vec(30));
    let w = t_test_2(&x, &y, 0.0, Alternative::TwoSided, 0.05).unwrap();
    assert_eq!(w.test(), Test::T2);
    assert_eq!(w.df().len(), 1);
    assert!(w.df()[0] > 29.0 && w.df()[0] < 68.0);
    assert!(w.std_error().is_some() && w.conf_int().is_some());
    assert_eq!(w.n(), &[40, 30]);
    assert_eq!(w.details(), Details::None);
    let f = var_test_2(&x, &y, 1.0, Alternative::Greater, 0.05).unwrap();
    assert_eq!(f.df(), &[39.0, 29.0]);
    assert_eq!(f.std_error(), None);
    assert_eq!(f.estimate().len(), 1);
    let (lo, hi) = f.conf_int().unwrap();
    assert!(lo > 0.0 && hi == f64::INFINITY); // one-sided: the open end is infinite, not missing
    let k = ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &KsOptions::default()).unwrap();
    assert!(k.df().is_empty() && k.estimate().is_empty());
    assert_eq!((k.conf_int(), k.null_value(), k.std_error()), (None, None, None));
    assert!(matches!(k.details(), Details::Ks { weight: KsWeight::Canner, n_sim: 0, .. }));
    let no_crit = KsOptions { critical: false, ..Default::default() };
    assert_eq!(ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &no_crit).unwrap().critical(), None);
    let sim = KsOptions { method: Method::Simulate, n_sim: 500, seed: 2, ..Default::default() };
    let s = ks_test_2(&x, &y, Alternative::Less, 0.05, &sim).unwrap();
    assert!(matches!(s.details(), Details::Ks { n_sim: 500, .. }));
    let bad = KsOptions { method: Method::Analytic, ..Default::default() };
    assert_eq!(ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &bad).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let bad = KsOptions { threads: 0, ..Default::default() };
    assert_eq!(ks_test_2(&x, &y, Alternative::TwoSided, 0.05, &bad).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(ks_test_2(&x, &[], Alternative::TwoSided, 0.05, &KsOptions::default()).unwrap_err().kind(), ErrorKind::TooFewObservations);
}

// ---- equivalence ------------------------------------------------------------------

#[test]
fn equivalence_against_r() {
    let body = read("equivalence_ref.tsv");
    let mut cases = 0;
    for line in body.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split('\t').collect();
        assert_eq!(f.len(), 15);
        let x: Vec<f64> = f[0].split(',').map(hex_float).collect();
        let y: Option<Vec<f64>> = if f[1] == "-" { None } else { Some(f[1].split(',').map(hex_float).collect()) };
        let v: Vec<f64> = f[2..].iter().map(|s| if *s == "NA" { f64::NAN } else { s.parse().unwrap() }).collect();
        let (mu0, lower, upper, alpha) = (v[0], v[1], v[2], v[3]);
        let (tl, pl, tu, pu, df, ci0, ci1) = (v[4], v[5], v[6], v[7], v[8], v[9], v[10]);
        let mut mx = Moments::new();
        mx.add_slice(&x).unwrap();
        let (r, rm) = match &y {
            None => (
                equivalence_test_1(&x, mu0, lower, upper, alpha).unwrap(),
                equivalence_test_1_moments(&mx, mu0, lower, upper, alpha).unwrap(),
            ),
            Some(y) => {
                let mut my = Moments::new();
                my.add_slice(y).unwrap();
                (
                    equivalence_test_2(&x, y, lower, upper, alpha).unwrap(),
                    equivalence_test_2_moments(&mx, &my, lower, upper, alpha).unwrap(),
                )
            }
        };
        assert_eq!(r.test(), if y.is_some() { Test::Equiv2 } else { Test::Equiv1 });
        assert_eq!(r.p_value().to_bits(), rm.p_value().to_bits());
        let (t_lower, p_lower, t_upper, p_upper, bl, bu) = match r.details() {
            Details::Tost { t_lower, p_lower, t_upper, p_upper, lower, upper } => (t_lower, p_lower, t_upper, p_upper, lower, upper),
            d => panic!("no TOST details: {d:?}"),
        };
        // R forms mean(x) - mu in double: its t loses digits at an offset
        // (the C test's tolerance, the same condition number)
        let cond = 1.0 + r.estimate()[0].abs() / (r.std_error().unwrap() * tl.abs().min(tu.abs()));
        let ttol = 1e-11 + 8.0 * 2.2e-16 * cond;
        let ptol = 1e-9 + 30.0 * ttol;
        assert!(rel_err(t_lower, tl) <= ttol && rel_err(t_upper, tu) <= ttol, "case {cases}: t");
        assert!(rel_err(p_lower, pl) <= ptol && rel_err(p_upper, pu) <= ptol, "case {cases}: p");
        assert!(rel_err(r.p_value(), pl.max(pu)) <= ptol);
        assert!(rel_err(r.df()[0], df) <= 1e-12 && r.df().len() == 1);
        let (c0, c1) = r.conf_int().unwrap();
        let ctol = 1e-10 * (ci1 - ci0) + 4.0 * 2.2e-16 * r.estimate()[0].abs();
        assert!((c0 - ci0).abs() <= ctol && (c1 - ci1).abs() <= ctol, "case {cases}: interval");
        assert!(rel_err(bl, mu0 + lower) <= 1e-15 && rel_err(bu, mu0 + upper) <= 1e-15);
        assert_eq!(r.reject(), pl.max(pu) <= alpha);
        assert!(r.format("x", "y").contains("equivalen"));
        cases += 1;
    }
    assert!(cases >= 20, "{cases} cases");
    let x = [1.0, 2.0, 3.0, 4.0];
    assert_eq!(equivalence_test_1(&x, 2.5, 1.0, -1.0, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(equivalence_test_1(&x, 2.5, -1.0, 1.0, 0.6).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(equivalence_test_2(&x, &[1.0], -1.0, 1.0, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
}

// ---- rows, accumulator arrays, stream ------------------------------------------

#[test]
fn rows_are_the_single_tests_bit_for_bit() {
    let (rows, n) = (6, 25);
    let mut rng = Rng::new(3);
    let x = rng.vec(rows * n);
    let y: Vec<f64> = rng.vec(rows * n).iter().map(|v| 0.3 + 2.0 * v).collect();
    let (mx, my) = (Matrix::new(&x, rows, n).unwrap(), Matrix::new(&y, rows, n).unwrap());
    let a = Alternative::TwoSided;
    let all = [
        rows::t_test_1_matrix(&mx, 0.1, a, 0.05, RowFlags::default()).unwrap(),
        rows::t_test_2_matrix(&mx, &my, 0.0, a, 0.05, RowFlags::default()).unwrap(),
        rows::var_test_1_matrix(&mx, 1.0, a, 0.05, RowFlags::default()).unwrap(),
        rows::var_test_2_matrix(&mx, &my, 1.0, a, 0.05, RowFlags::default()).unwrap(),
    ];
    let mut accx = MomentsArray::new(rows);
    let mut accy = MomentsArray::new(rows);
    assert!(accx.add(&mx, false).unwrap().all_ok());
    assert!(accy.add(&my, false).unwrap().all_ok());
    let on_moments = [
        rows::t_test_1_moments_rows(&accx, 0.1, a, 0.05, RowFlags::default()).unwrap(),
        rows::t_test_2_moments_rows(&accx, &accy, 0.0, a, 0.05, RowFlags::default()).unwrap(),
        rows::var_test_1_moments_rows(&accx, 1.0, a, 0.05, RowFlags::default()).unwrap(),
        rows::var_test_2_moments_rows(&accx, &accy, 1.0, a, 0.05, RowFlags::default()).unwrap(),
    ];
    for i in 0..rows {
        let (xi, yi) = (&x[i * n..(i + 1) * n], &y[i * n..(i + 1) * n]);
        let single = [
            t_test_1(xi, 0.1, a, 0.05).unwrap(),
            t_test_2(xi, yi, 0.0, a, 0.05).unwrap(),
            var_test_1(xi, 1.0, a, 0.05).unwrap(),
            var_test_2(xi, yi, 1.0, a, 0.05).unwrap(),
        ];
        let single_m = [
            t_test_1_moments(&accx[i], 0.1, a, 0.05).unwrap(),
            t_test_2_moments(&accx[i], &accy[i], 0.0, a, 0.05).unwrap(),
            var_test_1_moments(&accx[i], 1.0, a, 0.05).unwrap(),
            var_test_2_moments(&accx[i], &accy[i], 1.0, a, 0.05).unwrap(),
        ];
        for k in 0..4 {
            let r = all[k].get(i).unwrap();
            assert_eq!(r.p_value().to_bits(), single[k].p_value().to_bits(), "test {k} row {i}");
            assert_eq!(r.conf_int(), single[k].conf_int());
            let m = on_moments[k].get(i).unwrap();
            assert_eq!(m.p_value().to_bits(), single_m[k].p_value().to_bits(), "moments test {k} row {i}");
            assert!(rel_err(m.p_value(), r.p_value()) < 1e-12);
        }
    }
    assert_eq!(all[0].p_values().len(), rows);
    // no intervals: None, not NaN; the decision stays
    let cheap = rows::t_test_1_matrix(&mx, 0.1, a, 0.05, RowFlags { no_intervals: true, ..Default::default() }).unwrap();
    let r = cheap.get(0).unwrap();
    assert_eq!((r.conf_int(), r.critical()), (None, None));
    assert_eq!(r.p_value(), all[0].get(0).unwrap().p_value());
    // a stride: every other row of x as a 3-row matrix
    let every_other = Matrix::with_stride(&x, 3, n, 2 * n).unwrap();
    let eo = rows::t_test_1_matrix(&every_other, 0.1, a, 0.05, RowFlags::default()).unwrap();
    assert_eq!(eo.get(2).unwrap().p_value(), all[0].get(4).unwrap().p_value());
}

#[test]
fn rows_report_failures_per_row_and_refuse_bad_shapes() {
    let (rows, n) = (4, 10);
    let mut x = Rng::new(4).vec(rows * n);
    x[2 * n + 3] = f64::NAN;
    for v in &mut x[3 * n..4 * n] {
        *v = 5.0; // constant row
    }
    let m = Matrix::new(&x, rows, n).unwrap();
    let r = rows::t_test_1_matrix(&m, 0.0, Alternative::TwoSided, 0.05, RowFlags::default()).unwrap();
    assert!(r.get(0).is_ok() && r.get(1).is_ok());
    assert_eq!(r.get(2).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(r.get(3).unwrap_err().kind(), ErrorKind::DegenerateData);
    assert!(!r.statuses().all_ok());
    assert_eq!(r.statuses().failed().iter().map(|f| f.0).collect::<Vec<_>>(), vec![2, 3]);
    let p = r.p_values();
    assert!(p[2].is_nan() && !p[0].is_nan());
    assert_eq!(r.iter().filter(|r| r.is_ok()).count(), 2);
    // omit NaN: row 2 is tested on its 9 values
    let o = rows::t_test_1_matrix(&m, 0.0, Alternative::TwoSided, 0.05, RowFlags { omit_nan: true, ..Default::default() }).unwrap();
    let mut nine = x[2 * n..3 * n].to_vec();
    nine.retain(|v| !v.is_nan());
    assert_eq!(o.get(2).unwrap().p_value(), t_test_1(&nine, 0.0, Alternative::TwoSided, 0.05).unwrap().p_value());
    // whole-call errors: shapes, alpha, flags that do not apply
    assert_eq!(Matrix::new(&x, rows + 1, n).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(Matrix::with_stride(&x, 2, n, usize::MAX).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let m3 = Matrix::new(&x[..3 * n], 3, n).unwrap();
    assert_eq!(rows::t_test_2_matrix(&m, &m3, 0.0, Alternative::TwoSided, 0.05, RowFlags::default()).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let bad_alpha = rows::t_test_1_matrix(&m, 0.0, Alternative::TwoSided, 2.0, RowFlags::default());
    match bad_alpha {
        Err(e) => assert_eq!(e.kind(), ErrorKind::InvalidArgument),
        // every row fails: the clean ones for alpha, the others for their data
        Ok(r) => {
            assert!(r.iter().all(|r| r.is_err()));
            assert_eq!(r.get(0).unwrap_err().kind(), ErrorKind::InvalidArgument);
        }
    }
    let acc = MomentsArray::new(rows);
    let e = rows::t_test_1_moments_rows(&acc, 0.0, Alternative::TwoSided, 0.05, RowFlags { omit_nan: true, ..Default::default() });
    assert_eq!(e.unwrap_err().kind(), ErrorKind::InvalidArgument);
    let r = rows::t_test_1_moments_rows(&acc, 0.0, Alternative::TwoSided, 0.05, RowFlags::default()).unwrap();
    assert_eq!(r.get(0).unwrap_err().kind(), ErrorKind::TooFewObservations);
    let empty = rows::t_test_1_matrix(&Matrix::new(&[], 0, 5).unwrap(), 0.0, Alternative::TwoSided, 0.05, RowFlags::default()).unwrap();
    assert!(empty.is_empty());
}

#[test]
fn accumulator_arrays_add_merge_and_serialize() {
    let (rows, k) = (5, 7);
    let mut rng = Rng::new(5);
    // two batches of a pixel-major stack of k images
    let a = rng.vec(rows * k);
    let b = rng.vec(rows * k);
    let mut one = MomentsArray::new(rows);
    one.add(&Matrix::new(&a, rows, k).unwrap(), false).unwrap();
    one.add(&Matrix::new(&b, rows, k).unwrap(), false).unwrap();
    let mut other = MomentsArray::new(rows);
    other.add(&Matrix::new(&b, rows, k).unwrap(), false).unwrap();
    let mut merged = MomentsArray::new(rows);
    merged.add(&Matrix::new(&a, rows, k).unwrap(), false).unwrap();
    merged.merge(&other).unwrap();
    for i in 0..rows {
        // pushing A then B on one machine is bit for bit A and B merged
        assert_eq!(one[i].mean().to_bits(), merged[i].mean().to_bits());
        assert_eq!(one[i].var().to_bits(), merged[i].var().to_bits());
        let mut direct = Moments::new();
        direct.add_slice(&a[i * k..(i + 1) * k]).unwrap();
        direct.add_slice(&b[i * k..(i + 1) * k]).unwrap();
        assert!(rel_err(direct.mean(), one[i].mean()) < 1e-15 && rel_err(direct.var(), one[i].var()) < 1e-13);
        assert_eq!(one[i].n(), 2 * k as u64);
    }
    let bytes = one.to_bytes();
    assert_eq!(bytes.len(), rows * 96);
    let back = MomentsArray::from_bytes(&bytes).unwrap();
    assert_eq!(back.to_bytes(), bytes);
    let mut bad = bytes.clone();
    bad[96 * 3 + 40] ^= 1;
    assert_eq!(MomentsArray::from_bytes(&bad).unwrap_err().kind(), ErrorKind::Corrupt);
    assert_eq!(MomentsArray::from_bytes(&bytes[..100]).unwrap_err().kind(), ErrorKind::Corrupt);
    assert!(MomentsArray::from_bytes(&[]).unwrap().is_empty());
    // a failing row is left unchanged, the others are added
    let mut c = a.clone();
    c[k + 2] = f64::INFINITY;
    let mut acc = MomentsArray::new(rows);
    let st = acc.add(&Matrix::new(&c, rows, k).unwrap(), true).unwrap();
    assert_eq!(st.get(1).unwrap_err().kind(), ErrorKind::NonFinite);
    assert!(st.get(0).is_ok() && acc[1].n() == 0 && acc[0].n() == k as u64);
    assert_eq!(st.codes()[1], sys::MCSTAT_ENONFINITE);
    // shapes
    assert_eq!(acc.add(&Matrix::new(&c, rows - 1, k).unwrap(), false).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(acc.merge(&one[..2]).unwrap_err().kind(), ErrorKind::InvalidArgument);
    // summaries: n, mean and M2 give the data's t test
    let x = &a[..k];
    let mut m = Moments::new();
    m.add_slice(x).unwrap();
    let s = Moments::from_summary(k as u64, m.mean(), m.var() * (k as f64 - 1.0)).unwrap();
    let (p1, p2) = (
        t_test_1_moments(&m, 0.2, Alternative::Less, 0.05).unwrap().p_value(),
        t_test_1_moments(&s, 0.2, Alternative::Less, 0.05).unwrap().p_value(),
    );
    assert!(rel_err(p1, p2) < 1e-12);
    assert_eq!(Moments::from_summary(0, 1.0, 0.0).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(Moments::from_summary(3, 1.0, -1.0).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(Moments::from_summary(3, f64::NAN, 1.0).unwrap_err().kind(), ErrorKind::NonFinite);
    let mut o = Moments::new();
    assert_eq!(o.add_slice_omit_nan(&[1.0, f64::NAN, 3.0]).unwrap(), 1);
    assert_eq!(o.n(), 2);
}

#[test]
fn stream_checks_are_the_tests_on_its_moments() {
    let mut rng = Rng::new(6);
    let x: Vec<f64> = rng.vec(2000).iter().map(|v| 1.0 + 0.1 * v).collect();
    let mut s = Stream::new();
    s.add_slice(&x[..1500]);
    let mut t = Stream::new();
    for &v in &x[1500..] {
        t.add(v);
    }
    s.merge(&t).unwrap();
    assert_eq!(s.n(), 2000);
    let m = s.moments();
    let mut direct = Moments::new();
    direct.add_slice(&x).unwrap();
    assert!(rel_err(m.mean(), direct.mean()) < 1e-15 && rel_err(m.var(), direct.var()) < 1e-12);
    let c = s.check_mean(1.0, 0.0, 0.01).unwrap();
    let r = t_test_1_moments(&m, 1.0, Alternative::TwoSided, 0.01).unwrap();
    assert_eq!(c.p_value().to_bits(), r.p_value().to_bits());
    assert!(rel_err(c.p_value(), t_test_1(&x, 1.0, Alternative::TwoSided, 0.01).unwrap().p_value()) < 1e-10);
    let v = s.check_var(0.01, 0.01).unwrap();
    assert_eq!(v.p_value().to_bits(), var_test_1_moments(&m, 0.01, Alternative::Greater, 0.01).unwrap().p_value().to_bits());
    // a wrong reference fails; a tolerance covers it
    assert!(s.check_mean(1.05, 0.0, 0.01).unwrap().reject());
    assert!(!s.check_mean(1.05, 0.1, 0.01).unwrap().reject());
    s.flush().unwrap();
    assert_eq!(s.raw().count, 0);
    // non-finite values are counted, and the checks refuse
    s.add(f64::NAN);
    s.flush().unwrap();
    assert_eq!((s.n_nonfinite(), s.n_overflow()), (1, 0));
    assert_eq!(s.check_mean(1.0, 0.0, 0.01).unwrap_err().kind(), ErrorKind::NonFinite);
    s.clear();
    assert_eq!(s.n(), 0);
    assert_eq!(s.check_var(1.0, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(Stream::new().check_mean(0.0, -1.0, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
}

// ---- multiple testing --------------------------------------------------------------

#[test]
fn p_adjust_against_r() {
    let body = read("p_adjust_ref.txt");
    let lines: Vec<&str> = body.lines().collect();
    let values = |l: &str, tag: &str| -> Vec<f64> {
        let rest = l.strip_prefix(tag).unwrap_or_else(|| panic!("expected {tag}"));
        rest.split_whitespace().map(|v| v.parse::<f64>().unwrap()).collect()
    };
    let mut work = Workspace::new();
    let mut cases = 0;
    for (i, l) in lines.iter().enumerate() {
        let f: Vec<&str> = l.split_whitespace().collect();
        if f.first() != Some(&"case") {
            continue;
        }
        let method: PAdjustMethod = f[2].parse().unwrap();
        assert_eq!(method.to_string(), f[2]);
        let p = values(lines[i + 1], "p ");
        let want = values(lines[i + 2], "adj ");
        assert_eq!(p.len(), f[3].parse::<usize>().unwrap());
        let got = p_adjust(&p, method).unwrap();
        let mut inplace = p.clone();
        p_adjust_in_place(&mut inplace, method, &mut work).unwrap();
        for k in 0..p.len() {
            assert!(got[k].is_nan() == want[k].is_nan() && (want[k].is_nan() || rel_err(got[k], want[k]) <= 1e-14), "{} {} [{k}]", f[1], f[2]);
            assert_eq!(got[k].to_bits(), inplace[k].to_bits());
        }
        cases += 1;
    }
    assert_eq!(cases, 72);
    assert_eq!("fdr".parse::<PAdjustMethod>().unwrap(), PAdjustMethod::BH);
    assert_eq!("FDR?".parse::<PAdjustMethod>().unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(PAdjustMethod::Bonferroni.work_size(1000).unwrap(), 0);
    assert!(PAdjustMethod::Holm.work_size(1000).unwrap() >= 8000);
    assert_eq!(PAdjustMethod::Hommel.work_size(usize::MAX / 2).unwrap_err().kind(), ErrorKind::TooBig);
    let mut bad = vec![0.1, 1.5];
    assert_eq!(p_adjust_in_place(&mut bad, PAdjustMethod::BH, &mut work).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(bad, vec![0.1, 1.5]); // nothing written
}

#[test]
fn e_bh_hand_values_and_method() {
    // descending 20, 10, 1, 0.5 with m = 4: 4/(k e_(k)) = 0.2, 0.2, 4/3, 2,
    // the minimum from each rank on, capped at 1
    let got = mcstat::e_bh(&[20.0, 10.0, 1.0, 0.5]).unwrap();
    let want = [0.2, 0.2, 1.0, 1.0];
    for k in 0..4 {
        assert!(rel_err(got[k], want[k]) <= 1e-15, "[{k}] {}", got[k]);
    }
    // m = 3 (NaN not counted), descending inf, 4, 0: 3/(2*4) = 0.375 for the 4
    let got = mcstat::e_bh(&[f64::NAN, 4.0, f64::INFINITY, 0.0]).unwrap();
    assert!(got[0].is_nan() && rel_err(got[1], 0.375) <= 1e-15 && got[2] == 0.0 && got[3] == 1.0);
    assert_eq!(mcstat::e_bh(&[1.0, -1.0]).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert!(mcstat::e_bh(&[]).unwrap().is_empty());
    // the method: e-BH on e = p^(-9/10) / 10
    let m: PAdjustMethod = "e-BH".parse().unwrap();
    assert_eq!(m, PAdjustMethod::EBH);
    assert_eq!("ebh".parse::<PAdjustMethod>().unwrap(), PAdjustMethod::EBH);
    assert_eq!(m.to_string(), "e-BH");
    let p: [f64; 4] = [0.001, 0.02, 0.3, 0.0];
    let e: Vec<f64> = p.iter().map(|&v| if v > 0.0 { 0.1 * v.powf(-0.9) } else { f64::INFINITY }).collect();
    let via_e = mcstat::e_bh(&e).unwrap();
    let got = p_adjust(&p, m).unwrap();
    for k in 0..4 {
        assert!(rel_err(got[k], via_e[k]) <= 1e-12 || got[k] == via_e[k], "[{k}] {} {}", got[k], via_e[k]);
    }
}

// ---- power --------------------------------------------------------------------

#[test]
fn power_against_r() {
    let body = read("power_ref.tsv");
    let mut counts = [0; 4];
    for line in body.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split('\t').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let test = match f[1] {
            "t_1" => PowerTest::T1,
            "t_2" => PowerTest::T2,
            "welch" => PowerTest::Welch,
            "var_1" => PowerTest::Var1,
            "var_2" => PowerTest::Var2,
            t => panic!("test {t}"),
        };
        let o = Power {
            test,
            alternative: f[2].parse().unwrap(),
            strict: f[3] == "1",
            n: Some(num(4)),
            n_ratio: num(5),
            sd_ratio: num(6),
            effect: Some(num(7)),
            alpha: Some(num(8)),
            power: Some(num(9)),
        };
        let is_t = matches!(test, PowerTest::T1 | PowerTest::T2 | PowerTest::Welch);
        match f[0] {
            "power" => {
                let p = o.compute().unwrap();
                assert!((p - num(9)).abs() <= 1e-10 + 1e-9 * num(9), "{line}: {p}");
                let s = Power { power: None, ..o }.solve().unwrap();
                assert_eq!(s.power(), p);
                counts[0] += 1;
            }
            "n" => {
                let s = Power { n: None, ..o }.solve().unwrap();
                let want = num(4);
                if is_t {
                    // R's n is the continuous root, mcstat's the next integer
                    assert!(s.n() == (want - 1e-7).ceil() || ((want - want.round()).abs() < 1e-6 && s.n() == want.round() + 1.0), "{line}: {}", s.n());
                } else {
                    assert_eq!(s.n(), want, "{line}");
                }
                assert!(s.power() >= num(9));
                counts[1] += 1;
            }
            "effect" => {
                let s = Power { effect: None, ..o }.solve().unwrap();
                assert!(rel_err(s.effect(), num(7)) <= 1e-8, "{line}: {}", s.effect());
                counts[2] += 1;
            }
            _ => {
                let s = Power { alpha: None, ..o }.solve().unwrap();
                assert!((s.alpha() - num(8)).abs() <= 1e-11 + 1e-7 * num(8), "{line}: {}", s.alpha());
                counts[3] += 1;
            }
        }
    }
    assert_eq!(counts, [1640, 168, 68, 36]);
    // R's power.t.test(delta = 0.5, sd = 1, power = 0.8): n = 63.76576 per
    // group; type = "one.sample": n = 33.36713
    let two = Power { test: PowerTest::T2, effect: Some(0.5), power: Some(0.8), ..Default::default() }.solve().unwrap();
    assert_eq!(two.n(), 64.0);
    let one = Power { test: PowerTest::T1, effect: Some(0.5), power: Some(0.8), ..Default::default() }.solve().unwrap();
    assert_eq!(one.n(), 34.0);
    let text = two.to_string();
    assert!(text.contains("power calculation") && text.contains("n = 64"), "{text}");
    // bad input
    let none_twice = Power { effect: Some(0.5), ..Default::default() };
    assert_eq!(none_twice.solve().unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(none_twice.compute().unwrap_err().kind(), ErrorKind::InvalidArgument);
    let zero = Power { effect: Some(0.0), power: Some(0.8), ..Default::default() };
    assert_eq!(zero.solve().unwrap_err().kind(), ErrorKind::InvalidArgument);
    let one = Power { n: Some(1.0), effect: Some(0.5), ..Default::default() };
    assert_eq!(one.compute().unwrap_err().kind(), ErrorKind::InvalidArgument);
}

// ---- diagnostics -----------------------------------------------------------------

#[test]
fn diagnostics_against_closed_forms() {
    // Hill's estimate on exact Pareto order statistics
    for &a in &[0.7, 1.5, 2.0, 4.0] {
        for &k in &[10usize, 31, 100] {
            let mut x = vec![0.0];
            for i in 0..=k {
                let v = ((i + 1) as f64).powf(-1.0 / a);
                x.push(v);
                x.push(-v);
            }
            for i in 0..20 {
                let v = 1e-3 * ((k + 2) as f64).powf(-1.0 / a) * (i + 1) as f64 / 21.0;
                x.push(v);
                x.push(-v);
            }
            let lgamma_k1: f64 = (1..=k).map(|i| (i as f64).ln()).sum();
            let want = a * k as f64 / (k as f64 * ((k + 1) as f64).ln() - lgamma_k1);
            let idx = diag::tail_index(&x, Some(k)).unwrap();
            assert!(rel_err(idx[0], want) < 1e-12 && rel_err(idx[1], want) < 1e-12, "a {a} k {k}: {idx:?} vs {want}");
        }
    }
    // Edgeworth: exponential (g1 = 2, g2 = 6), k = 1, m = 10
    let z = 1.959963984540054f64;
    let phi = (-0.5 * z * z).exp() / (2.0 * PI).sqrt();
    let a = 2.0 * (2.0 * z * z + 1.0) / 6.0 * phi / 10f64.sqrt();
    let b = z * (6.0 * (z * z - 3.0) / 12.0 - 4.0 * (z.powi(4) + 2.0 * z * z - 3.0) / 18.0) * phi / 10.0;
    let s = diag::t_size(2.0, 6.0, 1, 10, 0.05).unwrap();
    assert!(rel_err(s[0], 0.025 + a - b) < 1e-12 && rel_err(s[1], (0.025 - a - b).max(0.0)) < 1e-12);
    assert_eq!(diag::t_size(0.0, 0.0, 1, 10, 0.05).unwrap(), [0.025, 0.025]);
    assert_eq!(diag::batch_size(0.0, 0.0, 10, 0.05, 0.2).unwrap(), 1);
    assert!(diag::batch_size(4.0, 1.0, 20, 0.05, 0.2).unwrap() > 10 * diag::batch_size(1.0, 1.0, 20, 0.05, 0.2).unwrap());
    // the whole report on exponential data
    let mut rng = Rng::new(7);
    let x: Vec<f64> = (0..20000).map(|_| -(1.0 - rng.next()).ln()).collect();
    let d = diagnose(&x, &DiagOptions::default()).unwrap();
    let mut m = Moments::new();
    m.add_slice(&x).unwrap();
    assert_eq!((d.n(), d.skewness().0, d.kurtosis().0), (20000, m.skewness(), m.kurtosis()));
    assert!((d.skewness().0 - 2.0).abs() < 0.3 && !d.heavy_tail());
    assert_eq!((d.batch_size(), d.batch_means()), (1, sys::MCSTAT_DIAG_DEFAULT_M));
    assert!(d.t_size()[0] > d.t_size()[1] && d.recommended_batch_size() > 1);
    assert!(d.tail_index_se()[1].is_some());
    let d = diagnose(&x, &DiagOptions { batch_size: Some(100), ..Default::default() }).unwrap();
    assert_eq!((d.batch_size(), d.batch_means()), (100, 200));
    // heavy tails: U^-1/2 has tail index 2
    let y: Vec<f64> = (0..20000).map(|_| (1.0 - rng.next()).powf(-0.5)).collect();
    assert!(diagnose(&y, &DiagOptions::default()).unwrap().heavy_tail());
    // bad input
    assert_eq!(diagnose(&x[..7], &DiagOptions::default()).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(diagnose(&x, &DiagOptions { alpha: 1.5, ..Default::default() }).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(diagnose(&[1.0; 64], &DiagOptions::default()).unwrap_err().kind(), ErrorKind::DegenerateData);
    let mut nan = x[..64].to_vec();
    nan[5] = f64::NAN;
    assert_eq!(diag::tail_index(&nan, None).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(diag::t_size(f64::NAN, 0.0, 1, 10, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(diag::batch_size(1.0, 1.0, 1, 0.05, 0.2).unwrap_err().kind(), ErrorKind::TooFewObservations);
}

// ---- goodness of fit, binomial, battery ------------------------------------------

/// The value of "key" in a one-line JSON object (numbers and arrays of numbers).
fn json_field<'a>(line: &'a str, key: &str) -> &'a str {
    let k = format!("\"{key}\": ");
    let start = line.find(&k).unwrap_or_else(|| panic!("no {key}")) + k.len();
    let rest = &line[start..];
    let end = if rest.starts_with('[') { rest.find(']').unwrap() + 1 } else { rest.find([',', '}']).unwrap() };
    rest[..end].trim()
}

fn json_numbers(v: &str) -> Vec<f64> {
    v.trim_matches(|c| c == '[' || c == ']').split(',').map(|s| s.trim().parse().unwrap()).collect()
}

#[test]
fn gof_chisq_against_r() {
    let body = read("chisq_ref.json");
    let mut n = 0;
    for line in body.lines().filter(|l| l.trim_start().starts_with('{')) {
        let name = json_field(line, "name");
        let x = json_numbers(json_field(line, "x"));
        let p = json_numbers(json_field(line, "p"));
        let num = |k: &str| json_field(line, k).parse::<f64>().unwrap();
        let opt = GofOptions {
            expected: if num("counts") == 1.0 { Expected::Counts } else { Expected::Probabilities },
            pool: num("pool") == 1.0,
            min_expected: num("min_expected"),
            n_estimated: num("n_estimated") as u32,
            ..Default::default()
        };
        let r = gof_chisq_test(&x, &p, &opt, 0.05).unwrap();
        assert_eq!(r.test(), Test::ChisqGof);
        assert!(rel_err(r.statistic(), num("statistic")) <= 1e-12 || (r.statistic() - num("statistic")).abs() < 1e-12, "{name} statistic");
        assert!(rel_err(r.p_value(), num("pvalue")) <= 1e-11, "{name}: p {} vs {}", r.p_value(), num("pvalue"));
        assert_eq!(r.df(), &[num("df")]);
        assert_eq!((r.conf_int(), r.null_value(), r.std_error()), (None, None, None));
        match r.details() {
            Details::ChisqGof { cells, cells_given, n_estimated, pool_below, .. } => {
                assert_eq!(cells as f64, num("cells"), "{name} cells");
                assert_eq!(cells_given as usize, x.len());
                assert_eq!(n_estimated, opt.n_estimated);
                assert_eq!(pool_below.is_some(), opt.pool);
            }
            d => panic!("{name}: {d:?}"),
        }
        n += 1;
    }
    assert!(n >= 40, "{n} cases");
    assert_eq!(gof::default_min_expected(), 5.0);
    let d = GofOptions::default();
    assert!(d.pool && !d.rescale && d.expected == Expected::Probabilities);
    let obs = [10.0, 20.0, 30.0];
    assert_eq!(gof_chisq_test(&obs, &[0.5, 0.5], &d, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(gof_chisq_test(&obs, &[0.2, 0.2, 0.2], &d, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let rescaled = GofOptions { rescale: true, pool: false, ..d };
    assert!(gof_chisq_test(&obs, &[0.2, 0.2, 0.2], &rescaled, 0.05).is_ok());
    assert_eq!(gof_chisq_test(&[1.0, f64::NAN], &[0.5, 0.5], &d, 0.05).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(gof_chisq_test(&[5.0], &[1.0], &d, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
}

#[test]
fn binomial_and_battery_against_r() {
    let body = read("binom_ref.csv");
    let mut n = 0;
    for line in body.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let (x, trials) = (f[0].parse::<u64>().unwrap(), f[1].parse::<u64>().unwrap());
        let a: Alternative = f[3].parse().unwrap();
        let r = binom_test(x, trials, num(2), a, num(4)).unwrap();
        assert_eq!((r.test(), r.method()), (Test::Binom, Method::Exact));
        let log_p_value = match r.details() {
            Details::Binom { log_p_value } => log_p_value,
            d => panic!("no binomial details: {d:?}"),
        };
        let (want_p, want_log) = (num(5), num(6));
        if want_p > 1e-300 {
            assert!(rel_err(r.p_value(), want_p) <= 1e-10, "{line}: p {}", r.p_value());
        }
        if want_log == f64::NEG_INFINITY {
            assert_eq!((r.p_value(), log_p_value), (0.0, f64::NEG_INFINITY), "{line}");
        } else if want_p > 1e-300 {
            assert!((log_p_value - want_log).abs() <= 1e-10 * want_log.abs().max(1.0), "{line}: log p {log_p_value}");
        } else {
            // R's log is exact for one-sided tails, and that of its
            // underflowed p-value for two-sided ones: mcstat's goes on below
            let close = (log_p_value - want_log).abs() <= 1e-10 * want_log.abs();
            assert!(log_p_value.is_finite() && (close || log_p_value < want_log), "{line}: log p {log_p_value}");
        }
        let (lo, hi) = r.conf_int().unwrap();
        assert!((lo - num(7)).abs() <= 1e-10 * num(7).max(1e-300) + 1e-300 && (hi - num(8)).abs() <= 1e-10 * num(8), "{line}: [{lo}, {hi}]");
        assert_eq!(r.df(), &[] as &[f64]);
        assert_eq!(r.estimate(), &[x as f64 / trials as f64]);
        n += 1;
    }
    assert!(n > 100, "{n} rows");
    // the battery meta-test is the binomial test against the level
    let b = battery_test(12, 100, 0.05, Alternative::Greater, 0.01).unwrap();
    let r = binom_test(12, 100, 0.05, Alternative::Greater, 0.01).unwrap();
    assert_eq!(b.p_value(), r.p_value());
    // R 4.2: print(binom.test(12, 100, 0.05, "greater")$p.value, digits = 17)
    assert!(b.reject());
    assert!(rel_err(b.p_value(), 0.004_274_182_466_365_92) < 1e-12, "{}", b.p_value());
    let p: Vec<f64> = (0..100).map(|i| if i < 12 { 0.01 } else { 0.5 }).collect();
    assert_eq!(battery_test_p_values(&p, 0.05, Alternative::Greater, 0.01).unwrap().p_value(), b.p_value());
    assert_eq!(binom_test(5, 3, 0.5, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(binom_test(0, 0, 0.5, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(battery_test(1, 10, 1.0, Alternative::Greater, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(battery_test_p_values(&[0.1, f64::NAN], 0.05, Alternative::Greater, 0.05).unwrap_err().kind(), ErrorKind::NonFinite);
    assert_eq!(battery_test_p_values(&[], 0.05, Alternative::Greater, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
}

// ---- renderer checks --------------------------------------------------------------

/// A Lambertian BSDF (albedo 0.8) sampled by cosine-weighted directions;
/// `weight_bug` scales the reported weight.
fn lambert<'a>(weight_bug: f64) -> CheckModel<'a> {
    let rho = 0.8;
    CheckModel::new(
        Domain::Hemisphere,
        2,
        move |s: Samples<'_>| {
            assert!(s.wi.is_some());
            for k in 0..s.len() {
                let (u1, u2) = (s.u[2 * k], s.u[2 * k + 1]);
                let (r, phi) = (u1.sqrt(), 2.0 * PI * u2);
                let z = (1.0 - u1).sqrt();
                s.x[3 * k..3 * k + 3].copy_from_slice(&[r * phi.cos(), r * phi.sin(), z]);
                s.pdf[k] = z / PI;
                s.weight[k] = rho * weight_bug;
            }
            Ok(())
        },
        |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (k, o) in out.iter_mut().enumerate() {
                *o = x[3 * k + 2].max(0.0) / PI;
            }
            Ok(())
        },
    )
    .eval(move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        for (k, o) in out.iter_mut().enumerate() {
            *o = rho * x[3 * k + 2].max(0.0) / PI;
        }
        Ok(())
    })
}

#[test]
fn zero_weights_with_positive_pdf_are_counted() {
    // a fifth of the samples "fail" by weight 0 alone, their pdf kept
    let rho = 0.8;
    let mut m = CheckModel::new(
        Domain::Hemisphere,
        2,
        move |s: Samples<'_>| {
            for k in 0..s.len() {
                let (u1, u2) = (s.u[2 * k], s.u[2 * k + 1]);
                let (r, phi) = (u1.sqrt(), 2.0 * PI * u2);
                let z = (1.0 - u1).sqrt();
                s.x[3 * k..3 * k + 3].copy_from_slice(&[r * phi.cos(), r * phi.sin(), z]);
                s.pdf[k] = z / PI;
                s.weight[k] = if (u2 * 10.0).fract() < 0.2 { 0.0 } else { rho };
            }
            Ok(())
        },
        |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (k, o) in out.iter_mut().enumerate() {
                *o = x[3 * k + 2].max(0.0) / PI;
            }
            Ok(())
        },
    )
    .eval(move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        for (k, o) in out.iter_mut().enumerate() {
            *o = rho * x[3 * k + 2].max(0.0) / PI;
        }
        Ok(())
    });
    let r = check_bsdf(&mut m, [0.3, 0.1, 0.9], 5000, 3, 0.01, &CheckOptions::default()).unwrap();
    assert!(r.reject() && r.route(Route::Weight).reject(), "{r}");
    let frac = r.zero_weight() as f64 / r.n() as f64;
    assert!(frac > 0.17 && frac < 0.23, "{frac}");
    assert!(r.to_string().contains("must return pdf 0"), "{r}");
    let ok = check_bsdf(&mut lambert(1.0), [0.3, 0.1, 0.9], 5000, 3, 0.01, &CheckOptions::default()).unwrap();
    assert_eq!(ok.zero_weight(), 0);
}

#[test]
fn renderer_checks_pass_correct_models_and_catch_bugs() {
    let wi = [0.3, 0.1, 0.9];
    let opt = CheckOptions::default();
    let ok = check_bsdf(&mut lambert(1.0), wi, 20000, 3, 0.01, &opt).unwrap();
    assert!(!ok.reject(), "{ok}");
    assert_eq!(ok.domain(), Some(Domain::Hemisphere));
    let (mass, err) = ok.mass().unwrap();
    assert!((mass - 1.0).abs() <= err.max(1e-6), "mass {mass} +- {err}");
    let (albedo, _) = ok.albedo().unwrap();
    assert!((albedo - 0.8).abs() < 1e-12);
    assert_eq!(ok.route(Route::Weight).state(), RouteState::Ran);
    assert!(ok.route(Route::Weight).deterministic());
    assert!(ok.route(Route::Cells).p_value().is_some());
    assert_eq!(ok.route(Route::Reciprocity).state(), RouteState::Skipped);
    assert!(ok.wi().is_some() && ok.n() == 20000 && ok.calls() > 0);
    let text = ok.to_string();
    assert!(text.contains("cells") && text.contains("weight"), "{text}");
    // the weight 10% off: the WEIGHT route sees it
    let bad = check_bsdf(&mut lambert(1.1), wi, 20000, 3, 0.01, &opt).unwrap();
    assert!(bad.reject() && bad.route(Route::Weight).reject());
    assert!(bad.route(Route::Weight).worst().is_some());
    // reciprocity asked for: eval is called with the point as wi
    let recip = CheckOptions { reciprocal: true, ..Default::default() };
    let r = check_bsdf(&mut lambert(1.0), wi, 20000, 3, 0.01, &recip).unwrap();
    assert_eq!(r.route(Route::Reciprocity).state(), RouteState::Ran);
    assert!(!r.reject());
    assert!(check_work_size(&lambert(1.0), 20000, &opt).unwrap() > 20000 * 16);

    // warps: x = u^2 on [0, 1] and its density; the bug forgets the 2
    for bug in [false, true] {
        let c = if bug { 0.55 } else { 0.5 };
        let mut warp = CheckModel::new(
            Domain::Interval,
            1,
            |s: Samples<'_>| {
                for (x, u) in s.x.iter_mut().zip(s.u) {
                    *x = u * u;
                }
                Ok(())
            },
            move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
                for (o, &x) in out.iter_mut().zip(x) {
                    *o = if x > 0.0 { c / x.sqrt() } else { 0.0 };
                }
                Ok(())
            },
        )
        .sample_reports(false);
        let r = check_warp(&mut warp, 20000, 3, 0.01, &opt).unwrap();
        assert_eq!(r.reject(), bug, "{r}");
        assert_eq!(r.albedo(), None);
        if bug {
            assert!(r.route(Route::Mass).reject());
        }
    }

    // an emitter of constant radiance 2 sampled uniformly over the sphere
    let mut emitter = CheckModel::new(
        Domain::Sphere,
        2,
        |s: Samples<'_>| {
            assert!(s.wi.is_none());
            for k in 0..s.len() {
                let z = 1.0 - 2.0 * s.u[2 * k];
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * s.u[2 * k + 1];
                s.x[3 * k..3 * k + 3].copy_from_slice(&[r * phi.cos(), r * phi.sin(), z]);
                s.pdf[k] = 0.25 / PI;
                s.weight[k] = 8.0 * PI;
            }
            Ok(())
        },
        |_: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
            out.iter_mut().for_each(|o| *o = 0.25 / PI);
            Ok(())
        },
    )
    .eval(|_: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
        out.iter_mut().for_each(|o| *o = 2.0);
        Ok(())
    })
    .weight(WeightConvention::OverPdf);
    let e = check_emitter(&mut emitter, 20000, 5, 0.01, &opt).unwrap();
    assert!(!e.reject(), "{e}");
    assert_eq!(e.wi(), None);
}

#[test]
fn renderer_check_callbacks_fail_cleanly() {
    let wi = [0.0, 0.0, 1.0];
    let opt = CheckOptions::default();
    // an error returned by a closure
    let mut calls = 0;
    let mut m = CheckModel::new(
        Domain::Square,
        2,
        |s: Samples<'_>| {
            calls += 1;
            if calls == 2 {
                return Err("the sampler ran out of paint".into());
            }
            s.x.copy_from_slice(s.u);
            s.pdf.iter_mut().for_each(|p| *p = 1.0);
            s.weight.iter_mut().for_each(|w| *w = 1.0);
            Ok(())
        },
        |_: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
            out.iter_mut().for_each(|o| *o = 1.0);
            Ok(())
        },
    )
    .sample_reports(false);
    let small_batches = CheckOptions { batch: 1024, ..Default::default() };
    let e = check_warp(&mut m, 5000, 1, 0.01, &small_batches).unwrap_err();
    assert_eq!((e.kind(), e.status()), (ErrorKind::Callback, sys::MCSTAT_ECALLBACK));
    assert!(e.message().contains("sample()") && e.message().contains("ran out of paint"), "{e}");
    drop(m);
    assert_eq!(calls, 2); // the check stopped at the failing call

    // a panic is caught at the boundary and reported, never unwound into C
    let mut m = CheckModel::new(
        Domain::Square,
        2,
        |s: Samples<'_>| {
            s.x.copy_from_slice(s.u);
            Ok(())
        },
        |_: Option<&[f64; 3]>, _x: &[f64], _out: &mut [f64]| -> CallbackResultAlias { panic!("pdf exploded") },
    )
    .sample_reports(false);
    let e = check_warp(&mut m, 5000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains("pdf() panicked: pdf exploded"), "{e}");

    // invalid values: libmcstat names the callback, the point and the value
    let mut m = CheckModel::new(
        Domain::Hemisphere,
        2,
        |s: Samples<'_>| {
            for k in 0..s.len() {
                s.x[3 * k..3 * k + 3].copy_from_slice(&[0.0, 0.0, 1.0]);
                s.pdf[k] = f64::NAN;
                s.weight[k] = 1.0;
            }
            Ok(())
        },
        |_: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
            out.iter_mut().for_each(|o| *o = 1.0);
            Ok(())
        },
    )
    .eval(|_: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
        out.iter_mut().for_each(|o| *o = 1.0);
        Ok(())
    });
    let e = check_bsdf(&mut m, wi, 5000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains("sample() returned pdf nan at sample 0"), "{e}");

    // bad options and arguments: errors, not panics
    let mut good = lambert(1.0);
    let none = CheckOptions { routes: RouteSet::of(&[]), ..Default::default() };
    assert_eq!(check_bsdf(&mut good, wi, 5000, 1, 0.01, &none).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(check_bsdf(&mut good, wi, 999, 1, 0.01, &opt).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(check_bsdf(&mut good, [0.0; 3], 5000, 1, 0.01, &opt).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(check_bsdf(&mut good, wi, 5000, 1, 1.5, &opt).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let bad_batch = CheckOptions { batch: 10, ..Default::default() };
    assert_eq!(check_bsdf(&mut good, wi, 5000, 1, 0.01, &bad_batch).unwrap_err().kind(), ErrorKind::InvalidArgument);
    // a BSDF without eval is refused
    let mut no_eval = CheckModel::new(Domain::Hemisphere, 2, |_s: Samples<'_>| Ok(()), |_: Option<&[f64; 3]>, _: &[f64], _: &mut [f64]| Ok(()));
    assert_eq!(check_bsdf(&mut no_eval, wi, 5000, 1, 0.01, &opt).unwrap_err().kind(), ErrorKind::InvalidArgument);
    let mut too_many_u = CheckModel::new(Domain::Square, 9, |_s: Samples<'_>| Ok(()), |_: Option<&[f64; 3]>, _: &[f64], _: &mut [f64]| Ok(()));
    assert_eq!(check_warp(&mut too_many_u, 5000, 1, 0.01, &opt).unwrap_err().kind(), ErrorKind::InvalidArgument);
}

type CallbackResultAlias = mcstat::check::CallbackResult;

#[test]
fn route_and_domain_names() {
    for r in Route::ALL {
        assert_eq!(r.name().parse::<Route>().unwrap(), r);
        assert!(!r.meaning().is_empty() && !r.blind_spot().is_empty());
    }
    assert_eq!(Route::PdfValue.to_string(), "pdf_value");
    assert_eq!("nope".parse::<Route>().unwrap_err().kind(), ErrorKind::InvalidArgument);
    let dims: Vec<usize> = Domain::ALL.iter().map(|d| d.dims()).collect();
    assert_eq!(dims, vec![3, 3, 2, 2, 1]);
    for d in Domain::ALL {
        assert_eq!(d.to_string().parse::<Domain>().unwrap(), d);
    }
    assert_eq!("cube".parse::<Domain>().unwrap_err().kind(), ErrorKind::InvalidArgument);
    let s = RouteSet::all().without(Route::Ks);
    assert!(!s.contains(Route::Ks) && s.contains(Route::Cells) && s.with(Route::Ks) == RouteSet::all());
}

fn tsv_num(s: &str) -> f64 {
    match s {
        "NA" | "NaN" => f64::NAN,
        "Inf" => f64::INFINITY,
        "-Inf" => f64::NEG_INFINITY,
        _ => hex_float(s),
    }
}

/// |got - want| within tol of scale (plus a few ulps of want).
fn near(got: f64, want: f64, scale: f64, tol: f64) -> bool {
    got == want || (got - want).abs() <= tol * scale + 8.0 * f64::EPSILON * want.abs()
}

#[test]
fn pooled_and_paired_t_against_r() {
    let alts = [Alternative::TwoSided, Alternative::Less, Alternative::Greater];
    let mut seen = (0, 0);
    for line in read("t_ref.tsv").lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split('\t').collect();
        if f[0] != "pooled" && f[0] != "paired" {
            continue;
        }
        let a = alts[f[1].parse::<usize>().unwrap()];
        let (mu, alpha) = (tsv_num(f[2]), tsv_num(f[3]));
        let x: Vec<f64> = f[4].split(',').map(tsv_num).collect();
        let y: Vec<f64> = f[5].split(',').map(tsv_num).collect();
        let v: Vec<f64> = f[6..18].iter().map(|s| tsv_num(s)).collect();
        let (stat, df, p, logp, lo, hi, se, conf2, lo2, hi2) = (v[0], v[1], v[2], v[3], v[4], v[5], v[8], v[9], v[10], v[11]);
        let r = if f[0] == "pooled" {
            seen.0 += 1;
            let r = t_test_2_pooled(&x, &y, mu, a, alpha).unwrap();
            assert_eq!(r.test(), Test::T2Pooled);
            let (mut mx, mut my) = (Moments::new(), Moments::new());
            mx.add_slice(&x).unwrap();
            my.add_slice(&y).unwrap();
            let rm = t_test_2_pooled_moments(&mx, &my, mu, a, alpha).unwrap();
            assert_eq!(rm.statistic().to_bits(), r.statistic().to_bits(), "{line}");
            r
        } else {
            seen.1 += 1;
            let r = t_test_paired(&x, &y, mu, a, alpha).unwrap();
            assert_eq!(r.test(), Test::TPaired);
            assert_eq!(r.estimate().len(), 1);
            r
        };
        assert!(near(r.statistic(), stat, stat.abs(), 1e-11), "statistic {} vs R {stat}", r.statistic());
        assert_eq!(r.df().len(), 1);
        assert!(near(r.df()[0], df, df, 1e-13));
        if p > 1e-300 {
            assert!(near(r.p_value(), p, p, 1e-11), "p {} vs R {p}", r.p_value());
        }
        let lp = r.log_p_value().unwrap();
        assert!(near(lp, logp, logp.abs().max(1.0), 1e-12), "log p {lp} vs R {logp}");
        assert!(lp.is_finite());
        let width = if (hi - lo).is_finite() { hi - lo } else { se };
        let (l, h) = r.conf_int().unwrap();
        assert!(near(l, lo, width, 1e-10) && near(h, hi, width, 1e-10), "interval {l} {h} vs R {lo} {hi}");
        let width2 = if (hi2 - lo2).is_finite() { hi2 - lo2 } else { se };
        let (l2, h2) = r.conf_int_at(conf2).unwrap();
        assert!(near(l2, lo2, width2, 1e-10) && near(h2, hi2, width2, 1e-10), "at {conf2}: {l2} {h2} vs R {lo2} {hi2}");
    }
    assert!(seen.0 >= 20 && seen.1 >= 20, "rows read: {seen:?}");
}

#[test]
fn paired_lengths_and_levels_are_checked() {
    let x = [1.0, 2.0, 3.5, 4.0];
    let e = t_test_paired(&x, &x[..3], 0.0, Alternative::TwoSided, 0.05).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert!(e.message().contains("x has 4, y has 3"), "{e}");
    let r = t_test_2_pooled(&x, &[0.5, 1.0, 1.25], 0.0, Alternative::TwoSided, 0.05).unwrap();
    for bad in [0.0, 1.0, f64::NAN, -0.5] {
        assert_eq!(r.conf_int_at(bad).unwrap_err().kind(), ErrorKind::InvalidArgument);
    }
    let k = ks_test_2(&x, &[0.5, 1.0, 1.25], Alternative::TwoSided, 0.05, &KsOptions::default()).unwrap();
    assert_eq!(k.conf_int_at(0.9).unwrap_err().kind(), ErrorKind::InvalidArgument);
}

// ---- the efficiency-ratio test ---------------------------------------------------

#[test]
fn efficiency_against_the_mpmath_oracle() {
    let text = read("efficiency_ref.tsv");
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#') && !l.is_empty()) {
        let f: Vec<&str> = line.split('\t').collect();
        let num = |s: &str| if s == "Inf" { f64::INFINITY } else { hex_float(s) };
        let acc = |s: &str| {
            let v: Vec<f64> = s.split(',').map(num).collect();
            let mut m = Moments::new();
            m.add_slice(&v).unwrap();
            m
        };
        let alt = [Alternative::TwoSided, Alternative::Less, Alternative::Greater][f[1].parse::<usize>().unwrap()];
        let r = efficiency_test(&acc(f[4]), &acc(f[5]), &acc(f[6]), &acc(f[7]), num(f[2]), alt, num(f[3])).unwrap();
        assert_eq!(r.test(), Test::Efficiency);
        assert!(rel_err(r.statistic(), num(f[8])) < 1e-12, "{}", f[0]);
        assert!(rel_err(r.df()[0], num(f[9])) < 1e-12, "{}", f[0]);
        assert!(rel_err(r.log_p_value().unwrap(), num(f[11])) < 1e-12, "{}", f[0]);
        assert!(rel_err(r.std_error().unwrap(), num(f[17])) < 1e-12, "{}", f[0]);
        match r.details() {
            Details::Efficiency { time_ratio, batches_x, .. } => {
                assert!(rel_err(time_ratio, num(f[16])) < 1e-12, "{}", f[0]);
                assert_eq!(batches_x as usize, f[6].split(',').count());
            }
            d => panic!("{d:?}"),
        }
        rows += 1;
    }
    assert!(rows >= 6);
    // bad input: an error, never a panic
    let m = |v: &[f64]| {
        let mut a = Moments::new();
        a.add_slice(v).unwrap();
        a
    };
    let (x, t, one) = (m(&[1.0, 2.0, 4.0]), m(&[1.0, 1.1]), m(&[1.0]));
    assert_eq!(efficiency_test(&x, &x, &t, &one, 1.0, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::TooFewObservations);
    assert_eq!(efficiency_test(&x, &x, &t, &t, 0.0, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::InvalidArgument);
    assert_eq!(efficiency_test(&m(&[3.0, 3.0]), &x, &t, &t, 1.0, Alternative::TwoSided, 0.05).unwrap_err().kind(), ErrorKind::DegenerateData);
}
