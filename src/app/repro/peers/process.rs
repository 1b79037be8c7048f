//! Starting the peer programs: finding them on `PATH` (through pyenv shims), running them with
//! a time limit while capturing their output, and reading the timings they print.

use anisomesh::error::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The first executable file called `name` in the directories of `PATH`. A pyenv shim (as
/// `pip install mmgpy` leaves for `mmg2d_O3`) is resolved to the program it starts, so that the
/// timings do not include the shim's start-up (about 0.5 s here).
pub fn find_program(name: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    let found = std::env::split_paths(&path)
        .map(|d| d.join(name))
        .find(|p| p.is_file())?;
    if found.to_string_lossy().contains("pyenv/shims") {
        let real = Command::new("pyenv")
            .arg("which")
            .arg(name)
            .stderr(Stdio::null())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| PathBuf::from(String::from_utf8_lossy(&o.stdout).trim()))
            .filter(|p| p.is_file());
        return Some(real.map(unwrap_mmgpy).unwrap_or(found));
    }
    Some(unwrap_mmgpy(found))
}

/// `pip install mmgpy` installs `mmg2d_O3` as a Python console script that starts the binary
/// shipped in the package (`mmgpy/bin/mmg2d_O3`); that binary, when found, else `script`.
fn unwrap_mmgpy(script: PathBuf) -> PathBuf {
    let Ok(text) = std::fs::read(&script) else {
        return script;
    };
    let head = String::from_utf8_lossy(&text[..text.len().min(512)]).to_string();
    let (Some(python), true) = (
        head.lines().next().and_then(|l| l.strip_prefix("#!")),
        head.contains("mmgpy"),
    ) else {
        return script;
    };
    let Some(name) = script.file_name() else {
        return script;
    };
    Command::new(python.trim())
        .args([
            "-c",
            "import mmgpy, os; print(os.path.dirname(mmgpy.__file__))",
        ])
        .stderr(Stdio::null())
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| {
            PathBuf::from(String::from_utf8_lossy(&o.stdout).trim())
                .join("bin")
                .join(name)
        })
        .filter(|p| p.is_file())
        .unwrap_or(script)
}

/// The end of an external run.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    pub seconds: f64,
    pub success: bool,
    pub timed_out: bool,
    pub stdout: String,
    pub stderr: String,
}

/// Runs `cmd` (output captured through files in `log_dir`, named after `tag`), killing it after
/// `timeout`. An error only when the program cannot be started.
pub fn run_with_timeout(
    cmd: &mut Command,
    timeout: Duration,
    log_dir: &Path,
    tag: &str,
) -> Result<RunOutcome> {
    let out_path = log_dir.join(format!("{tag}.stdout"));
    let err_path = log_dir.join(format!("{tag}.stderr"));
    let out = std::fs::File::create(&out_path).map_err(|e| Error::io(&out_path, e))?;
    let err = std::fs::File::create(&err_path).map_err(|e| Error::io(&err_path, e))?;
    let t0 = Instant::now();
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(out)
        .stderr(err)
        .spawn()
        .map_err(|e| Error::io(Path::new(cmd.get_program()), e))?;
    let mut timed_out = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if t0.elapsed() > timeout => {
                timed_out = true;
                // The child is ours: kill it by its handle and reap it.
                let _ = child.kill();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => return Err(Error::io(Path::new(cmd.get_program()), e)),
        }
    };
    let seconds = t0.elapsed().as_secs_f64();
    let read = |p: &Path| std::fs::read_to_string(p).unwrap_or_default();
    Ok(RunOutcome {
        seconds,
        success: status.is_some_and(|s| s.success()),
        timed_out,
        stdout: read(&out_path),
        stderr: read(&err_path),
    })
}

/// MMG's self-reported time in seconds, from its last `ELAPSED TIME  1.234s` line (runs over a
/// minute print `ELAPSED TIME  25m21s (1521.280s)`: the number in parentheses).
pub fn parse_mmg_elapsed(stdout: &str) -> Option<f64> {
    let rest = stdout
        .lines()
        .rev()
        .find_map(|l| l.trim().strip_prefix("ELAPSED TIME"))?;
    let secs = match (rest.find('('), rest.find(')')) {
        (Some(a), Some(b)) if a < b => &rest[a + 1..b],
        _ => rest,
    };
    secs.trim().trim_end_matches('s').trim().parse().ok()
}

/// The BAMG driver's `BAMG_SECONDS t` line.
pub fn parse_bamg_seconds(stdout: &str) -> Option<f64> {
    stdout
        .lines()
        .find_map(|l| l.trim().strip_prefix("BAMG_SECONDS"))
        .and_then(|s| s.trim().parse().ok())
}
