//! Every refusal of the renderer checks says why, in libmcstat's words: the
//! crate converts its arguments and passes C's reason on verbatim
//! (mcstat_last_error(), read on the calling thread), so each range is
//! written once, in C.  The cases are tests/python/test_check_reasons.py's
//! with C's "options."/"model." prefix kept (the Rust names are C's); each
//! compares the whole message, so a reason that drifts from the field's
//! name or value fails; and the crate's source holds none of the ranges.
use mcstat::check::{check_bsdf, check_medium, check_phase, check_warp, check_work_size, CheckModel, CheckOptions, Domain, Lobe, Samples};
use mcstat::{sys, Error, ErrorKind};
use std::ffi::CStr;
use std::f64::consts::PI;

const WI: [f64; 3] = [0.0, 0.0, 1.0];

/// A Lambertian BSDF sampled by its cosine, on `domain` with `n_uniforms`.
fn lambert<'a>(domain: Domain, n_uniforms: usize) -> CheckModel<'a> {
    CheckModel::new(
        domain,
        n_uniforms,
        move |s: Samples<'_>| {
            for k in 0..s.weight.len() {
                let (u0, u1) = (s.u[n_uniforms * k], s.u[n_uniforms * k + 1]);
                let (r, phi) = (u0.sqrt(), 2.0 * PI * u1);
                let z = (1.0 - u0).max(0.0).sqrt();
                s.x[3 * k..3 * k + 3].copy_from_slice(&[r * phi.cos(), r * phi.sin(), z]);
                s.weight[k] = 1.0;
                s.pdf[k] = z / PI;
            }
            Ok(())
        },
        |_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
            for (o, p) in out.iter_mut().zip(x.chunks(3)) {
                *o = p[2].max(0.0) / PI;
            }
            Ok(())
        },
    )
    .eval(|_wi: Option<&[f64; 3]>, x: &[f64], out: &mut [f64]| {
        for (o, p) in out.iter_mut().zip(x.chunks(3)) {
            *o = p[2].max(0.0) / PI;
        }
        Ok(())
    })
}

fn bsdf() -> CheckModel<'static> {
    lambert(Domain::Hemisphere, 2)
}

fn opts(f: impl FnOnce(&mut CheckOptions)) -> CheckOptions {
    let mut o = CheckOptions::default();
    f(&mut o);
    o
}

fn refusal(r: mcstat::Result<mcstat::CheckReport>) -> Error {
    match r {
        Ok(rep) => panic!("accepted:\n{rep}"),
        Err(e) => e,
    }
}

fn assert_reason(e: &Error, kind: ErrorKind, reason: &str) {
    assert_eq!(e.kind(), kind, "{e}");
    assert_eq!(e.message(), reason);
    assert_eq!(e.to_string(), format!("{reason} (mcstat status {})", e.status()));
}

#[test]
fn bsdf_refusals_are_cs_reasons() {
    let d = CheckOptions::default();
    let cases: Vec<(mcstat::Result<mcstat::CheckReport>, &str)> = vec![
        (check_bsdf(&mut bsdf(), WI, 10, 0, 0.01, &d), "n must be at least 1000, got 10"),
        (check_bsdf(&mut bsdf(), WI, 5000, 0, 1.5, &d), "alpha must be in (0, 1), got 1.5"),
        (
            check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.cells = Some(1))),
            "options.cells must be 0 (automatic) or 2..1048576, got 1",
        ),
        (check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.batch = 3)), "options.batch must be in 64..2^32, got 3"),
        (check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.rtol = 0.0)), "options.rtol must be in (0, 1), got 0"),
        (
            check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.tolerated = 1.0)),
            "options.tolerated must be in [0, 1), got 1",
        ),
        (
            check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.resolution = Some(0.5))),
            "options.resolution must be 0 (derived from the values) or in (0, 0.01), got 0.5",
        ),
        (
            check_bsdf(&mut lambert(Domain::Hemisphere, 9), WI, 5000, 0, 0.01, &d),
            "model.n_uniforms must be in 1..8, got 9",
        ),
        (
            check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.n_pilot = Some(10))),
            "options.n_pilot must be 0 (automatic) or at least 64, got 10",
        ),
        (
            check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.n_eval = Some(10))),
            "options.n_eval must be 0 (n) or at least 1000, got 10",
        ),
        (
            check_bsdf(&mut lambert(Domain::Disk, 2), WI, 5000, 0, 0.01, &d),
            "model.domain of a BSDF must be sphere or hemisphere (directions), got disk",
        ),
        (check_bsdf(&mut bsdf(), [0.0; 3], 5000, 0, 0.01, &d), "wi must be a finite, non-zero direction, got (0, 0, 0)"),
    ];
    for (r, reason) in cases {
        assert_reason(&refusal(r), ErrorKind::InvalidArgument, reason);
    }
}

#[test]
fn too_big_has_a_reason() {
    let n = (1usize << 48) + 1;
    let e = refusal(check_bsdf(&mut bsdf(), WI, n, 0, 0.01, &CheckOptions::default()));
    assert_reason(&e, ErrorKind::TooBig, &format!("n must be at most 2^48, got {n}"));
}

#[test]
fn other_checks_give_reasons() {
    let d = CheckOptions::default();
    let warp = || {
        CheckModel::new(
            Domain::Square,
            2,
            |s: Samples<'_>| {
                s.x.copy_from_slice(s.u);
                Ok(())
            },
            |_wi: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
                out.iter_mut().for_each(|o| *o = 1.0);
                Ok(())
            },
        )
        .sample_reports(false)
    };
    let e = refusal(check_warp(&mut warp(), 10, 0, 0.01, &d));
    assert_reason(&e, ErrorKind::InvalidArgument, "n must be at least 1000, got 10");
    let mut medium = CheckModel::new(
        Domain::Interval,
        1,
        |s: Samples<'_>| {
            s.x.copy_from_slice(s.u);
            s.weight.iter_mut().for_each(|w| *w = 1.0);
            s.pdf.iter_mut().for_each(|p| *p = 1.0);
            Ok(())
        },
        |_wi: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
            out.iter_mut().for_each(|o| *o = 1.0);
            Ok(())
        },
    )
    .eval(|_wi: Option<&[f64; 3]>, _x: &[f64], out: &mut [f64]| {
        out.iter_mut().for_each(|o| *o = 1.0);
        Ok(())
    });
    let e = refusal(check_medium(&mut medium, -1.0, 5000, 0, 0.01, &d));
    assert_reason(&e, ErrorKind::InvalidArgument, "sigma_ref must be finite and > 0, got -1");
    // what only a BSDF takes: C's reason, not one of the crate's own
    let mut lobed = lambert(Domain::Sphere, 2).lobes(|_wi: &[f64; 3]| Ok(Vec::<Lobe>::new()));
    let e = refusal(check_phase(&mut lobed, WI, 5000, 0, 0.01, &d));
    let reason = "model.lobes is set in the check of a phase function: discrete lobes are a BSDF's";
    assert_reason(&e, ErrorKind::InvalidArgument, reason);
    // mcstat_check_work_size gives reasons too
    let e = check_work_size(&bsdf(), 5000, &opts(|o| o.cells = Some(1))).unwrap_err();
    assert_reason(&e, ErrorKind::InvalidArgument, "options.cells must be 0 (automatic) or 2..1048576, got 1");
}

/// Conversions stay the crate's: C's int32_t would not hold these values.
#[test]
fn conversions_are_the_crates() {
    let e = refusal(check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.cells = Some(u32::MAX))));
    assert_reason(&e, ErrorKind::InvalidArgument, &format!("options.cells {} does not fit C's int32_t", u32::MAX));
    if let Some(nu) = (i32::MAX as usize).checked_add(3) {
        let e = refusal(check_bsdf(&mut lambert(Domain::Hemisphere, nu), WI, 5000, 0, 0.01, &CheckOptions::default()));
        assert_reason(&e, ErrorKind::InvalidArgument, &format!("model.n_uniforms {nu} does not fit C's int32_t"));
    }
}

fn last_error() -> String {
    unsafe { CStr::from_ptr(sys::mcstat_last_error()) }.to_string_lossy().into_owned()
}

#[test]
fn a_later_success_leaves_no_reason() {
    let e = refusal(check_bsdf(&mut bsdf(), WI, 10, 0, 0.01, &CheckOptions::default()));
    assert_eq!(e.kind(), ErrorKind::InvalidArgument);
    assert_eq!(last_error(), "n must be at least 1000, got 10");
    let r = check_bsdf(&mut bsdf(), WI, 2000, 1, 0.01, &CheckOptions::default()).unwrap();
    assert!(!r.reject(), "{r}");
    assert_eq!(last_error(), "");
    assert!(check_work_size(&bsdf(), 2000, &CheckOptions::default()).unwrap() > 0);
}

#[test]
fn each_thread_keeps_its_reason() {
    let threads: Vec<_> = (0..4u64)
        .map(|k| {
            std::thread::spawn(move || {
                let batch = 3 + k;
                for _ in 0..20 {
                    let e = refusal(check_bsdf(&mut bsdf(), WI, 5000, 0, 0.01, &opts(|o| o.batch = batch)));
                    assert_eq!(e.message(), format!("options.batch must be in 64..2^32, got {batch}"));
                }
            })
        })
        .collect();
    for t in threads {
        t.join().unwrap();
    }
}

/// The checks' code (comments dropped: the docs may state the ranges)
/// neither says nor tests the ranges libmcstat checks.
#[test]
fn the_crate_holds_no_range() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/check.rs");
    let text = std::fs::read_to_string(path).unwrap();
    let code: String = text.lines().map(|l| l.split("//").next().unwrap_or("")).collect::<Vec<_>>().join("\n");
    for literal in [
        "1048576",
        "1 << 20",
        "2^32",
        "<< 32",
        "(0, 0.01)",
        "at least",
        "must be in (0, 1)",
        "must be in 1..",
        "finite and > 0",
        "non-zero",
        "MAX_UNIFORMS",
        "sphere or hemisphere",
        "check_medium's only",
        "only check_bsdf",
    ] {
        assert!(!code.contains(literal), "check.rs holds {literal:?}");
    }
    // no comparison of a field C checks, as `x < 1000` or `(0.0..1.0).contains(&x)`
    let fields = ["n_uniforms", "cells", "batch", "rtol", "tolerated", "resolution", "n_pilot", "n_eval", "alpha", "sigma_ref"];
    for field in fields {
        for (i, _) in code.match_indices(field) {
            let after = code[i + field.len()..].trim_start();
            let compared = ["<", ">", "=="].iter().any(|op| after.starts_with(op));
            let before = code[..i].trim_end_matches(|c: char| c == '.' || c == '&' || c.is_alphanumeric() || c == '_');
            let contained = before.ends_with("contains(");
            let at: String = code[i..].chars().take(60).collect();
            assert!(!compared && !contained, "check.rs compares {field}: {at}");
        }
    }
}

/// The t and variance tests give C's reason too.
#[test]
fn test_refusal_is_c_reason() {
    use mcstat::{t_test_1, t_test_2, var_test_1, Alternative};
    let x = [1.0, 2.5, 3.0, 4.5, 2.0];
    for (err, want) in [
        (t_test_1(&x, 0.0, Alternative::TwoSided, 1.5).unwrap_err(), "alpha must be in (0, 1), got 1.5"),
        (var_test_1(&x, -1.0, Alternative::TwoSided, 0.05).unwrap_err(), "sigma2 must be finite and > 0, got -1"),
        (t_test_2(&x, &x, f64::INFINITY, Alternative::Less, 0.05).unwrap_err(), "mu0 must be finite, got inf"),
    ] {
        assert_eq!(err.kind(), ErrorKind::InvalidArgument, "{err}");
        assert_eq!(err.message(), want);
    }
    t_test_1(&x, 0.0, Alternative::TwoSided, 0.05).unwrap();
    let why = unsafe { CStr::from_ptr(sys::mcstat_last_error()) }.to_string_lossy().into_owned();
    assert_eq!(why, "", "a success leaves no reason");
}
