use super::*;
use std::mem::{size_of, MaybeUninit};

/// Byte offset of a (possibly nested, possibly union) field.
macro_rules! offset {
    ($t:ty, $($f:tt)+) => {{
        let u = MaybeUninit::<$t>::uninit();
        let base = u.as_ptr();
        #[allow(unused_unsafe)]
        unsafe { (std::ptr::addr_of!((*base).$($f)+) as *const u8).offset_from(base as *const u8) as usize }
    }};
}

#[test]
fn sizes_match_the_library() {
    unsafe {
        assert_eq!(size_of::<mcstat_moments>(), mcstat_sizeof_moments());
        assert_eq!(size_of::<mcstat_result>(), mcstat_sizeof_result());
        assert_eq!(size_of::<mcstat_stream>(), mcstat_sizeof_stream());
        assert_eq!(size_of::<mcstat_ks_options>(), mcstat_sizeof_ks_options());
        assert_eq!(size_of::<mcstat_power_options>(), mcstat_sizeof_power_options());
        assert_eq!(size_of::<mcstat_diag_options>(), mcstat_sizeof_diag_options());
        assert_eq!(size_of::<mcstat_diagnostics>(), mcstat_sizeof_diagnostics());
        assert_eq!(size_of::<mcstat_gof_options>(), mcstat_sizeof_gof_options());
        assert_eq!(size_of::<mcstat_check_options>(), mcstat_sizeof_check_options());
        assert_eq!(size_of::<mcstat_check_model>(), mcstat_sizeof_check_model());
        assert_eq!(size_of::<mcstat_check_report>(), mcstat_sizeof_check_report());
        assert_eq!(size_of::<mcstat_seq_options>(), mcstat_sizeof_seq_options());
        assert_eq!(size_of::<mcstat_seq>(), mcstat_sizeof_seq());
        assert_eq!(mcstat_sizeof_moments_bytes(), MCSTAT_MOMENTS_BYTES);
        #[allow(deprecated)]
        {
            assert_eq!(mcstat_moments_bytes(), MCSTAT_MOMENTS_BYTES);
            assert_eq!(mcstat_sizeof_chisq_options(), size_of::<mcstat_chisq_options>());
        }
    }
}

/// Every listed field's offset (and the listed structs' sizes) as Rust lays
/// them out, against the C compiler's offsetof / sizeof on the
/// repository's mcstat.h: a program compiled and run by this test ($CC, or
/// cc).  The fields are those after each change of alignment or union; in C
/// the unions and their structs are anonymous, so a field is its last name.
macro_rules! layout {
    ($( $item:tt $( = $c:literal )? ),* $(,)?) => {{
        let mut v: Vec<(String, String, usize)> = Vec::new();
        $( layout!(@one v, $item $( = $c )?); )*
        v
    }};
    (@one $v:ident, ($t:ident, $($f:tt)+) = $c:literal) => {
        $v.push((stringify!($t).to_string(), format!("offsetof({}, {})", stringify!($t), $c), offset!($t, $($f)+)))
    };
}

macro_rules! sizes {
    ($v:ident, $($t:ident),* $(,)?) => {
        $( $v.push((stringify!($t).to_string(), format!("sizeof({})", stringify!($t)), size_of::<$t>())); )*
    };
}

fn c_compiler_layout(exprs: &[String]) -> Vec<usize> {
    let dir = std::env::temp_dir().join(format!("mcstat-sys-layout-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join("layout.c");
    let mut c = String::from("#include <stddef.h>\n#include <stdio.h>\n#include \"mcstat.h\"\nint main(void)\n{\n");
    for e in exprs {
        c += &format!("    printf(\"%zu\\n\", (size_t){e});\n");
    }
    c += "    return 0;\n}\n";
    std::fs::write(&src, c).unwrap();
    let include = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../libmcstat/include");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
    let exe = dir.join("layout");
    let built = std::process::Command::new(&cc)
        .args(["-std=c11", "-I", include, "-o"])
        .arg(&exe)
        .arg(&src)
        .output()
        .unwrap_or_else(|e| panic!("the C compiler {cc}: {e}"));
    assert!(
        built.status.success(),
        "{cc} failed on {}:\n{}",
        src.display(),
        String::from_utf8_lossy(&built.stderr)
    );
    let out = std::process::Command::new(&exe).output().unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stdout).unwrap().lines().map(|l| l.parse().unwrap()).collect()
}

#[test]
fn layout_matches_the_c_compiler() {
    let mut v = layout![
        (mcstat_moments, mean) = "mean",
        (mcstat_moments, reserved) = "reserved",
        (mcstat_stream, count) = "count",
        (mcstat_stream, n_nonfinite) = "n_nonfinite",
        (mcstat_stream, u.s.n_overflow) = "n_overflow",
        (mcstat_stream, buf) = "buf",
        (mcstat_result, ints.s.ks_weight) = "ks_weight",
        (mcstat_result, ints.s.chisq_n_estimated) = "chisq_n_estimated",
        (mcstat_result, n) = "n",
        (mcstat_result, statistic) = "statistic",
        (mcstat_result, std_error) = "std_error",
        (mcstat_result, per_test.ks.ks_critical_se) = "ks_critical_se",
        (mcstat_result, per_test.tost.tost_upper) = "tost_upper",
        (mcstat_result, per_test.binom.binom_log_p_value) = "binom_log_p_value",
        (mcstat_result, per_test.chisq.chisq_pool_below) = "chisq_pool_below",
        (mcstat_ks_options, cache) = "cache",
        (mcstat_ks_options, critical) = "critical",
        (mcstat_power_options, n) = "n",
        (mcstat_power_options, power) = "power",
        (mcstat_power_options, reserved) = "reserved",
        (mcstat_diag_options, k) = "k",
        (mcstat_diag_options, alpha) = "alpha",
        (mcstat_diag_options, tail_threshold) = "tail_threshold",
        (mcstat_diagnostics, heavy_tail) = "heavy_tail",
        (mcstat_diagnostics, mean) = "mean",
        (mcstat_diagnostics, tail_index) = "tail_index",
        (mcstat_diagnostics, t_size) = "t_size",
        (mcstat_diagnostics, reserved) = "reserved",
        (mcstat_gof_options, min_expected) = "min_expected",
        (mcstat_gof_options, n_estimated) = "n_estimated",
        (mcstat_check_model, user) = "user",
        (mcstat_check_model, sample) = "sample",
        (mcstat_check_model, eval) = "eval",
        (mcstat_check_model, extra) = "reserved", // the anonymous union's first member
        (mcstat_check_model, extra.s.lobes) = "lobes",
        (mcstat_check_model, extra.s.reserved_rest) = "reserved_rest",
        (mcstat_check_options, n_pilot) = "n_pilot",
        (mcstat_check_options, batch) = "batch",
        (mcstat_check_options, rtol) = "rtol",
        (mcstat_check_options, reserved) = "reserved",
        (mcstat_check_options, escape_transmittance) = "escape_transmittance",
        (mcstat_check_route_result, statistic) = "statistic",
        (mcstat_check_route_result, checked) = "checked",
        (mcstat_check_route_result, r#where) = "where",
        (mcstat_check_route_result, value) = "value",
        (mcstat_check_route_result, resolution) = "resolution",
        (mcstat_check_report, alpha) = "alpha",
        (mcstat_check_report, wi) = "wi",
        (mcstat_check_report, n) = "n",
        (mcstat_check_report, mass) = "mass",
        (mcstat_check_report, tail_index) = "tail_index",
        (mcstat_check_report, extra) = "reserved", // the anonymous union's first member
        (mcstat_check_report, route) = "route",
        (mcstat_check_report, message) = "message",
        (mcstat_result, ints.seq.seq_hold) = "seq_hold",
        (mcstat_result, per_test.seq.seq_looks) = "seq_looks",
        (mcstat_result, per_test.seq.seq_n_gate) = "seq_n_gate",
        (mcstat_seq_options, alpha) = "alpha",
        (mcstat_seq_options, min_n) = "min_n",
        (mcstat_seq, x) = "x",
        (mcstat_seq, y) = "y",
        (mcstat_seq, null_value) = "null_value",
        (mcstat_seq, min_n) = "min_n",
        (mcstat_seq, log_e) = "log_e",
        (mcstat_seq, cs) = "cs",
        (mcstat_seq, reserved) = "reserved",
        (mcstat_escalation, alpha1) = "alpha1",
        (mcstat_escalation, alpha0) = "alpha0",
        (mcstat_escalation, c) = "c",
        (mcstat_result, ints.eff.eff_batches_y) = "eff_batches_y",
        (mcstat_result, per_test.eff.eff_se_log_time_y) = "eff_se_log_time_y",
        (mcstat_check_report, extra.s.zero_weight) = "zero_weight",
        (mcstat_check_report, extra.s.sigma_ref) = "sigma_ref",
        (mcstat_check_report, extra.s.rest) = "reserved_rest",
        (mcstat_check_report, extra.s.rest.s.lobes) = "lobes",
        (mcstat_check_report, extra.s.rest.s.n_lobe) = "n_lobe",
        (mcstat_check_report, extra.s.rest.s.lobe_mass) = "lobe_mass",
        (mcstat_check_report, extra.s.rest.s.lobe_albedo) = "lobe_albedo",
        (mcstat_check_report, extra.s.rest.s.escape_weight) = "escape_weight",
        (mcstat_check_report, extra.s.rest.s.escape_weight_se) = "escape_weight_se",
        (mcstat_pixels_in, data) = "data",
        (mcstat_pixels_in, weights) = "weights",
        (mcstat_pixels_options, threads) = "threads",
        (mcstat_pixels_out, p_value) = "p_value",
        (mcstat_pixels_out, status) = "status",
        (mcstat_pixels_out, decision) = "decision",
        (mcstat_pixels_out, n_y) = "n_y",
    ];
    sizes!(
        v, mcstat_moments, mcstat_result, mcstat_stream, mcstat_ks_options, mcstat_power_options,
        mcstat_diag_options, mcstat_diagnostics, mcstat_gof_options, mcstat_check_model, mcstat_check_options,
        mcstat_check_route_result, mcstat_check_report, mcstat_seq_options, mcstat_seq, mcstat_escalation,
        mcstat_pixels_in, mcstat_pixels_options, mcstat_pixels_out
    );
    // the header's constants of the discrete lobes (the tolerance as its reciprocal)
    v.push(("const".to_string(), "MCSTAT_CHECK_MAX_LOBES".to_string(), MCSTAT_CHECK_MAX_LOBES));
    v.push((
        "const".to_string(),
        "(1 / MCSTAT_CHECK_LOBE_TOLERANCE + 0.5)".to_string(),
        (1.0 / MCSTAT_CHECK_LOBE_TOLERANCE).round() as usize,
    ));
    // the options' sizes by release
    v.push(("const".to_string(), "MCSTAT_CHECK_OPTIONS_SIZE_0_2".to_string(), MCSTAT_CHECK_OPTIONS_SIZE_0_2));
    v.push(("const".to_string(), "MCSTAT_CHECK_OPTIONS_SIZE_0_3".to_string(), MCSTAT_CHECK_OPTIONS_SIZE_0_3));
    // the route result's named storage, and the why and verdict values
    v.push((
        "offset".to_string(),
        "offsetof(mcstat_check_route_result, why)".to_string(),
        std::mem::offset_of!(mcstat_check_route_result, why),
    ));
    v.push((
        "offset".to_string(),
        "offsetof(mcstat_check_options, resolution)".to_string(),
        std::mem::offset_of!(mcstat_check_options, resolution),
    ));
    for (name, value) in [
        ("MCSTAT_CHECK_WHY_HEAVY_TAIL", MCSTAT_CHECK_WHY_HEAVY_TAIL),
        ("MCSTAT_CHECK_WHY_TOO_FEW", MCSTAT_CHECK_WHY_TOO_FEW),
        ("MCSTAT_CHECK_WHY_ENVELOPE", MCSTAT_CHECK_WHY_ENVELOPE),
        ("MCSTAT_CHECK_WHY_NOTHING", MCSTAT_CHECK_WHY_NOTHING),
        ("MCSTAT_CHECK_WHY_NUMERIC", MCSTAT_CHECK_WHY_NUMERIC),
        ("MCSTAT_CHECK_WHY_INTEGRATION", MCSTAT_CHECK_WHY_INTEGRATION),
        ("MCSTAT_CHECK_INCONSISTENT", MCSTAT_CHECK_INCONSISTENT),
        ("MCSTAT_CHECK_INCONCLUSIVE", MCSTAT_CHECK_INCONCLUSIVE),
    ] {
        v.push(("const".to_string(), name.to_string(), value as usize));
    }
    // the resolutions as their reciprocals (2^18, 2^47)
    v.push((
        "const".to_string(),
        "(size_t)(1 / MCSTAT_RESOLUTION_FLOAT32)".to_string(),
        (1.0 / MCSTAT_RESOLUTION_FLOAT32) as usize,
    ));
    v.push((
        "const".to_string(),
        "(size_t)(1 / MCSTAT_RESOLUTION_FLOAT64)".to_string(),
        (1.0 / MCSTAT_RESOLUTION_FLOAT64) as usize,
    ));
    let exprs: Vec<String> = v.iter().map(|e| e.1.clone()).collect();
    let c = c_compiler_layout(&exprs);
    assert_eq!(c.len(), v.len());
    let bad: Vec<String> = v
        .iter()
        .zip(&c)
        .filter(|((_, _, rust), c)| rust != *c)
        .map(|((_, e, rust), c)| format!("{e}: Rust {rust}, C {c}"))
        .collect();
    assert!(bad.is_empty(), "layouts differ: {bad:?}");
}

/// MAJOR.MINOR.PATCH of the repository's mcstat/version.h, the one source of
/// the version: Cargo.toml's and the constants here must follow it.
fn header_version() -> (u32, u32, u32) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../libmcstat/include/mcstat/version.h");
    let text = std::fs::read_to_string(path).expect("the repository's mcstat/version.h");
    let get = |name: &str| -> u32 {
        let key = format!("#define MCSTAT_VERSION_{name} ");
        let line = text.lines().find(|l| l.starts_with(&key)).expect("a version macro");
        line[key.len()..].trim().parse().expect("a number")
    };
    (get("MAJOR"), get("MINOR"), get("PATCH"))
}

#[test]
fn version_is_the_header_version() {
    let (major, minor, patch) = header_version();
    let want = format!("{major}.{minor}.{patch}");
    assert_eq!(env!("CARGO_PKG_VERSION"), want, "Cargo.toml's version differs from mcstat.h's");
    assert_eq!((MCSTAT_VERSION_MAJOR, MCSTAT_VERSION_MINOR, MCSTAT_VERSION_PATCH), (major, minor, patch));
    let v = unsafe { std::ffi::CStr::from_ptr(mcstat_version()) };
    assert_eq!(v.to_str().unwrap(), want);
    assert_eq!(unsafe { mcstat_version_number() }, MCSTAT_VERSION_NUMBER);
}

#[test]
fn ks_options_initialiser_writes_the_callers_size() {
    // a buffer larger than the struct: the sized initialiser writes the
    // struct, nothing beyond; the default starts no thread
    let n = size_of::<mcstat_ks_options>();
    let mut buf = [0xABu8; 128];
    let st = unsafe { mcstat_ks_options_init_size(buf.as_mut_ptr() as *mut mcstat_ks_options, n) };
    assert_eq!(st, MCSTAT_OK);
    assert!(buf[n..].iter().all(|&b| b == 0xAB));
    let o: mcstat_ks_options = unsafe { std::ptr::read_unaligned(buf.as_ptr() as *const mcstat_ks_options) };
    assert_eq!((o.size as usize, o.threads), (n, 1));
    let st = unsafe { mcstat_ks_options_init_size(buf.as_mut_ptr() as *mut mcstat_ks_options, n + 8) };
    assert_eq!(st, MCSTAT_EINVAL);
}

/// 0.1.0's fixed-size initialisers write the 0.1.0 struct, as the sized ones do.
#[test]
fn old_initialisers_equal_the_sized_ones() {
    unsafe {
        let mut a = MaybeUninit::<mcstat_ks_options>::zeroed().assume_init();
        let mut b = a;
        assert_eq!(mcstat_ks_options_init(&mut a), MCSTAT_OK);
        assert_eq!(mcstat_ks_options_init_size(&mut b, MCSTAT_KS_OPTIONS_SIZE_0_1), MCSTAT_OK);
        assert_eq!((a.size, a.weight, a.n_sim, a.critical), (b.size, b.weight, b.n_sim, b.critical));
        let mut p = MaybeUninit::<mcstat_power_options>::zeroed().assume_init();
        let mut q = p;
        assert_eq!(mcstat_power_options_init(&mut p), MCSTAT_OK);
        assert_eq!(mcstat_power_options_init_size(&mut q, size_of::<mcstat_power_options>()), MCSTAT_OK);
        assert_eq!((p.size, p.test, p.alpha, p.n_ratio), (q.size, q.test, q.alpha, q.n_ratio));
        assert_eq!((p.alpha, p.strict), (0.05, 1));
        let mut d = MaybeUninit::<mcstat_diag_options>::zeroed().assume_init();
        let mut e = d;
        assert_eq!(mcstat_diag_options_init(&mut d), MCSTAT_OK);
        assert_eq!(mcstat_diag_options_init_size(&mut e, size_of::<mcstat_diag_options>()), MCSTAT_OK);
        assert_eq!((d.size, d.alpha, d.tolerance, d.tail_threshold), (e.size, 0.05, 0.2, 2.2));
        let mut c = MaybeUninit::<mcstat_check_options>::zeroed().assume_init();
        assert_eq!(mcstat_check_options_init_size(&mut c, size_of::<mcstat_check_options>()), MCSTAT_OK);
        assert_eq!((c.routes, c.batch, c.rtol), (MCSTAT_CHECK_ROUTE_ALL, 65536, 1e-3));
        assert_eq!(c.escape_transmittance, -1.0); // off
        // 0.2's size: the appended field is left as the caller had it
        c.escape_transmittance = 0.5;
        assert_eq!(mcstat_check_options_init_size(&mut c, MCSTAT_CHECK_OPTIONS_SIZE_0_2), MCSTAT_OK);
        assert_eq!((c.size as usize, c.escape_transmittance), (MCSTAT_CHECK_OPTIONS_SIZE_0_2, 0.5));
    }
}

fn data(n: usize, seed: u64) -> Vec<f64> {
    // a fixed, deterministic sample (xorshift), not random per run
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn result() -> mcstat_result {
    unsafe { MaybeUninit::<mcstat_result>::zeroed().assume_init() }
}

/// The deprecated names still link and give bit-identical results.
#[test]
#[allow(deprecated)]
fn deprecated_names_give_the_same_results() {
    let x = data(60, 1);
    let y = data(60, 2);
    unsafe {
        // rows: 0.1.0's order (rows before n) against the _matrix order
        let (mut a, mut b) = ([result(); 3], [result(); 3]);
        let (mut sa, mut sb) = ([9i32; 3], [9i32; 3]);
        assert_eq!(mcstat_t_test_1_rows(x.as_ptr(), 3, 20, 20, 0.5, MCSTAT_TWO_SIDED, 0.05, 0, a.as_mut_ptr(), sa.as_mut_ptr()), 0);
        assert_eq!(mcstat_t_test_1_matrix(x.as_ptr(), 20, 20, 3, 0.5, MCSTAT_TWO_SIDED, 0.05, 0, b.as_mut_ptr(), sb.as_mut_ptr()), 0);
        assert_eq!(sa, [0; 3]);
        for i in 0..3 {
            assert_eq!(a[i].p_value.to_bits(), b[i].p_value.to_bits());
        }
        assert_eq!(mcstat_var_test_1_rows(x.as_ptr(), 3, 20, 20, 0.1, MCSTAT_GREATER, 0.05, 0, a.as_mut_ptr(), sa.as_mut_ptr()), 0);
        assert_eq!(mcstat_var_test_1_matrix(x.as_ptr(), 20, 20, 3, 0.1, MCSTAT_GREATER, 0.05, 0, b.as_mut_ptr(), sb.as_mut_ptr()), 0);
        assert_eq!(a[2].statistic.to_bits(), b[2].statistic.to_bits());
        assert_eq!(mcstat_t_test_2_rows(x.as_ptr(), 20, 20, y.as_ptr(), 20, 20, 3, 0.0, MCSTAT_LESS, 0.05, 0, a.as_mut_ptr(), sa.as_mut_ptr()), 0);
        assert_eq!(mcstat_t_test_2_matrix(x.as_ptr(), 20, 20, y.as_ptr(), 20, 20, 3, 0.0, MCSTAT_LESS, 0.05, 0, b.as_mut_ptr(), sb.as_mut_ptr()), 0);
        assert_eq!(a[1].df[0].to_bits(), b[1].df[0].to_bits());
        assert_eq!(mcstat_var_test_2_rows(x.as_ptr(), 20, 20, y.as_ptr(), 20, 20, 3, 1.0, MCSTAT_TWO_SIDED, 0.05, 0, a.as_mut_ptr(), sa.as_mut_ptr()), 0);
        assert_eq!(mcstat_var_test_2_matrix(x.as_ptr(), 20, 20, y.as_ptr(), 20, 20, 3, 1.0, MCSTAT_TWO_SIDED, 0.05, 0, b.as_mut_ptr(), sb.as_mut_ptr()), 0);
        assert_eq!(a[0].p_value.to_bits(), b[0].p_value.to_bits());

        // goodness of fit
        let obs = [22.0, 21.0, 22.0, 27.0, 22.0, 36.0];
        let p = [1.0 / 6.0; 6];
        let mut o = MaybeUninit::<mcstat_chisq_options>::zeroed().assume_init();
        assert_eq!(mcstat_chisq_options_init_size(&mut o, size_of::<mcstat_chisq_options>()), 0);
        let mut o1 = o;
        assert_eq!(mcstat_chisq_options_init(&mut o1), 0);
        assert_eq!((o1.size as usize, o1.pool), (MCSTAT_CHISQ_OPTIONS_SIZE_0_1, 1));
        assert_eq!(mcstat_chisq_default_min_expected(), mcstat_gof_default_min_expected());
        let (mut r1, mut r2) = (result(), result());
        assert_eq!(mcstat_chisq_gof(obs.as_ptr(), p.as_ptr(), 6, &o, 0.05, &mut r1), 0);
        assert_eq!(mcstat_gof_chisq_test(obs.as_ptr(), p.as_ptr(), 6, &o, 0.05, &mut r2), 0);
        assert_eq!(r1.statistic, 6.72);
        assert_eq!(r1.p_value.to_bits(), r2.p_value.to_bits());
        assert_eq!(r2.ints().chisq_cells, 6);

        // diagnostics
        let z = data(500, 3);
        let mut d1 = MaybeUninit::<mcstat_diagnostics>::zeroed().assume_init();
        let mut d2 = d1;
        assert_eq!(mcstat_diagnose(z.as_ptr(), z.len(), std::ptr::null(), &mut d1), 0);
        assert_eq!(mcstat_diag_compute(z.as_ptr(), z.len(), std::ptr::null(), &mut d2), 0);
        assert_eq!(d1.tail_index[1].to_bits(), d2.tail_index[1].to_bits());
        assert_eq!(d1.recommended_k, d2.recommended_k);
        let (mut i1, mut i2) = ([0.0; 2], [0.0; 2]);
        assert_eq!(mcstat_tail_index(z.as_ptr(), z.len(), 0, i1.as_mut_ptr()), 0);
        assert_eq!(mcstat_diag_tail_index(z.as_ptr(), z.len(), 0, i2.as_mut_ptr()), 0);
        assert_eq!(i1, i2);
        assert_eq!(mcstat_t_size_edgeworth(2.0, 6.0, 1, 30, 0.05, i1.as_mut_ptr()), 0);
        assert_eq!(mcstat_diag_t_size(2.0, 6.0, 1, 30, 0.05, i2.as_mut_ptr()), 0);
        assert_eq!(i1, i2);
        let (mut k1, mut k2) = (0u64, 0u64);
        assert_eq!(mcstat_batch_size_recommend(2.0, 6.0, 30, 0.05, 0.2, &mut k1), 0);
        assert_eq!(mcstat_diag_batch_size(2.0, 6.0, 30, 0.05, 0.2, &mut k2), 0);
        assert!(k1 > 1 && k1 == k2);
    }
}

/// mcstat_stream_add (the header's inline function, in Rust) gives the
/// moments of add_array on the same values, across several flushes.
#[test]
fn stream_add_is_add_array() {
    let x = data(3 * MCSTAT_STREAM_CAPACITY as usize + 17, 4);
    unsafe {
        let mut s: Box<mcstat_stream> = Box::new(MaybeUninit::zeroed().assume_init());
        assert_eq!(mcstat_stream_init(&mut *s), 0);
        for &v in &x {
            mcstat_stream_add(&mut *s, v);
        }
        assert_eq!(s.count, 17);
        assert_eq!(s.moments.n, 3 * MCSTAT_STREAM_CAPACITY as u64);
        assert_eq!(s.n_overflow(), 0);
        let mut via_stream = MaybeUninit::<mcstat_moments>::zeroed().assume_init();
        assert_eq!(mcstat_stream_moments(&*s, &mut via_stream), 0);
        let mut direct = MaybeUninit::<mcstat_moments>::zeroed().assume_init();
        mcstat_moments_init(&mut direct);
        // the stream flushes blocks of CAPACITY values, then the rest
        for chunk in x.chunks(MCSTAT_STREAM_CAPACITY as usize) {
            let mut part = MaybeUninit::<mcstat_moments>::zeroed().assume_init();
            mcstat_moments_init(&mut part);
            mcstat_moments_add_array(&mut part, chunk.as_ptr(), chunk.len());
            mcstat_moments_merge(&mut direct, &part);
        }
        assert_eq!(via_stream.n, direct.n);
        assert_eq!(mcstat_moments_mean(&via_stream).to_bits(), mcstat_moments_mean(&direct).to_bits());
        assert_eq!(mcstat_moments_var(&via_stream).to_bits(), mcstat_moments_var(&direct).to_bits());
    }
}

/// The sequential test's defaults are the header's MCSTAT_SEQ_OPTIONS_INIT,
/// and pushing an array, its accumulator or a stream of it is the same look.
#[test]
fn seq_defaults_and_pushes() {
    unsafe {
        let mut o = MaybeUninit::<mcstat_seq_options>::zeroed().assume_init();
        assert_eq!(mcstat_seq_options_init_size(&mut o, size_of::<mcstat_seq_options>()), MCSTAT_OK);
        assert_eq!((o.size as usize, o.alternative, o.alpha, o.eps), (MCSTAT_SEQ_OPTIONS_SIZE_0_2, MCSTAT_TWO_SIDED, 0.05, 0.0));
        assert_eq!((o.t_opt, o.kurtosis_gate, o.var_ucb_z, o.min_n), (1e4, 10.0, 3.0, 100));
        assert_eq!(mcstat_seq_options_init_size(&mut o, size_of::<mcstat_seq_options>() + 8), MCSTAT_EINVAL);
        let x = data(700, 5);
        let mut a = MaybeUninit::<mcstat_seq>::zeroed().assume_init();
        assert_eq!(mcstat_seq_init(&mut a, MCSTAT_SEQ_MEAN_1, 0.5, std::ptr::null()), MCSTAT_OK);
        let (mut b, mut c) = (a, a);
        assert_eq!(mcstat_seq_push_array(&mut a, x.as_ptr(), x.len()), MCSTAT_OK);
        let mut m = MaybeUninit::<mcstat_moments>::zeroed().assume_init();
        mcstat_moments_init(&mut m);
        mcstat_moments_add_array(&mut m, x.as_ptr(), x.len());
        assert_eq!(mcstat_seq_push_moments(&mut b, &m), MCSTAT_OK);
        let mut s: Box<mcstat_stream> = Box::new(MaybeUninit::zeroed().assume_init());
        mcstat_stream_init(&mut *s);
        for &v in &x {
            mcstat_stream_add(&mut *s, v);
        }
        assert_eq!(mcstat_seq_push_stream(&mut c, &*s), MCSTAT_OK);
        let (mut ra, mut rb, mut rc) = (result(), result(), result());
        assert_eq!(mcstat_seq_result(&a, &mut ra), MCSTAT_OK);
        assert_eq!(mcstat_seq_result(&b, &mut rb), MCSTAT_OK);
        assert_eq!(mcstat_seq_finish(&c, &mut rc), MCSTAT_OK);
        assert_eq!(ra.test, MCSTAT_TEST_SEQ_MEAN_1);
        assert_eq!((ra.n[0], ra.seq().seq_looks, ra.ints_seq().seq_state), (700, 1.0, MCSTAT_SEQ_CONTINUE));
        assert_eq!(ra.statistic.to_bits(), rb.statistic.to_bits());
        assert_eq!(ra.seq().seq_log_e.to_bits(), rb.seq().seq_log_e.to_bits());
        // the stream sums in blocks of its capacity: the same to rounding
        assert!((ra.statistic - rc.statistic).abs() <= 1e-12 * ra.statistic.abs());
        assert_eq!((rc.n[0], rc.seq().seq_looks), (700, 1.0));
        // the wrong kind for the call, and a two-sample push
        assert_eq!(mcstat_seq_push_2_array(&mut a, x.as_ptr(), 1, x.as_ptr(), 1), MCSTAT_EINVAL);
        let mut t = MaybeUninit::<mcstat_seq>::zeroed().assume_init();
        assert_eq!(mcstat_seq_init(&mut t, MCSTAT_SEQ_VAR_2, 1.0, &o), MCSTAT_OK);
        assert_eq!(mcstat_seq_push_2_moments(&mut t, &m, &m), MCSTAT_OK);
        assert_eq!(mcstat_seq_push_moments(&mut t, &m), MCSTAT_EINVAL);
        assert_eq!(mcstat_seq_init(&mut t, 9, 1.0, &o), MCSTAT_EINVAL);
        let name = std::ffi::CStr::from_ptr(mcstat_seq_kind_name(MCSTAT_SEQ_VAR_2));
        assert_eq!(name.to_str().unwrap(), "var2");
        assert!(mcstat_seq_kind_name(0).is_null());
    }
}
