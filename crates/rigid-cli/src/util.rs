//! Small helpers of the command-line tool that are not about dynamics: outputs written
//! atomically (through a temporary file and a rename), so that a failed run never leaves a
//! half-written file behind.

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so that an
/// output is never left half-written.
///
/// # Errors
/// The file cannot be written (the message names it).
pub fn write_atomic(path: &std::path::Path, bytes: &[u8]) -> Result<(), String> {
    let tmp = temp_path(path);
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!("cannot write {}: {e}", path.display()));
    }
    Ok(())
}

/// The temporary file next to `path` that an atomic write goes through.
fn temp_path(path: &std::path::Path) -> std::path::PathBuf {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(std::path::Path::new("."));
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    dir.join(format!(".{name}.{}.tmp", std::process::id()))
}

/// A file written through a temporary file in the same folder, renamed into place by
/// [`commit`](Self::commit) (removed if dropped before): for outputs written as they are
/// produced (a CSV row per step).
pub struct AtomicFile {
    tmp: std::path::PathBuf,
    path: std::path::PathBuf,
    out: Option<std::io::BufWriter<std::fs::File>>,
}

impl AtomicFile {
    /// Opens the temporary file for `path`.
    ///
    /// # Errors
    /// The folder cannot be written (the message names the file).
    pub fn create(path: &std::path::Path) -> Result<Self, String> {
        let tmp = temp_path(path);
        let f = std::fs::File::create(&tmp)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        Ok(Self {
            tmp,
            path: path.to_path_buf(),
            out: Some(std::io::BufWriter::new(f)),
        })
    }

    /// The buffered writer.
    pub fn writer(&mut self) -> &mut std::io::BufWriter<std::fs::File> {
        self.out.as_mut().expect("not committed")
    }

    /// Flushes and renames the file into place.
    ///
    /// # Errors
    /// The file cannot be written.
    pub fn commit(mut self) -> Result<(), String> {
        use std::io::Write;
        let mut out = self.out.take().expect("committed once");
        let err = |e: std::io::Error| format!("cannot write {}: {e}", self.path.display());
        out.flush().map_err(err)?;
        drop(out);
        std::fs::rename(&self.tmp, &self.path).map_err(err)
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
