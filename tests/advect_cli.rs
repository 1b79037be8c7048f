//! `anisomesh advect` on bad input: every error is one line on stderr with a non-zero exit
//! status, never a panic, and no output file is written.

use std::process::{Command, Output};

fn advect(args: &[&str], out_dir: &std::path::Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_anisomesh"))
        .arg("advect")
        .args(args)
        .arg("-o")
        .arg(out_dir)
        .output()
        .expect("the binary runs")
}

#[test]
fn bad_advect_input_is_one_line_errors() {
    let dir = std::env::temp_dir().join(format!("anisomesh-advect-cli-{}", std::process::id()));
    let base = ["--t-end", "1", "--uniform", "16"];
    let cases: [(&[&str], &str); 7] = [
        (&["--expr", "x^2+y^2+1", "--velocity", "0; 0"], "zero level"),
        (&["--expr", "x +", "--velocity", "0; 0"], "shape"),
        (&["--expr", "", "--velocity", "0; 0"], "empty"),
        (
            &["--expr", "(x-0.5)^2+(y-0.5)^2-0.04", "--velocity", "1"],
            "two expressions",
        ),
        (
            &["--expr", "(x-0.5)^2+(y-0.5)^2-0.04", "--velocity", "1; 0"],
            "boundary",
        ),
        (
            &[
                "--expr",
                "(x-0.5)^2+(y-0.5)^2-0.04",
                "--velocity",
                "1/(x-0.5); 0",
            ],
            "not finite",
        ),
        (&["--case", "spiral"], "unknown case"),
    ];
    for (args, needle) in cases {
        let mut all: Vec<&str> = args.to_vec();
        all.extend(base);
        let out = advect(&all, &dir);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}: expected failure");
        assert!(!stderr.contains("panicked"), "{args:?}: panic: {stderr}");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{args:?}: one line: {stderr}"
        );
        assert!(
            stderr.contains(needle),
            "{args:?}: '{needle}' not in: {stderr}"
        );
    }
    assert!(!dir.join("advect.json").exists());
}
