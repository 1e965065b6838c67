//! `cargo bench`: the explicit step cost per element of both hexahedra (release build, the
//! figures docs/performance.md quotes), by `twoball bench kernel` on one thread with the
//! phase split and the kernel arithmetic alone, then on all threads with the bitwise check.
//! Extra arguments go to `bench kernel`, e.g. `cargo bench -- --element b-bar --kernel avx2`.

fn main() {
    // cargo passes `--bench` to a harness-less bench; the rest are the user's.
    let extra: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    let run = |fixed: &[&str]| {
        let args = ["twoball", "bench", "kernel"]
            .iter()
            .map(|s| s.to_string())
            .chain(fixed.iter().map(|s| s.to_string()))
            .chain(extra.iter().cloned());
        let code = twoball::cli::main_from(args);
        if code != 0 {
            std::process::exit(code);
        }
    };
    run(&["--threads", "1", "--repeats", "9", "--phases"]);
    run(&["--repeats", "9"]);
}
