//! Outputs a command writes only once all of them are made: each one is made under a temporary
//! name beside its target ([`AtomicFile`]), in the folders it needs (made as `mkdir -p` does),
//! and all are renamed into place together at the end. A command that fails leaves none of
//! them, nor any folder made for them.

use muscle_actuator_core::files::AtomicFile;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The outputs made so far, and the folders made for them.
#[derive(Default)]
pub(crate) struct Staged {
    files: Vec<AtomicFile>,
    /// Made by this command, deepest first.
    made_dirs: Vec<PathBuf>,
    committed: bool,
}

impl Staged {
    /// Makes the folders `target` needs and checks that it can be made: a temporary beside it,
    /// removed at once. For a check before the work.
    pub(crate) fn probe(&mut self, target: &Path) -> std::io::Result<()> {
        self.make_dirs(target)?;
        AtomicFile::create(target).map(drop)
    }

    /// `contents` made as `target`.
    pub(crate) fn text(&mut self, target: &Path, contents: &str) -> std::io::Result<()> {
        self.make_dirs(target)?;
        let mut f = AtomicFile::create(target)?;
        f.file().write_all(contents.as_bytes())?;
        self.files.push(f);
        Ok(())
    }

    /// A file made elsewhere, renamed into place with the others.
    pub(crate) fn push(&mut self, file: AtomicFile) {
        self.files.push(file);
    }

    /// Every output renamed into place; the first that cannot be, with its target.
    pub(crate) fn commit(mut self) -> Result<(), (PathBuf, std::io::Error)> {
        self.committed = true;
        for f in std::mem::take(&mut self.files) {
            let target = f.target().to_path_buf();
            f.commit().map_err(|e| (target, e))?;
        }
        Ok(())
    }

    /// The missing folders of `target`'s directory, made and noted.
    fn make_dirs(&mut self, target: &Path) -> std::io::Result<()> {
        let Some(dir) = target.parent().filter(|d| !d.as_os_str().is_empty()) else {
            return Ok(());
        };
        let missing: Vec<PathBuf> = dir
            .ancestors()
            .take_while(|d| !d.as_os_str().is_empty() && !d.exists())
            .map(Path::to_path_buf)
            .collect();
        std::fs::create_dir_all(dir)?;
        self.made_dirs.extend(missing);
        Ok(())
    }
}

impl Drop for Staged {
    /// Not committed: the temporaries removed (each [`AtomicFile`]'s drop), then the folders
    /// made for them, if still empty.
    fn drop(&mut self) {
        if self.committed {
            return;
        }
        self.files.clear();
        for d in &self.made_dirs {
            let _ = std::fs::remove_dir(d);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_command_leaves_nothing_and_a_done_one_everything() {
        let root = std::env::temp_dir().join(format!("staged_{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        let (a, b) = (root.join("x/y/a.csv"), root.join("b.csv"));
        {
            let mut s = Staged::default();
            s.probe(&a).unwrap();
            s.text(&b, "b").unwrap();
            assert!(root.join("x/y").is_dir());
        }
        let left: Vec<_> = std::fs::read_dir(&root).unwrap().collect();
        assert!(left.is_empty(), "{left:?}");
        let mut s = Staged::default();
        s.text(&a, "a").unwrap();
        s.text(&b, "b").unwrap();
        s.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&a).unwrap(), "a");
        assert_eq!(std::fs::read_to_string(&b).unwrap(), "b");
        let _ = std::fs::remove_dir_all(&root);
    }
}
