//! Writing output files into a folder a stranger may share: the one way every command that
//! writes files (`upgrade`, `render`, `compare --heatmap`, `lut`) places them.
//!
//! - Each file is written new under a random temporary name in its target folder (created
//!   with `O_EXCL`, never through an existing name or symlink), then renamed into place.
//! - Without `force` no existing name is replaced, not even a dangling symlink or a file
//!   created while the run writes; with it, the name itself is replaced (a symlink there is
//!   replaced, never written through), except names that reach an input of the run.
//! - The files of one output are placed as one set, under an exclusive lock on the folder,
//!   so two runs writing the same set leave one run's set, never a mix.
//! - Temporaries are removed when a run fails, on every terminating signal the CLI catches
//!   ([`exit_removing_unfinished`]), and, after a kill, by any later run into the folder
//!   (`remove_stale`): each temporary's name says which process made it.

use crate::document::file::FileId;
use std::path::{Path, PathBuf};

mod temporary;

pub use temporary::exit_removing_unfinished;
pub(crate) use temporary::{remove_stale, Temporary};

/// Why an output was not written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// The output would replace the input or a file the input reads.
    #[error("{} is the input or a file it reads: those are never replaced", .0.display())]
    WouldOverwriteInput(PathBuf),
    /// A GLB's length would not fit its 32-bit length field.
    #[error("{}: the GLB would be {} bytes, more than the 4 GiB a GLB can hold (write a .gltf instead)", .0.display(), .1)]
    GlbTooLarge(PathBuf, u64),
    /// A folder stands where a file is to be written.
    #[error("{} is a folder", .0.display())]
    IsFolder(PathBuf),
    /// A file (or a symlink, even a dangling one) exists and `force` was not given.
    #[error("{} exists (use --force to replace it)", .0.display())]
    Exists(PathBuf),
    /// Writing failed.
    #[error("{}: {}", .0.display(), .1)]
    Io(PathBuf, #[source] std::io::Error),
}

/// Whether `target` may be written: never when it is one of the `protected` files (the
/// input and everything it reads, by identity, so no other name or link for them gets
/// past), and only with `force` when the name exists (as a file, folder or symlink).
pub fn may_write(target: &Path, protected: &[FileId], force: bool) -> Result<(), WriteError> {
    let Ok(existing) = std::fs::symlink_metadata(target) else {
        return Ok(());
    };
    let reached = FileId::of_path(target).or(FileId::of(&existing));
    if reached.is_some_and(|id| protected.contains(&id)) {
        return Err(WriteError::WouldOverwriteInput(target.to_path_buf()));
    }
    if existing.is_dir() {
        return Err(WriteError::IsFolder(target.to_path_buf()));
    }
    if !force {
        return Err(WriteError::Exists(target.to_path_buf()));
    }
    Ok(())
}

/// Writes one file at `target` on the terms of this module: the bytes go to a temporary in
/// the target's folder, which is renamed into place.
pub fn write_file(
    target: &Path,
    bytes: &[u8],
    protected: &[FileId],
    force: bool,
) -> Result<PathBuf, WriteError> {
    write_files(&[(target, bytes)], protected, force).map(|mut placed| placed.remove(0))
}

/// Writes a set of files that belong together (each `(target, bytes)`, all in one folder) on
/// the terms of this module, placed as one set: all of them, or, when one cannot be placed
/// without `force`, none.
pub fn write_files(
    files: &[(&Path, &[u8])],
    protected: &[FileId],
    force: bool,
) -> Result<Vec<PathBuf>, WriteError> {
    let mut temporaries = Vec::new();
    let mut folder = None;
    for (target, bytes) in files {
        let (its_folder, name) = split(target)?;
        may_write(target, protected, force)?;
        if folder.is_none() {
            remove_stale(&its_folder);
        }
        if folder.as_ref().is_some_and(|f| *f != its_folder) {
            let other = std::io::Error::other("the files of one set must share a folder");
            return Err(WriteError::Io(target.to_path_buf(), other));
        }
        temporaries.push(Temporary::write(&its_folder, &name, [*bytes])?);
        folder = Some(its_folder);
    }
    match folder {
        Some(folder) => place_all(&folder, temporaries, force),
        None => Ok(Vec::new()),
    }
}

/// The folder (`.` for a bare name) and file name of `target`.
fn split(target: &Path) -> Result<(PathBuf, String), WriteError> {
    let name = (target.file_name().and_then(|n| n.to_str()))
        .ok_or_else(|| WriteError::IsFolder(target.to_path_buf()))?;
    let folder = match target.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((folder, name.to_string()))
}

/// Renames `temporaries` into place in `folder`, in order, while holding an exclusive lock
/// on the folder: another gltfmat run placing files there waits, so two runs writing the
/// same set of names leave all of one run's files, never some of each. Without `force`, a
/// name that exists stops the placing and the files this call already placed are taken
/// back (they were new), so the folder is as it was.
pub(crate) fn place_all(
    folder: &Path,
    temporaries: Vec<Temporary>,
    force: bool,
) -> Result<Vec<PathBuf>, WriteError> {
    let _lock = FolderLock::take(folder)?;
    let mut placed = Vec::new();
    for temporary in temporaries {
        match temporary.place(folder, force) {
            Ok(target) => placed.push(target),
            Err(e) => {
                if !force {
                    for target in &placed {
                        let _ = std::fs::remove_file(target);
                    }
                }
                return Err(e);
            }
        }
    }
    Ok(placed)
}

/// An exclusive advisory lock (`flock`) on a folder, held while a set of files is placed.
/// It lives on the folder's own inode, so it leaves no lock file behind.
struct FolderLock(std::fs::File);

impl FolderLock {
    fn take(folder: &Path) -> Result<FolderLock, WriteError> {
        let failed = |e| WriteError::Io(folder.to_path_buf(), e);
        let handle = std::fs::File::open(folder).map_err(failed)?;
        handle.lock().map_err(failed)?;
        Ok(FolderLock(handle))
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = self.0.unlock();
    }
}

/// The most bytes one `write` call is given: Linux writes a large buffer given in one call
/// many times slower than the same bytes in calls of this size (`dd` shows it too).
const WRITE_AT_ONCE: usize = 1 << 20;

/// Writes `parts` one after the other, in calls of at most `WRITE_AT_ONCE` (1 MiB) bytes.
pub(crate) fn write_parts<'p>(
    out: &mut impl std::io::Write,
    parts: impl IntoIterator<Item = &'p [u8]>,
) -> std::io::Result<()> {
    (parts.into_iter())
        .flat_map(|part| part.chunks(WRITE_AT_ONCE))
        .try_for_each(|chunk| out.write_all(chunk))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_file_is_written_and_an_existing_name_only_with_force() {
        let folder = tempfile::tempdir().unwrap();
        let target = folder.path().join("a.png");
        write_file(&target, b"one", &[], false).unwrap();
        let refused = write_file(&target, b"two", &[], false).unwrap_err();
        assert!(matches!(refused, WriteError::Exists(_)), "{refused}");
        assert_eq!(std::fs::read(&target).unwrap(), b"one");
        write_file(&target, b"two", &[], true).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"two");
        let names: Vec<_> = std::fs::read_dir(folder.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "no temporary left");
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_is_replaced_with_force_and_never_written_through() {
        let folder = tempfile::tempdir().unwrap();
        let outside = tempfile::tempdir().unwrap();
        let victim = outside.path().join("victim.txt");
        std::fs::write(&victim, b"keep").unwrap();
        let link = folder.path().join("out.png");
        std::os::unix::fs::symlink(&victim, &link).unwrap();
        let dangling = folder.path().join("dangling.png");
        std::os::unix::fs::symlink(outside.path().join("new.txt"), &dangling).unwrap();
        let refused = write_file(&dangling, b"x", &[], false).unwrap_err();
        assert!(matches!(refused, WriteError::Exists(_)), "{refused}");
        assert!(
            !outside.path().join("new.txt").exists(),
            "nothing made through the link"
        );
        write_file(&link, b"new", &[], true).unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep");
        assert!(!link.symlink_metadata().unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&link).unwrap(), b"new");
    }

    #[test]
    fn a_protected_file_is_never_replaced_even_with_force() {
        let folder = tempfile::tempdir().unwrap();
        let input = folder.path().join("texture.png");
        std::fs::write(&input, b"input").unwrap();
        let protected = [FileId::of_path(&input).unwrap()];
        let refused = write_file(&input, b"x", &protected, true).unwrap_err();
        assert!(
            matches!(refused, WriteError::WouldOverwriteInput(_)),
            "{refused}"
        );
        assert_eq!(std::fs::read(&input).unwrap(), b"input");
    }
}
