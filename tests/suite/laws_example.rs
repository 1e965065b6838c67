//! Issue 27, item 6: the example law in examples/custom_law.rs compiles (cargo builds
//! examples for `cargo test`) and runs here through the seam, the integrator and `laws run`.

#[path = "../../examples/custom_law.rs"]
#[allow(dead_code)]
mod custom_law;

#[test]
fn the_example_law_matches_its_closed_form_through_the_integrator() {
    let (e, e_cf, d, d_cf, res) = custom_law::check();
    assert!((e - e_cf).abs() < 1e-6 * e_cf, "{e} vs {e_cf}");
    assert!((d - d_cf).abs() < 1e-6 * d_cf, "{d} vs {d_cf}");
    assert!(res.abs() < 1e-8, "{res}");
}

#[test]
fn the_example_law_runs_through_laws_run_and_laws_fit() {
    let reg = custom_law::registry();
    let code = twoball::cli::laws_main_with(
        ["twoball laws", "run", "--law", "power-hysteresis", "--json"],
        &reg,
    );
    assert_eq!(code, 0);
    let dir = std::env::temp_dir().join(format!("twoball-laws-example-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let data = dir.join("data.csv");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        &data,
        "v_r [m/s],e [-],delta_max [m]\n1,0.5,3.0e-5\n2,0.5,4.5e-5\n",
    )
    .unwrap();
    let out = dir.join("fit");
    let code = twoball::cli::laws_main_with(
        [
            "twoball laws",
            "fit",
            "--law",
            "power-hysteresis",
            "--free",
            "e",
            "--against",
            data.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &reg,
    );
    assert_eq!(code, 0);
    let fit: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
    assert!((fit["params"]["e"].as_f64().unwrap() - 0.5).abs() < 1e-6);
    // An unknown law is still a clear error with the registry's names.
    assert_eq!(
        twoball::cli::laws_main_with(["twoball laws", "run", "--law", "nope"], &reg),
        1
    );
}
