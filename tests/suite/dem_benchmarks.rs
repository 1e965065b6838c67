//! `twoball bench dem`: Chung & Ooi's benchmark tests by converged FE. Test 1 (two identical
//! elastic glass spheres at ±10 m/s, a/R = 0.12) runs end to end; the continuum balls are
//! stiffer than Hertz's half-spaces, so the converged FE approaches less and parts sooner.

use twoball::study::bench::dem::{bench, OBLIQUE_TOLERANCE};

#[test]
fn test1_glass_runs_elastic_and_stiffer_than_hertz() {
    let dir = std::env::temp_dir().join(format!("twoball-dem-{}", std::process::id()));
    let rows = bench(&["test1-glass".into()], OBLIQUE_TOLERANCE, Some(&dir)).unwrap();
    assert_eq!(rows.len(), 1);
    let r = &rows[0];
    // Elastic: e = 1 within its bar and 0.1 %.
    assert!((r.e.0 - 1.0).abs() < r.e.1.max(1e-3), "e = {:?}", r.e);
    // Converged to 0.5 % or better, and 1-5 % below Hertz in δ_max and the contact time
    // (measured: −2.74 % and −2.78 %; docs/contact-penalty.md, "The free ball").
    let (d, bar, hertz) = r.delta_max;
    assert!(bar < 5e-3 * d, "δ_max bar {bar} of {d}");
    let dd = d / hertz - 1.0;
    let (t, _, th) = r.contact_duration;
    let dt = t / th - 1.0;
    assert!((-0.05..-0.01).contains(&dd), "δ_max {dd:+.4}");
    assert!((-0.05..-0.01).contains(&dt), "t_c {dt:+.4}");
    // Both files whole, the CSV with its SI header.
    let csv = std::fs::read_to_string(dir.join("cases.csv")).unwrap();
    assert!(csv.starts_with("case,angle_deg,slip_ratio,e,e_bar,delta_max_m,"));
    assert_eq!(csv.lines().count(), 2);
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("| test1-glass |"), "{report}");
    std::fs::remove_dir_all(&dir).unwrap();
}
