//! Temporary files in the output folder, as a hostile neighbour in that folder may meet
//! them. Each is created new (`O_EXCL`, never through an existing name or symlink) under a
//! random name and placed by rename: without `force` a
//! rename that refuses to replace (`RENAME_NOREPLACE`, or link and unlink), so two runs
//! writing the same new file cannot both succeed. Unfinished temporaries are removed on
//! drop, on interruption ([`exit_removing_unfinished`]), and, after a kill, by the next run
//! into the same folder ([`remove_stale`]).

use super::WriteError;
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
pub(super) struct Temporary {
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

/// `.NAME.gltfmat-PID-` starts every temporary for NAME, so that a later run can tell which
/// were left by a process that no longer exists.
fn prefix(name: &str) -> String {
    format!(".{name}.gltfmat-{}-", std::process::id())
}

const SUFFIX: &str = ".tmp";

impl Temporary {
    /// Creates a new temporary for `name` in `folder` and writes `parts` into it.
    pub fn write<'p>(
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
        super::write_parts(&mut temporary.file.as_file(), parts).map_err(failed)?;
        Ok(temporary)
    }

    /// Renames the temporary to its name in `folder`; an existing file is replaced only with
    /// `force`. On failure the temporary is removed.
    pub fn place(self, folder: &Path, force: bool) -> Result<PathBuf, WriteError> {
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

/// Removes temporaries for `names` in `folder` left by gltfmat processes that no longer
/// run (killed before they could clean up). Only regular files owned by this user, named
/// as a temporary for one of `names` by a process id that is not alive, are removed.
pub(super) fn remove_stale<'n>(folder: &Path, names: impl Iterator<Item = &'n str>) {
    #[cfg(target_os = "linux")]
    {
        let prefixes: Vec<String> = names.map(|n| format!(".{n}.gltfmat-")).collect();
        let Ok(entries) = std::fs::read_dir(folder) else {
            return;
        };
        for entry in entries.flatten() {
            let name = entry.file_name();
            let Some(name) = name.to_str() else { continue };
            let Some(rest) = prefixes.iter().find_map(|p| name.strip_prefix(p.as_str())) else {
                continue;
            };
            if !name.ends_with(SUFFIX) {
                continue;
            }
            let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<u32>().ok()) else {
                continue;
            };
            if pid == std::process::id() || Path::new(&format!("/proc/{pid}")).exists() {
                continue;
            }
            if let Ok(metadata) = entry.path().symlink_metadata() {
                use std::os::unix::fs::MetadataExt;
                // SAFETY: geteuid has no preconditions and cannot fail.
                let mine = metadata.uid() == unsafe { libc::geteuid() };
                if metadata.is_file() && mine {
                    let _ = std::fs::remove_file(entry.path());
                }
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = (folder, names.count());
    }
}
