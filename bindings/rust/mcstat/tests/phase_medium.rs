//! check_phase and check_medium: an isotropic phase function (correct, and
//! short by 10% in eval and weight together) and homogeneous free flights
//! up to a surface (correct, and pdf() with sigma_t 10% off).
use mcstat::check::{check_medium, check_phase, CheckModel, CheckOptions, Domain, Route, Samples};
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

fn homogeneous<'a>(pdf_sigma: f64) -> CheckModel<'a> {
    const ST: f64 = 2.0;
    const SS: f64 = 1.5;
    const TMAX: f64 = 1.0;
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
                s.weight[k] = if inside { SS / ST } else { 0.0 };
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
