//! Temporary files in the output folder, as a hostile neighbour in that folder may meet
//! them. Each is created new (`O_EXCL`, never through an existing name or symlink) under a
//! random name and placed by rename: without `force` a
//! rename that refuses to replace (`RENAME_NOREPLACE`, or link and unlink), so two runs
//! writing the same new file cannot both succeed. Unfinished temporaries are removed on
//! drop, on interruption ([`exit_removing_unfinished`]), and, after a kill, by any later run
//! into the same folder ([`remove_stale`]).

use super::{write_parts, WriteError};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The temporaries of this process not yet placed or removed. A temporary is created and
/// entered here under one lock, so an interruption never falls between the two.
static UNFINISHED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn unfinished() -> MutexGuard<'static, Vec<PathBuf>> {
    UNFINISHED.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes every temporary this process has not placed yet and exits with `code`. For the
/// handler of SIGINT and SIGTERM: a temporary can be as large as the output. The registry
/// stays locked until the process is gone, so a temporary another thread is about to
/// create waits instead of appearing after the clean-up.
pub fn exit_removing_unfinished(code: i32) -> ! {
    let unfinished = unfinished();
    for path in unfinished.iter() {
        let _ = std::fs::remove_file(path);
    }
    std::process::exit(code)
}

/// One output file under its temporary name.
pub(crate) struct Temporary {
    /// The name it will be placed under.
    pub name: String,
    file: tempfile::NamedTempFile,
    _unfinished: Unfinished,
}

/// A temporary's entry in [`UNFINISHED`], taken out when the temporary is placed or dropped.
struct Unfinished(PathBuf);

impl Unfinished {
    /// Creates a file with `create` and enters its path, both under the registry's lock.
    fn create(
        create: impl FnOnce() -> std::io::Result<tempfile::NamedTempFile>,
    ) -> std::io::Result<(tempfile::NamedTempFile, Unfinished)> {
        let mut unfinished = unfinished();
        let file = create()?;
        let path = file.path().to_path_buf();
        unfinished.push(path.clone());
        Ok((file, Unfinished(path)))
    }
}

impl Drop for Unfinished {
    fn drop(&mut self) {
        unfinished().retain(|p| *p != self.0);
    }
}

/// `.NAME.gltfmat-PID.START-` starts every temporary for NAME: the process that made it, by
/// its id and its start time (a later process may be given the same id), so that a later
/// run can tell which were left by a process that no longer exists.
fn prefix(name: &str) -> String {
    format!(".{name}{MARK}{}-", Creator::this().tag())
}

const MARK: &str = ".gltfmat-";
const SUFFIX: &str = ".tmp";

/// A process, as a temporary's name records it.
#[derive(PartialEq, Eq)]
struct Creator {
    pid: u32,
    /// Its start time in clock ticks since boot (Linux), or 0 where it is not known.
    start: u64,
}

impl Creator {
    fn this() -> Creator {
        let pid = std::process::id();
        Creator {
            pid,
            start: start_time(pid).unwrap_or(0),
        }
    }

    fn tag(&self) -> String {
        format!("{}.{}", self.pid, self.start)
    }

    /// The creator a temporary's file name records, if it is one of ours.
    fn of_name(name: &str) -> Option<Creator> {
        let rest = name.strip_suffix(SUFFIX)?;
        let (rest, _random) = rest.rsplit_once('-')?;
        let (_, tag) = rest.rsplit_once(MARK)?;
        let (pid, start) = tag.split_once('.')?;
        Some(Creator {
            pid: pid.parse().ok()?,
            start: start.parse().ok()?,
        })
    }

    /// Whether the process is still running: the same id started at the same time.
    fn alive(&self) -> bool {
        start_time(self.pid).is_some_and(|start| self.start == 0 || start == self.start)
    }
}

/// When process `pid` started (field 22 of `/proc/PID/stat`), or None when no such process
/// runs (or the system has no `/proc`).
fn start_time(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let after_name = &stat[stat.rfind(')')? + 1..];
    after_name.split_whitespace().nth(19)?.parse().ok()
}

impl Temporary {
    /// Creates a new temporary for `name` in `folder` and writes `parts` into it.
    pub(crate) fn write<'p>(
        folder: &Path,
        name: &str,
        parts: impl IntoIterator<Item = &'p [u8]>,
    ) -> Result<Temporary, WriteError> {
        let failed = |e| WriteError::Io(folder.join(name), e);
        let prefix = prefix(name);
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(SUFFIX);
        // Output files get the permissions any new file gets (0666 less the umask), not
        // the owner-only ones of a temporary.
        #[cfg(unix)]
        builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
        let (file, unfinished) =
            Unfinished::create(|| builder.tempfile_in(folder)).map_err(failed)?;
        let temporary = Temporary {
            name: name.to_string(),
            file,
            _unfinished: unfinished,
        };
        write_parts(&mut temporary.file.as_file(), parts).map_err(failed)?;
        Ok(temporary)
    }

    /// Renames the temporary to its name in `folder`; an existing file is replaced only with
    /// `force`. On failure the temporary is removed.
    pub(crate) fn place(self, folder: &Path, force: bool) -> Result<PathBuf, WriteError> {
        let target = folder.join(&self.name);
        let placed = if force {
            self.file.persist(&target)
        } else {
            self.file.persist_noclobber(&target)
        };
        match placed {
            Ok(_) => Ok(target),
            Err(e) if e.error.kind() == std::io::ErrorKind::AlreadyExists => {
                Err(WriteError::Exists(target))
            }
            Err(e) => Err(WriteError::Io(target, e.error)),
        }
    }
}

/// Removes the temporaries in `folder` left by gltfmat processes that no longer run (killed
/// before they could clean up), whatever output they were for. Only regular files owned by
/// this user, named as a temporary by a process that is not alive, are removed.
pub(crate) fn remove_stale(folder: &Path) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::MetadataExt;
        let Ok(entries) = std::fs::read_dir(folder) else {
            return;
        };
        let me = crate::system::effective_user();
        for entry in entries.flatten() {
            let name = entry.file_name();
            let Some(creator) = name.to_str().and_then(Creator::of_name) else {
                continue;
            };
            if creator.alive() {
                continue;
            }
            if let Ok(metadata) = entry.path().symlink_metadata() {
                if metadata.is_file() && metadata.uid() == me {
                    let _ = std::fs::remove_file(entry.path());
                }
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = folder;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_temporary_names_its_creator_and_only_a_gone_one_is_stale() {
        let name = format!("{}abc123{SUFFIX}", prefix("x-1.gltf"));
        let creator = Creator::of_name(&name).expect("our own name is read back");
        assert!(creator == Creator::this());
        #[cfg(target_os = "linux")]
        {
            assert!(creator.alive());
            let reborn = Creator {
                start: creator.start + 1,
                ..creator
            };
            assert!(
                !reborn.alive(),
                "the same id started later is another process"
            );
        }
        assert!(
            Creator::of_name(".x.gltfmat-12-abc.tmp").is_none(),
            "no start time"
        );
        assert!(Creator::of_name("x.gltf").is_none());
    }
}
