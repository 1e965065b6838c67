//! Figures 11–14 show the trends the paper states in Section 4.

use twoball::analytic::parametric::{figure11, figure12, figure13, figure14};

fn increasing(ys: &[f64]) -> bool {
    ys.windows(2).all(|w| w[1] >= w[0])
}

#[test]
fn eta_rises_with_density_and_flattens() {
    let f = figure11().unwrap();
    for (_, ys) in &f.curves {
        assert!(increasing(ys));
        let n = ys.len();
        // "does not change linearly": the second half rises less than the first.
        assert!(ys[n - 1] - ys[n / 2] < ys[n / 2] - ys[0]);
    }
}

#[test]
fn eta_rises_with_friction_more_for_faster_sliding() {
    let f = figure12().unwrap();
    let slopes: Vec<f64> = f
        .curves
        .iter()
        .map(|(_, ys)| {
            assert!(increasing(ys));
            ys[ys.len() - 1] - ys[0]
        })
        .collect();
    assert!(slopes.windows(2).all(|w| w[1] > w[0]), "{slopes:?}");
}

#[test]
fn eta_rises_with_modulus_and_ratio() {
    let f = figure13().unwrap();
    for (_, ys) in &f.curves {
        assert!(increasing(ys));
    }
    // Curves are ordered by decreasing ratio 100 … 0.1: η falls with the ratio at every E.
    for i in 0..f.x.len() {
        assert!(f.curves.windows(2).all(|w| w[0].1[i] >= w[1].1[i]));
    }
}

#[test]
fn eta_falls_with_yield_and_ratios_above_one_coincide() {
    let f = figure14().unwrap();
    for (_, ys) in &f.curves {
        assert!(ys.windows(2).all(|w| w[1] <= w[0]));
    }
    // σ_p = min(σ_p1, σ_p2): for ratios ≥ 1 ball 1 governs, so the curves are identical.
    let one = &f.curves[2].1;
    for (_, ys) in &f.curves[3..] {
        assert_eq!(ys, one);
    }
}
