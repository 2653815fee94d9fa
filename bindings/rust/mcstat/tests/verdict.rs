//! The numerical floor and the three verdicts, as tests/python/
//! test_check_resolution.py checks them: a float32 isotropic phase function
//! (eval = pdf = the float32 1/(4 pi)) passes with the derived floor and is
//! rejected without it; a BSDF whose eval() divides by the cosine (weights
//! rho/cos^2, heavy-tailed) is inconclusive, with the routes and why.
use mcstat::check::{check_bsdf, check_phase, CheckModel, CheckOptions, Domain, Route, Samples, Verdict};
use std::f64::consts::PI;

fn isotropic_f32<'a>() -> CheckModel<'a> {
    let p = (1.0f32 / (4.0 * std::f32::consts::PI)) as f64;
    CheckModel::new(
        Domain::Sphere,
        2,
        move |s: Samples<'_>| {
            for k in 0..s.weight.len() {
                let z = 1.0 - 2.0 * s.u[2 * k] as f32;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = 2.0 * std::f32::consts::PI * s.u[2 * k + 1] as f32;
                s.x[3 * k] = (r * phi.cos()) as f64;
                s.x[3 * k + 1] = (r * phi.sin()) as f64;
                s.x[3 * k + 2] = z as f64;
                s.weight[k] = 1.0;
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
        out.iter_mut().for_each(|o| *o = p);
        Ok(())
    })
}

#[test]
fn float32_rounding_is_not_evidence() {
    let wi = [0.0, 0.0, 1.0];
    let r = check_phase(&mut isotropic_f32(), wi, 100_000, 0, 0.01, &CheckOptions::default()).unwrap();
    assert!(!r.reject(), "{r}");
    assert_eq!(r.route(Route::Integrals).resolution(), Some(2f64.powi(-18)));
    assert_eq!(r.route(Route::PdfValue).resolution(), None);
    let opt = CheckOptions { resolution: Some(2f64.powi(-47)), ..CheckOptions::default() };
    let low = check_phase(&mut isotropic_f32(), wi, 100_000, 0, 0.01, &opt).unwrap();
    assert!(low.route(Route::Integrals).reject(), "{low}");
    let bad = CheckOptions { resolution: Some(0.5), ..CheckOptions::default() };
    assert!(check_phase(&mut isotropic_f32(), wi, 100_000, 0, 0.01, &bad).is_err());
}

/// f |cos| = rho 3 cos^2/(2 pi), sampled exactly; wrong: eval() without the
/// cos^2 (the cosine divided where it should multiply), sample() reusing it.
fn cosine_bsdf<'a>(wrong: bool) -> CheckModel<'a> {
    let rho = 0.8;
    let eval = move |c: f64| if c > 0.0 { rho * 3.0 / (2.0 * PI) * if wrong { 1.0 } else { c * c } } else { 0.0 };
    let pdf = |c: f64| if c > 0.0 { 3.0 * c * c / (2.0 * PI) } else { 0.0 };
    CheckModel::new(
        Domain::Hemisphere,
        3,
        move |s: Samples<'_>| {
            for k in 0..s.weight.len() {
                let c = (1.0 - s.u[3 * k]).cbrt().clamp(1e-12, 1.0);
                let r = (1.0 - c * c).max(0.0).sqrt();
                let phi = 2.0 * PI * s.u[3 * k + 1];
                s.x[3 * k] = r * phi.cos();
                s.x[3 * k + 1] = r * phi.sin();
                s.x[3 * k + 2] = c;
                s.pdf[k] = pdf(c);
                s.weight[k] = eval(c) / pdf(c);
            }
            Ok(())
        },
        move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (k, o) in out.iter_mut().enumerate() {
                *o = pdf(x[3 * k + 2]);
            }
            Ok(())
        },
    )
    .eval(move |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        for (k, o) in out.iter_mut().enumerate() {
            *o = eval(x[3 * k + 2]);
        }
        Ok(())
    })
}

#[test]
fn heavy_tails_are_inconclusive() {
    let wi = [0.0, 0.0, 1.0];
    let ok = check_bsdf(&mut cosine_bsdf(false), wi, 20_000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert_eq!(ok.verdict(), Verdict::Consistent, "{ok}");
    assert!(ok.unanswered().is_empty());
    let r = check_bsdf(&mut cosine_bsdf(true), wi, 20_000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(!r.reject(), "{r}");
    assert_eq!(r.verdict(), Verdict::Inconclusive, "{r}");
    assert_eq!(r.verdict().name(), "inconclusive");
    let open = r.unanswered();
    assert!(open.contains(&Route::Integrals) && open.contains(&Route::Energy), "{open:?}");
    assert!(r.route(Route::Energy).why().unwrap().contains("heavy-tailed"));
    assert!(r.route(Route::Cells).why().is_none());
    assert!(r.to_string().contains("INCONCLUSIVE"));
}
