//! What the command-line tests share: running the binary, checking its outcome, scratch paths.
//! Each test file uses a part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs the `anisomesh` binary with `args` from the package root.
pub fn anisomesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_anisomesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// The standard output of a run that must succeed (its standard error in the failure message).
pub fn ok(out: &Output) -> String {
    assert!(
        out.status.success(),
        "failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Runs the binary and returns its standard output; the run must succeed.
pub fn anisomesh_ok(args: &[&str]) -> String {
    ok(&anisomesh(args))
}

/// A run that must fail with one line on standard error containing `needle`, and no panic.
pub fn assert_clean_error(out: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "expected failure, got success");
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(stderr.contains(needle), "'{needle}' not in: {stderr}");
}

/// A scratch folder `anisomesh-<tag>-<pid>` in the temporary directory, created.
pub fn scratch(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("anisomesh-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A path as `&str` for the argument list.
pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}
