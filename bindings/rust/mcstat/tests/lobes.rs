//! check_bsdf with discrete lobes: a coated diffuse BSDF (a specular
//! reflection picked with probability Q, weight F/Q, over a Lambertian
//! base), as in tests/c/test_check_lobes.c: correct with its lobe; its
//! specular samples rejected by pdf_value without it; the specular weight
//! 5% off rejected by weight; lobes() failing, panicking or giving too many
//! lobes stopping the check with Error::Callback naming lobes().
use mcstat::check::{check_bsdf, check_emitter, CallbackResult, CheckModel, CheckOptions, Domain, Lobe, Route, Samples, MAX_LOBES};
use mcstat::ErrorKind;
use std::f64::consts::PI;

const Q: f64 = 0.3;
const RHO: f64 = 0.6;
const WI: [f64; 3] = [0.4, 0.1, 0.9];

fn fresnel(c: f64) -> f64 {
    0.04 + 0.96 * (1.0 - c).powi(5)
}

fn mirror(wi: &[f64; 3]) -> [f64; 3] {
    [-wi[0], -wi[1], wi[2]]
}

/// The coated BSDF without its lobes; `spec_weight` scales the specular
/// samples' weight (1: correct).
fn coated<'a>(spec_weight: f64) -> CheckModel<'a> {
    CheckModel::new(
        Domain::Hemisphere,
        3,
        move |s: Samples<'_>| {
            let wi = s.wi.expect("a BSDF check has wi");
            let f = fresnel(wi[2]);
            for k in 0..s.len() {
                let u = &s.u[3 * k..3 * k + 3];
                let d = &mut s.x[3 * k..3 * k + 3];
                if u[0] < Q {
                    d.copy_from_slice(&mirror(wi));
                    s.pdf[k] = Q;
                    s.weight[k] = f / Q * spec_weight;
                } else {
                    let (r, phi) = (u[1].sqrt(), 2.0 * PI * u[2]);
                    d.copy_from_slice(&[r * phi.cos(), r * phi.sin(), (1.0 - u[1]).sqrt()]);
                    s.pdf[k] = (1.0 - Q) * d[2] / PI;
                    s.weight[k] = (1.0 - f) * RHO / (1.0 - Q);
                }
            }
            Ok(())
        },
        |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (k, o) in out.iter_mut().enumerate() {
                *o = (1.0 - Q) * x[3 * k + 2].max(0.0) / PI;
            }
            Ok(())
        },
    )
    .eval(|wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        let f = fresnel(wi.expect("wi")[2]);
        for (k, o) in out.iter_mut().enumerate() {
            *o = (1.0 - f) * RHO * x[3 * k + 2].max(0.0) / PI;
        }
        Ok(())
    })
}

fn specular(wi: &[f64; 3]) -> CallbackResult<Vec<Lobe>> {
    Ok(vec![Lobe { direction: mirror(wi), mass: Q, value: fresnel(wi[2]) }])
}

#[test]
fn coated_bsdf_with_its_lobe_passes() {
    let mut calls = 0;
    let mut m = coated(1.0).lobes(|wi: &[f64; 3]| {
        calls += 1;
        specular(wi)
    });
    let r = check_bsdf(&mut m, WI, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    drop(m);
    assert!(!r.reject(), "{r}");
    assert_eq!(calls, 1); // once per check
    assert_eq!(r.lobes(), 1);
    assert!(r.n_lobe() > 5000 && r.n_lobe() < 7000, "{}", r.n_lobe());
    assert!((r.lobe_mass() - Q).abs() < 1e-15);
    // lobes() sees the normalised wi
    let cos = WI[2] / WI.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((r.lobe_albedo() - fresnel(cos)).abs() < 1e-12 * fresnel(cos));
    let (albedo, _) = r.albedo().unwrap(); // the smooth part's
    assert!((albedo / ((1.0 - fresnel(cos)) * RHO) - 1.0).abs() < 0.02, "{albedo}");
    assert_eq!(r.route(Route::PdfValue).checked(), 20000);
    assert!(r.to_string().contains("discrete lobes: 1"), "{r}");
}

#[test]
fn without_lobes_no_lobe_counts_and_pdf_value_rejects() {
    let r = check_bsdf(&mut coated(1.0), WI, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(r.reject() && r.route(Route::PdfValue).reject(), "{r}");
    assert_eq!((r.lobes(), r.n_lobe(), r.lobe_mass(), r.lobe_albedo()), (0, 0, 0.0, 0.0));
}

#[test]
fn a_discrete_weight_error_rejects_by_weight() {
    let mut m = coated(1.05).lobes(specular);
    let r = check_bsdf(&mut m, WI, 20000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(r.reject() && r.route(Route::Weight).reject() && !r.route(Route::PdfValue).reject(), "{r}");
    let effect = r.route(Route::Weight).effect().unwrap();
    assert!((effect - 0.05 / 1.05).abs() < 1e-9, "{effect}");
}

#[test]
fn lobes_errors_panics_and_too_many_lobes_are_callback_errors() {
    let opt = CheckOptions::default();
    let mut m = coated(1.0).lobes(|_wi: &[f64; 3]| Err("no lobes today".into()));
    let e = check_bsdf(&mut m, WI, 20000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains("lobes() returned an error: no lobes today"), "{e}");

    let mut m = coated(1.0).lobes(|_wi: &[f64; 3]| -> CallbackResult<Vec<Lobe>> { panic!("lobes exploded") });
    let e = check_bsdf(&mut m, WI, 20000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains("lobes() panicked: lobes exploded"), "{e}");

    let mut m = coated(1.0).lobes(|wi: &[f64; 3]| {
        let mut v = specular(wi)?;
        for k in 0..MAX_LOBES {
            let a = 0.3 * k as f64;
            v.push(Lobe { direction: [a.sin() * 0.5, a.cos() * 0.5, 0.75f64.sqrt()], mass: 0.0, value: 0.0 });
        }
        Ok(v)
    });
    let e = check_bsdf(&mut m, WI, 20000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains(&format!("lobes() gave {} lobes: at most {MAX_LOBES}", MAX_LOBES + 1)), "{e}");

    // garbage libmcstat finds: a mass that is not a probability
    let mut m = coated(1.0).lobes(|wi: &[f64; 3]| Ok(vec![Lobe { direction: mirror(wi), mass: 1.5, value: 0.1 }]));
    let e = check_bsdf(&mut m, WI, 20000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Callback);
    assert!(e.message().contains("lobes()") && e.message().contains("mass 1.5"), "{e}");

    // lobes are a BSDF's: libmcstat refuses them elsewhere and says so (an
    // emitter: a hemisphere is an emitter's domain, not a phase function's)
    let mut m = coated(1.0).lobes(specular);
    let e = check_emitter(&mut m, 20000, 1, 0.01, &opt).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(e.message(), "model.lobes is set in the check of an emitter: discrete lobes are a BSDF's");
}
