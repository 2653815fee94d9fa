// rows::t_test_2_pixels: every pixel against t_test_2 on its two samples,
// float32 and f64, luminance weights, pixels that cannot be tested, bad sizes.
use mcstat::rows::{t_test_2_pixels, t_test_2_pixels_f32, RowFlags};
use mcstat::*;

#[test]
fn pixels_match_the_single_call() {
    let (nx, ny, pixels, ch) = (6usize, 9usize, 40usize, 3usize);
    let w = [0.2126, 0.7152, 0.0722];
    let mut s = 11u64;
    let mut next = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 * (1.0 / (1u64 << 53) as f64) - 0.5
    };
    let mut x: Vec<f64> = (0..nx * pixels * ch).map(|i| 1.0 + next() + 0.2 * (i % 7) as f64).collect();
    let mut y: Vec<f64> = (0..ny * pixels * ch).map(|_| 1.0 + 2.0 * next()).collect();
    for c in 0..ch {
        for k in 0..nx {
            x[k * pixels * ch + 5 * ch + c] = 2.0; // pixel 5: constant in both
        }
        for k in 0..ny {
            y[k * pixels * ch + 5 * ch + c] = 2.0;
        }
    }
    x[2 * pixels * ch + 7 * ch + 1] = f64::NAN; // pixel 7
    let xf: Vec<f32> = x.iter().map(|&v| v as f32).collect();
    let yf: Vec<f32> = y.iter().map(|&v| v as f32).collect();
    for f32_ in [false, true] {
        let r = if f32_ {
            t_test_2_pixels_f32(&xf, nx, &yf, ny, pixels, ch, Some(&w), 0.0, Alternative::TwoSided, 0.05, RowFlags::default())
        } else {
            t_test_2_pixels(&x, nx, &y, ny, pixels, ch, Some(&w), 0.0, Alternative::TwoSided, 0.05, RowFlags::default())
        }
        .unwrap();
        let lo = r.conf_lo.as_ref().unwrap();
        let hi = r.conf_hi.as_ref().unwrap();
        for i in 0..pixels {
            let val = |k: usize, c: usize, isx: bool| -> f64 {
                let j = k * pixels * ch + i * ch + c;
                match (isx, f32_) {
                    (true, true) => xf[j] as f64,
                    (true, false) => x[j],
                    (false, true) => yf[j] as f64,
                    (false, false) => y[j],
                }
            };
            let sx: Vec<f64> = (0..nx).map(|k| (0..ch).fold(0.0, |a, c| a + w[c] * val(k, c, true))).collect();
            let sy: Vec<f64> = (0..ny).map(|k| (0..ch).fold(0.0, |a, c| a + w[c] * val(k, c, false))).collect();
            let one = t_test_2(&sx, &sy, 0.0, Alternative::TwoSided, 0.05);
            if i == 5 || i == 7 {
                assert!(one.is_err() && r.status[i] != 0 && r.p_value[i].is_nan() && lo[i].is_nan(), "pixel {i}");
                continue;
            }
            let one = one.unwrap();
            assert_eq!(r.status[i], 0, "pixel {i}");
            assert!((r.p_value[i] - one.p_value()).abs() <= 6e-14 * one.p_value(), "pixel {i}: p {} vs {}", r.p_value[i], one.p_value());
            assert!((r.statistic[i] - one.statistic()).abs() <= 1e-14 * one.statistic().abs().max(1.0), "pixel {i}");
            assert!((r.df[i] - one.df()[0]).abs() <= 1e-13 * one.df()[0], "pixel {i}");
            let (l, h) = one.conf_int().unwrap();
            assert!((lo[i] - l).abs() <= 1e-13 * l.abs().max(1.0) && (hi[i] - h).abs() <= 1e-13 * h.abs().max(1.0), "pixel {i}");
        }
    }
    let r = t_test_2_pixels(&x, nx, &y, ny, pixels, ch, Some(&w), 0.0, Alternative::TwoSided, 0.05,
                            RowFlags { no_intervals: true, omit_nan: false }).unwrap();
    assert!(r.conf_lo.is_none() && r.conf_hi.is_none() && r.p_value.len() == pixels);
}

#[test]
fn pixels_bad_arguments() {
    let x = vec![0.0; 12];
    let d = RowFlags::default();
    let a = Alternative::TwoSided;
    assert!(t_test_2_pixels(&x, 3, &x, 3, 5, 1, None, 0.0, a, 0.05, d).is_err()); // 15 values needed
    assert!(t_test_2_pixels(&x, 2, &x, 2, 2, 3, Some(&[1.0, 1.0]), 0.0, a, 0.05, d).is_err());
    assert!(t_test_2_pixels(&x, 2, &x, 2, 2, 3, None, 0.0, a, 0.05, d).is_err());
    assert!(t_test_2_pixels(&x, 2, &x, 2, 6, 1, None, 0.0, a, 1.5, d).is_err());
    assert!(t_test_2_pixels_f32(&[], 2, &[], 2, 0, 1, None, 0.0, a, 0.05, d).is_ok());
}

#[test]
fn t_quantiles_match_the_single_call() {
    let df: Vec<f64> = (0..500).map(|i| 1.0 + 0.37 * i as f64).chain([0.5, 2e3, 1e9]).collect();
    for &(p, upper) in &[(0.025, true), (1e-9, false), (0.4, true)] {
        let x = mcstat::dist::t_quantiles(p, &df, upper).unwrap();
        for (d, q) in df.iter().zip(&x) {
            let want = mcstat::dist::t_quantile(p, *d, upper).unwrap();
            assert!((q - want).abs() <= 2e-14 * want.abs(), "p {p} df {d}: {q} vs {want}");
        }
    }
    assert!(mcstat::dist::t_quantiles(0.05, &[3.0, f64::NAN], true).is_err());
    assert!(mcstat::dist::t_quantiles(f64::NAN, &[3.0], true).is_err());
    assert!(mcstat::dist::t_quantiles(0.05, &[], true).unwrap().is_empty());
}
