//! Bounded reading of the files a user names (configurations, scenarios, parameter files,
//! recordings): regular files only, of a bounded size; no output written over an input; and
//! every output of an offline command written whole or not at all ([`AtomicFile`]).

/// Largest configuration or scenario file read, bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Reads `path` if it is a regular file of at most `max_bytes` bytes. The type and size are
/// checked before reading, so a device (`/dev/zero`), a FIFO or a directory is refused instead of
/// read without end or waited on; the read itself stops after `max_bytes` + 1 bytes, so a file
/// that grows meanwhile cannot make it allocate more. Errors give the reason only (the caller
/// names the file).
pub fn read_regular_file(path: &std::path::Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind, Read};
    let check = |meta: &std::fs::Metadata| -> std::io::Result<()> {
        if !meta.is_file() {
            return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
        }
        if meta.len() > max_bytes {
            return Err(Error::new(
                ErrorKind::InvalidInput,
                format!(
                    "{} bytes, more than the {max_bytes} such a file may have",
                    meta.len()
                ),
            ));
        }
        Ok(())
    };
    check(&std::fs::metadata(path)?)?;
    // The check is repeated on the open file, so a path that changed kind meanwhile is still
    // refused. Only a path turned into a FIFO between the two calls could make the open wait
    // for a writer; avoiding that takes a platform's non-blocking open flag, which the engine
    // does without so that it builds on every platform std supports.
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    check(&meta)?;
    let mut buf = Vec::with_capacity(meta.len() as usize);
    file.take(max_bytes + 1).read_to_end(&mut buf)?;
    if buf.len() as u64 > max_bytes {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("grew beyond the {max_bytes} bytes such a file may have while read"),
        ));
    }
    Ok(buf)
}

/// Whether `a` and `b` name the same file: on Unix the same device and inode where both exist
/// (a hard link, a symbolic link, `./x` and `x`), else the same canonical path, else equal paths.
pub fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// Refuses to write `out` over any of `inputs` (the recordings, configurations and scenarios a
/// command reads, or another of its outputs), before anything is read or written; `-`
/// (standard output) is no file.
pub fn check_not_an_input(
    out: &std::path::Path,
    inputs: &[&std::path::Path],
) -> Result<(), OverwritesInput> {
    if out.as_os_str() == "-" {
        return Ok(());
    }
    match inputs.iter().find(|i| same_file(i, out)) {
        Some(input) => Err(OverwritesInput {
            out: out.to_path_buf(),
            input: input.to_path_buf(),
        }),
        None => Ok(()),
    }
}

/// An output that would be written over a file the command reads ([`check_not_an_input`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{}: the output would overwrite {}, which this command reads; give another path",
    .out.display(),
    .input.display()
)]
pub struct OverwritesInput {
    /// The output, as named.
    pub out: std::path::PathBuf,
    /// The input it names, as named.
    pub input: std::path::PathBuf,
}

/// An output file written whole or not at all: created under a hidden temporary name beside its
/// target (`.NAME.tmp-PID-N.EXT`, in the same directory, so that the rename stays on one file
/// system; the target's extension kept, for writers that pick the format by it), and renamed over
/// the target by [`AtomicFile::commit`] once complete, after an fsync. Dropped uncommitted (an
/// error on the way) it removes the temporary, so a failure leaves neither the target nor a
/// temporary; a target that existed is untouched until the rename replaces it. A process killed
/// meanwhile leaves at most the hidden temporary, never a partial file under the target's name.
///
/// A symbolic link to a file is followed: the file it names is replaced, the link kept. A target
/// that exists and is no regular file (`/dev/null`, `/dev/stdout`, a FIFO) is written directly,
/// as there is nothing to replace.
#[derive(Debug)]
pub struct AtomicFile {
    /// The output as named.
    target: std::path::PathBuf,
    /// The temporary and the file the commit renames it to (the target, or the file a link
    /// there names); `None`: `target` is written directly.
    temp: Option<(std::path::PathBuf, std::path::PathBuf)>,
    file: std::fs::File,
    committed: bool,
}

impl AtomicFile {
    /// Creates the temporary of `target` (empty, new: never an existing file followed). Fails as
    /// creating `target` would: its directory missing or unwritable, `target` a directory.
    pub fn create(target: &std::path::Path) -> std::io::Result<AtomicFile> {
        use std::io::{Error, ErrorKind};
        let direct = |file| AtomicFile {
            target: target.to_path_buf(),
            temp: None,
            file,
            committed: false,
        };
        let dest = match std::fs::metadata(target) {
            // Refused with the platform's own error for writing a directory (EISDIR on Unix).
            Ok(m) if m.is_dir() => {
                let open = std::fs::OpenOptions::new().write(true).open(target);
                return Err(open.err().unwrap_or_else(|| ErrorKind::IsADirectory.into()));
            }
            Ok(m) if !m.is_file() => {
                return Ok(direct(
                    std::fs::OpenOptions::new().write(true).open(target)?,
                ))
            }
            Ok(_) if target.is_symlink() => target.canonicalize()?,
            _ => target.to_path_buf(),
        };
        let name = dest
            .file_name()
            .ok_or_else(|| Error::new(ErrorKind::InvalidInput, "not a file name"))?;
        let dir = dest
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        // At most `n` bytes of `s`: the temporary's name within NAME_MAX (255 bytes) whatever
        // the target's.
        let cut = |s: &std::ffi::OsStr, n: usize| {
            let s = s.to_string_lossy();
            let end = (0..=s.len().min(n)).rev().find(|&i| s.is_char_boundary(i));
            s[..end.unwrap_or(0)].to_string()
        };
        let ext = dest
            .extension()
            .map(|e| format!(".{}", cut(e, 16)))
            .unwrap_or_default();
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let mut tries = 0;
        loop {
            let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let temp = dir.join(format!(
                ".{}.tmp-{}-{n}{ext}",
                cut(name, 160),
                std::process::id()
            ));
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&temp)
            {
                Ok(file) => {
                    let mut out = direct(file);
                    out.temp = Some((temp, dest));
                    return Ok(out);
                }
                // One left by a process killed with this id, or another writer's: the next.
                Err(e) if e.kind() == ErrorKind::AlreadyExists && tries < 100 => tries += 1,
                Err(e) => return Err(e),
            }
        }
    }

    /// The temporary's path (the target's, written directly), for writers that open a path
    /// themselves (plotters' backends, the MCAP recorder): they truncate and fill it;
    /// [`commit`](Self::commit) publishes it.
    pub fn path(&self) -> &std::path::Path {
        self.temp.as_ref().map_or(&self.target, |(temp, _)| temp)
    }

    /// The output as named (the name it is written under once committed, or the link to it).
    pub fn target(&self) -> &std::path::Path {
        &self.target
    }

    /// The open temporary, to write into.
    pub fn file(&mut self) -> &mut std::fs::File {
        &mut self.file
    }

    /// Flushes the temporary to disk and renames it over the target (then syncs the directory,
    /// so the rename survives a power cut too). On an error the temporary is removed and the
    /// target left as it was.
    pub fn commit(mut self) -> std::io::Result<()> {
        let Some((temp, dest)) = &self.temp else {
            return Ok(());
        };
        self.file.sync_all()?;
        std::fs::rename(temp, dest)?;
        self.committed = true;
        let dir = dest.parent().filter(|d| !d.as_os_str().is_empty());
        if let Ok(d) = std::fs::File::open(dir.unwrap_or(std::path::Path::new("."))) {
            let _ = d.sync_all();
        }
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if let Some((temp, _)) = self.temp.as_ref().filter(|_| !self.committed) {
            let _ = std::fs::remove_file(temp);
        }
    }
}

/// `std::fs::write` whole or not at all ([`AtomicFile`]).
pub fn write_atomically(target: &std::path::Path, contents: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = AtomicFile::create(target)?;
    out.file().write_all(contents)?;
    out.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use std::path::{Path, PathBuf};

    fn dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!(
            "muscle_actuator_files_{tag}_{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_committed_file_replaces_the_target_and_leaves_no_temporary() {
        let d = dir("commit");
        let target = d.join("out.csv");
        std::fs::write(&target, "old").unwrap();
        let mut f = AtomicFile::create(&target).unwrap();
        let temp = f.path().to_path_buf();
        let temp_name = temp.file_name().unwrap().to_string_lossy().into_owned();
        assert!(temp_name.starts_with(".out.csv.tmp-"), "{temp_name}");
        assert!(temp_name.ends_with(".csv"), "{temp_name}");
        assert_eq!(temp.parent(), Some(d.as_path()));
        f.file().write_all(b"new").unwrap();
        // Until the commit the target is what it was.
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        f.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        assert_eq!(names(&d), ["out.csv"]);
        write_atomically(&target, b"again").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"again");
        assert_eq!(names(&d), ["out.csv"]);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn an_uncommitted_file_leaves_nothing_and_the_target_intact() {
        let d = dir("drop");
        let fresh = d.join("fresh.png");
        let mut f = AtomicFile::create(&fresh).unwrap();
        f.file().write_all(b"half").unwrap();
        drop(f);
        let kept = d.join("kept.mcap");
        std::fs::write(&kept, "whole").unwrap();
        let mut f = AtomicFile::create(&kept).unwrap();
        f.file().write_all(b"half").unwrap();
        drop(f);
        assert_eq!(names(&d), ["kept.mcap"]);
        assert_eq!(std::fs::read(&kept).unwrap(), b"whole");
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn temporaries_are_distinct_and_fail_where_the_target_would() {
        let d = dir("fail");
        let target = d.join("x.svg");
        let a = AtomicFile::create(&target).unwrap();
        let b = AtomicFile::create(&target).unwrap();
        assert_ne!(a.path(), b.path());
        drop((a, b));
        let missing = d.join("no such dir").join("x.csv");
        assert!(AtomicFile::create(&missing).is_err());
        assert!(write_atomically(&missing, b"x").is_err());
        let e = AtomicFile::create(&d).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::IsADirectory);
        // A name as long as the file system allows still gets a temporary.
        let long = d.join(format!("{}.csv", "n".repeat(250)));
        write_atomically(&long, b"x").unwrap();
        assert_eq!(std::fs::read(&long).unwrap(), b"x");
        std::fs::remove_file(&long).unwrap();
        assert!(names(&d).is_empty(), "{:?}", names(&d));
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    #[cfg(unix)]
    fn a_link_is_followed_and_a_device_written_directly() {
        let d = dir("link");
        std::fs::create_dir_all(d.join("real")).unwrap();
        let real = d.join("real").join("run.csv");
        std::fs::write(&real, "old").unwrap();
        let link = d.join("link.csv");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        let f = AtomicFile::create(&link).unwrap();
        assert_eq!(f.target(), link);
        assert_eq!(f.path().parent(), Some(d.join("real").as_path()));
        drop(f);
        write_atomically(&link, b"new").unwrap();
        assert!(link.is_symlink());
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert_eq!(names(&d.join("real")), ["run.csv"]);
        // Nothing to replace: /dev/null stays the device.
        let null = Path::new("/dev/null");
        let f = AtomicFile::create(null).unwrap();
        assert_eq!(f.path(), null);
        drop(f);
        write_atomically(null, b"x").unwrap();
        use std::os::unix::fs::FileTypeExt;
        assert!(std::fs::metadata(null)
            .unwrap()
            .file_type()
            .is_char_device());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
