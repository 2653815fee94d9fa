//! check_phase and check_medium: an isotropic phase function (correct, and
//! short by 10% in eval and weight together), homogeneous free flights up
//! to a surface (correct, and pdf() with sigma_t 10% off), and the escapes'
//! weights against T(tmax) (analog escapes of weight 1, and 10% low).
use mcstat::check::{check_medium, check_phase, CheckModel, CheckOptions, Domain, Route, Samples, WeightConvention};
use mcstat::ErrorKind;
use std::f64::consts::PI;

fn isotropic<'a>(scale: f64) -> CheckModel<'a> {
    let p = 1.0 / (4.0 * PI);
    CheckModel::new(
        Domain::Sphere,
        2,
        move |s: Samples<'_>| {
            for k in 0..s.weight.len() {
                let z = 1.0 - 2.0 * s.u[2 * k];
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * PI * s.u[2 * k + 1];
                s.x[3 * k] = r * phi.cos();
                s.x[3 * k + 1] = r * phi.sin();
                s.x[3 * k + 2] = z;
                s.weight[k] = scale;
                s.pdf[k] = p;
            }
            Ok(())
        },
        move |_wi: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
            out.iter_mut().for_each(|o| *o = p);
            Ok(())
        },
    )
    .eval(move |_wi: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
        out.iter_mut().for_each(|o| *o = scale * p);
        Ok(())
    })
}

#[test]
fn phase_normalisation() {
    let ok = check_phase(&mut isotropic(1.0), [0.0, 0.6, 0.8], 5000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(!ok.reject(), "{ok}");
    let short = check_phase(&mut isotropic(0.9), [0.0, 0.6, 0.8], 5000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(short.reject() && short.route(Route::Energy).reject(), "{short}");
    assert!(check_phase(&mut isotropic(1.0), [0.0, 0.0, 0.0], 5000, 1, 0.01, &CheckOptions::default()).is_err());
}

const ST: f64 = 2.0;
const SS: f64 = 1.5;
const TMAX: f64 = 1.0;

fn homogeneous<'a>(pdf_sigma: f64) -> CheckModel<'a> {
    flights(pdf_sigma, 0.0)
}

/// Analog flights (sigma_t ST) whose escapes carry the weight `escape`
/// (0: failed samples; 1: the weight analog tracking carries on), as
/// tests/c/test_check_phase.c's med_sample_esc.
fn flights<'a>(pdf_sigma: f64, escape: f64) -> CheckModel<'a> {
    let density = |t: f64, s: f64| if t < TMAX { s * (-s * t).exp() } else { 0.0 };
    CheckModel::new(
        Domain::Interval,
        1,
        move |s: Samples<'_>| {
            for k in 0..s.weight.len() {
                let t = -(-s.u[k]).ln_1p() / ST;
                let inside = t < TMAX;
                s.x[k] = if inside { t } else { 0.0 };
                s.pdf[k] = if inside { density(t, ST) } else { 0.0 };
                s.weight[k] = if inside { SS / ST } else { escape };
            }
            Ok(())
        },
        move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (o, &t) in out.iter_mut().zip(x) {
                *o = density(t, pdf_sigma);
            }
            Ok(())
        },
    )
    .eval(move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        for (o, &t) in out.iter_mut().zip(x) {
            *o = SS / ST * density(t, ST);
        }
        Ok(())
    })
}

#[test]
fn medium_distance_sampling() {
    let ok = check_medium(&mut homogeneous(2.0), 2.0, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(!ok.reject(), "{ok}");
    let bad = check_medium(&mut homogeneous(2.2), 2.0, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(bad.reject() && bad.route(Route::PdfValue).reject(), "{bad}");
    assert!(check_medium(&mut homogeneous(2.0), 0.0, 20000, 1, 0.01, &CheckOptions::default()).is_err());
}

fn with_escapes(t: f64) -> CheckOptions {
    CheckOptions { escape_transmittance: Some(t), ..Default::default() }
}

#[test]
fn medium_escape_weights() {
    let t = (-ST * TMAX).exp();
    let none = check_medium(&mut homogeneous(2.0), 2.0, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert_eq!((none.escape_weight(), none.escape_weight_se()), (None, None));
    // analog escapes of weight 1: their mean over the flights is the escape share
    let ok = check_medium(&mut flights(2.0, 1.0), 2.0, 20000, 1, 0.01, &with_escapes(t)).unwrap();
    assert!(!ok.reject(), "{ok}");
    let share = ok.n_failed() as f64 / ok.n() as f64;
    let mean = ok.escape_weight().unwrap();
    assert!((mean - share).abs() <= 1e-12 * share, "escape weight {mean} vs share {share}");
    assert!(ok.escape_weight_se().unwrap() > 0.0);
    let mass = ok.route(Route::Mass);
    assert_eq!((mass.raw().value[0], mass.raw().value[1]), (mean, t));
    assert!(ok.to_string().contains("escape weights"), "{ok}");
    // escapes 10% light: the mass route sees it
    let light = check_medium(&mut flights(2.0, 0.9), 2.0, 20000, 1, 0.01, &with_escapes(t)).unwrap();
    assert!(light.reject() && light.route(Route::Mass).reject(), "{light}");
}

#[test]
fn medium_escape_transmittance_refused() {
    for bad in [f64::NAN, -0.5, 1.5, f64::INFINITY] {
        let e = check_medium(&mut flights(2.0, 1.0), 2.0, 20000, 1, 0.01, &with_escapes(bad)).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{bad}: {e}");
        assert!(e.to_string().contains("escape_transmittance"), "{bad}: {e}");
    }
    let mut value = flights(2.0, 1.0).weight(WeightConvention::Value);
    let e = check_medium(&mut value, 2.0, 20000, 1, 0.01, &with_escapes(0.5)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{e}");
    assert!(e.to_string().contains("escape_transmittance"), "{e}");
    let e = check_phase(&mut isotropic(1.0), [0.0, 0.6, 0.8], 5000, 1, 0.01, &with_escapes(0.5)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument, "{e}");
    assert_eq!(e.message(), "options.escape_transmittance is 0.5 in the check of a phase function: it is a medium's");
}
