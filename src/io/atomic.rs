//! Atomic file output: write to a temporary file beside the target, fsync, rename.
//!
//! A reader of the target never sees a half-written file, and a writer that fails (an I/O error,
//! an error returned by the formatting closure, or a panic) leaves the previous target untouched
//! and no temporary file behind.

use crate::error::{Error, Result};
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Removes the temporary file on drop unless the write was committed.
struct TempGuard {
    path: PathBuf,
    committed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// Writes `path` atomically: `write` fills a temporary file in the same directory (unique name
/// `.<name>.tmp.<pid>.<n>`), which is flushed, synced to disk and renamed over `path`.
///
/// On any failure the temporary file is removed, `path` is left as it was, and the error names
/// `path`.
pub fn atomic_write(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let name = path.file_name().ok_or_else(|| {
        Error::InvalidInput(format!(
            "cannot write '{}': the path has no file name",
            path.display()
        ))
    })?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let (file, guard) =
        create_temp(&dir, &name.to_string_lossy()).map_err(|e| Error::io(path, e))?;
    let mut guard = guard;
    let mut out = BufWriter::new(file);
    let result = write(&mut out)
        .and_then(|()| out.flush())
        .and_then(|()| out.get_ref().sync_all());
    drop(out);
    result.map_err(|e| Error::io(path, e))?;
    std::fs::rename(&guard.path, path).map_err(|e| Error::io(path, e))?;
    guard.committed = true;
    // Make the rename durable; failure here does not undo the write, so it is not an error.
    #[cfg(unix)]
    if let Ok(d) = File::open(&dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

fn create_temp(dir: &Path, name: &str) -> std::io::Result<(File, TempGuard)> {
    let pid = std::process::id();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.tmp.{pid}.{n}"));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => {
                return Ok((
                    f,
                    TempGuard {
                        path: tmp,
                        committed: false,
                    },
                ))
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("anisomesh-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn entries(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_and_replaces() {
        let d = scratch("ok");
        let p = d.join("a.txt");
        atomic_write(&p, |w| w.write_all(b"one")).unwrap();
        atomic_write(&p, |w| w.write_all(b"two")).unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "two");
        assert_eq!(entries(&d), vec!["a.txt".to_string()]);
    }

    #[test]
    fn failing_writer_leaves_nothing() {
        let d = scratch("fail");
        let p = d.join("b.txt");
        let err = atomic_write(&p, |w| {
            w.write_all(&[b'x'; 100_000])?;
            Err(std::io::Error::other("disk full half-way"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("b.txt"), "{err}");
        assert!(err.to_string().contains("disk full half-way"), "{err}");
        assert!(entries(&d).is_empty(), "{:?}", entries(&d));
        // An existing target is left untouched.
        std::fs::write(&p, "old").unwrap();
        assert!(atomic_write(&p, |_| Err(std::io::Error::other("no"))).is_err());
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        assert_eq!(entries(&d), vec!["b.txt".to_string()]);
    }

    #[test]
    fn panicking_writer_leaves_no_temp_file() {
        let d = scratch("panic");
        let p = d.join("c.txt");
        let r = std::panic::catch_unwind(|| {
            let _ = atomic_write(&p, |w| {
                w.write_all(b"partial")?;
                panic!("writer bug");
            });
        });
        assert!(r.is_err());
        assert!(entries(&d).is_empty(), "{:?}", entries(&d));
    }

    #[test]
    fn missing_directory_is_an_error_naming_the_path() {
        let p = std::env::temp_dir().join("anisomesh-no-such-dir-xyz/file.mesh");
        let err = atomic_write(&p, |w| w.write_all(b"x")).unwrap_err();
        assert!(err.to_string().contains("file.mesh"), "{err}");
    }
}
