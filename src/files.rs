//! Bounded reading of the files a user names (configurations, scenarios, parameter files,
//! recordings): regular files only, of a bounded size; and no output written over an input.

/// Largest configuration or scenario file read, bytes.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// Reads `path` if it is a regular file of at most `max_bytes` bytes. The type and size are
/// checked before reading, so a device (`/dev/zero`), a FIFO or a directory is refused instead of
/// read without end or waited on; the read itself stops after `max_bytes` + 1 bytes, so a file
/// that grows meanwhile cannot make it allocate more. Errors give the reason only (the caller
/// names the file).
pub fn read_regular_file(path: &std::path::Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind, Read};
    use std::os::unix::fs::OpenOptionsExt;
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
    // Non-blocking open: should the path become a FIFO after the check above, opening it does
    // not wait for a writer; the check is repeated on the open file.
    let file = std::fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)?;
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

/// Whether `a` and `b` name the same file: the same device and inode where both exist (a hard
/// link, a symbolic link, `./x` and `x`), else the same canonical path, else equal paths.
pub fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
        return ma.dev() == mb.dev() && ma.ino() == mb.ino();
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
) -> Result<(), String> {
    if out.as_os_str() == "-" {
        return Ok(());
    }
    match inputs.iter().find(|i| same_file(i, out)) {
        Some(input) => Err(format!(
            "{}: the output would overwrite {}, which this command reads; give another path",
            out.display(),
            input.display()
        )),
        None => Ok(()),
    }
}
