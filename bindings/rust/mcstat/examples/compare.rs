//! Compares two estimators of the same integral, then plans a sample size:
//! `cargo run --example compare` (after `cmake --install`, with
//! PKG_CONFIG_PATH pointing at the installed mcstat.pc; no LD_LIBRARY_PATH).
use mcstat::{equivalence_test_2, t_test_2, Alternative, Moments, Power, PowerTest};

/// The integral of x^2 over [0, 1] (1/3) by two estimators of the same
/// uniform points: plain Monte Carlo, and antithetic pairs.
fn estimates(n: usize) -> (Vec<f64>, Vec<f64>) {
    // a fixed low-discrepancy sequence: the example prints the same numbers every run
    let u: Vec<f64> = (0..n).map(|i| ((i as f64 + 0.5) * 0.618_033_988_749_895) % 1.0).collect();
    let plain = u.iter().map(|&x| x * x).collect();
    let antithetic = u.iter().map(|&x| 0.5 * (x * x + (1.0 - x) * (1.0 - x))).collect();
    (plain, antithetic)
}

fn main() -> Result<(), mcstat::Error> {
    let (plain, antithetic) = estimates(1000);
    let r = t_test_2(&plain, &antithetic, 0.0, Alternative::TwoSided, 0.01)?;
    println!("{}", r.format("plain", "antithetic"));
    let e = equivalence_test_2(&plain, &antithetic, -0.01, 0.01, 0.05)?;
    println!("{}", e.format("plain", "antithetic"));
    let mut m = Moments::new();
    m.add_slice(&plain)?;
    // samples that show a bias of 1% of the integral with power 0.9
    let plan = Power {
        test: PowerTest::T1,
        effect: Some(0.01 / 3.0 / m.sd()),
        power: Some(0.9),
        alpha: Some(0.01),
        ..Default::default()
    };
    println!("{}", plan.solve()?);
    Ok(())
}
