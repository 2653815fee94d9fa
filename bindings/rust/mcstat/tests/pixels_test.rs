// rows::pixels_test: every test in both layouts and both widths against the
// single calls on each pixel's values (bit for bit but Welch's and the
// variance tests, within the bounds of mcstat.h), threads, the structs, bad
// arguments.
use mcstat::rows::{pixels_struct_sizes, pixels_structs_init_size, pixels_test, PixelData, PixelTest, Pixels, RowFlags};
use mcstat::*;

const N: usize = 7;
const P: usize = 300;

fn data(seed: u64, n: usize, pixels: usize) -> Vec<f64> {
    let mut s = seed;
    (0..n * pixels)
        .map(|_| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            1.0 + ((s >> 11) as f64 * (1.0 / (1u64 << 53) as f64) - 0.5)
        })
        .collect()
}

fn single(test: PixelTest, x: &[f64], y: &[f64], nv: f64, alt: Alternative) -> Result<TestResult> {
    match test {
        PixelTest::T1 => t_test_1(x, nv, alt, 0.05),
        PixelTest::T2 => t_test_2(x, y, nv, alt, 0.05),
        PixelTest::T2Pooled => t_test_2_pooled(x, y, nv, alt, 0.05),
        PixelTest::TPaired => t_test_paired(x, y, nv, alt, 0.05),
        PixelTest::Var1 => var_test_1(x, nv, alt, 0.05),
        PixelTest::Var2 => var_test_2(x, y, nv, alt, 0.05),
    }
}

#[test]
fn every_test_layout_and_width_is_the_single_call() {
    let tests = [PixelTest::T1, PixelTest::T2, PixelTest::T2Pooled, PixelTest::TPaired, PixelTest::Var1, PixelTest::Var2];
    let mut xs = data(3, N, P); // seeds-major: value s of pixel i at s * P + i
    let ys = data(5, N, P);
    for s in 0..N {
        xs[s * P + 4] = 2.0; // pixel 4 constant: fails or is degenerate where the test needs spread
    }
    let rows = |v: &[f64]| -> Vec<f64> { (0..P * N).map(|k| v[(k % N) * P + k / N]).collect() };
    let (xr, yr) = (rows(&xs), rows(&ys));
    let f32s = |v: &[f64]| -> Vec<f32> { v.iter().map(|&a| a as f32).collect() };
    let (xsf, ysf, xrf, yrf) = (f32s(&xs), f32s(&ys), f32s(&xr), f32s(&yr));
    for &test in &tests {
        let nv = if matches!(test, PixelTest::Var1 | PixelTest::Var2) { 0.09 } else { 0.05 };
        for alt in [Alternative::TwoSided, Alternative::Less, Alternative::Greater] {
            for layout in 0..4 {
                let (x, y) = match layout {
                    0 => (Pixels::seeds_major(PixelData::F64(&xs), N, P), Pixels::seeds_major(PixelData::F64(&ys), N, P)),
                    1 => (Pixels::rows(PixelData::F64(&xr), N), Pixels::rows(PixelData::F64(&yr), N)),
                    2 => (Pixels::seeds_major(PixelData::F32(&xsf), N, P), Pixels::seeds_major(PixelData::F32(&ysf), N, P)),
                    _ => (Pixels::rows(PixelData::F32(&xrf), N), Pixels::rows(PixelData::F32(&yrf), N)),
                };
                let two = !matches!(test, PixelTest::T1 | PixelTest::Var1);
                let r = pixels_test(test, &x, if two { Some(&y) } else { None }, P, nv, alt, 0.05, RowFlags::default(), 2)
                    .unwrap();
                for i in 0..P {
                    let f32_ = layout >= 2;
                    let val = |v: &[f64], s: usize| if f32_ { v[s * P + i] as f32 as f64 } else { v[s * P + i] };
                    let sx: Vec<f64> = (0..N).map(|s| val(&xs, s)).collect();
                    let sy: Vec<f64> = (0..N).map(|s| val(&ys, s)).collect();
                    match single(test, &sx, &sy, nv, alt) {
                        Err(e) => {
                            assert_eq!(r.status[i], e.status(), "{test:?} pixel {i}");
                            assert!(r.p_value[i].is_nan() && r.decision[i] == 0);
                        }
                        Ok(s) => {
                            assert_eq!(r.status[i], 0, "{test:?} pixel {i}");
                            let p = s.p_value();
                            if matches!(test, PixelTest::T2 | PixelTest::Var1 | PixelTest::Var2) {
                                // the block paths: twice the bound of mcstat.h apart from the single call
                                let tol = 2.0 * (3e-14 + 4e-16 * p.max(f64::MIN_POSITIVE).ln().abs());
                                assert!((r.p_value[i] - p).abs() <= tol * p, "{test:?} pixel {i}: {} vs {p}", r.p_value[i]);
                                assert!((r.statistic[i] - s.statistic()).abs() <= 1e-14 * s.statistic().abs().max(1.0));
                                assert!((r.df[i] - s.df()[0]).abs() <= 1e-14 * s.df()[0]);
                            } else {
                                assert_eq!(r.p_value[i].to_bits(), p.to_bits(), "{test:?} pixel {i}");
                                assert_eq!(r.statistic[i].to_bits(), s.statistic().to_bits());
                                assert_eq!(r.df[i].to_bits(), s.df()[0].to_bits());
                                let (lo, hi) = s.conf_int().unwrap();
                                assert_eq!((r.conf_lo[i].to_bits(), r.conf_hi[i].to_bits()), (lo.to_bits(), hi.to_bits()));
                                assert_eq!(r.decision[i] as i32, s.raw().decision);
                            }
                            assert_eq!(r.n_x[i], s.n()[0]);
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn threads_change_no_bit() {
    let p = 20000;
    let (x, y) = (data(7, 4, p), data(9, 4, p));
    let (px, py) = (Pixels::rows(PixelData::F64(&x), 4), Pixels::rows(PixelData::F64(&y), 4));
    for test in [PixelTest::T2, PixelTest::Var2] {
        let nv = if test == PixelTest::Var2 { 1.0 } else { 0.0 };
        let a = pixels_test(test, &px, Some(&py), p, nv, Alternative::TwoSided, 0.05, RowFlags::default(), 1).unwrap();
        let b = pixels_test(test, &px, Some(&py), p, nv, Alternative::TwoSided, 0.05, RowFlags::default(), 2).unwrap();
        let bits = |v: &Vec<f64>| v.iter().map(|a| a.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&a.p_value), bits(&b.p_value));
        assert_eq!(bits(&a.conf_lo), bits(&b.conf_lo));
        assert_eq!(a.status, b.status);
    }
}

#[test]
fn structs_and_bad_arguments() {
    assert_eq!(pixels_struct_sizes(), (56, 24, 128));
    let (a, b, c) = pixels_structs_init_size(56, 24, 128).unwrap();
    assert!(a.size == 56 && b.threads == 1 && c.p_value.is_null());
    assert!(pixels_structs_init_size(56, 16, 128).is_ok()); // 0.2's options size stays known
    assert!(pixels_structs_init_size(40, 16, 128).is_err());
    let x = data(1, 4, 10);
    let short = &x[..39];
    let px = Pixels::rows(PixelData::F64(&x), 4);
    let bad = Pixels::rows(PixelData::F64(short), 4);
    let f = RowFlags::default();
    let a2 = Alternative::TwoSided;
    assert!(pixels_test(PixelTest::T1, &bad, None, 10, 0.0, a2, 0.05, f, 1).is_err()); // slice too short
    assert!(pixels_test(PixelTest::T2, &px, None, 10, 0.0, a2, 0.05, f, 1).is_err()); // y missing
    assert!(pixels_test(PixelTest::T1, &px, Some(&px), 10, 0.0, a2, 0.05, f, 1).is_err()); // y given
    assert!(pixels_test(PixelTest::T1, &px, None, 10, 0.0, a2, 1.5, f, 1).is_err()); // alpha
    assert!(pixels_test(PixelTest::T1, &px, None, 10, 0.0, a2, 0.05, f, 0).is_err()); // threads
    let y3 = Pixels::rows(PixelData::F64(&x[..30]), 3);
    assert!(pixels_test(PixelTest::TPaired, &px, Some(&y3), 10, 0.0, a2, 0.05, f, 1).is_err()); // unequal pairs
    let w = [0.5, 0.5];
    let mut wx = px;
    wx.weights = Some(&w); // two weights, one channel
    assert!(pixels_test(PixelTest::T1, &wx, None, 10, 0.0, a2, 0.05, f, 1).is_err());
    assert!(pixels_test(PixelTest::Var1, &px, None, 10, -1.0, a2, 0.05, f, 1).is_err()); // sigma2
}
