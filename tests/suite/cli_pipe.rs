//! A closed reader ends `twoball` quietly, as it ends any Unix filter (`twoball ... | head`),
//! instead of a panic in `println!`.

#[cfg(unix)]
#[test]
fn closed_stdout_ends_the_process_without_a_panic() {
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_twoball"))
        .arg("materials")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start twoball");
    // Close the read end before the child has written anything: its first write meets a
    // pipe without a reader.
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait for twoball");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "twoball panicked: {err}");
    // Killed by SIGPIPE (13), or, if it wrote everything before the pipe closed, a clean exit.
    assert!(
        out.status.signal() == Some(13) || out.status.success(),
        "unexpected end: {:?}, stderr: {err}",
        out.status
    );
}
