//! The files a run reads: each file named, and every .gltf/.glb below each folder named.

use crate::common::Failure;
use gltfmat::report::printable;
use std::path::{Path, PathBuf};

/// What a walk found.
pub struct Walked {
    /// The files, in argument order, each folder's sorted.
    pub files: Vec<PathBuf>,
    /// Whether a folder was named (the inputs then form a list).
    pub walked_a_folder: bool,
    /// Whether something named could not be read, or a folder held no asset (reported).
    pub unreadable: bool,
}

/// The files `inputs` name (`-` is stdin), walking folders with `exclude` globs applied.
pub fn assets(inputs: &[PathBuf], exclude: &[String]) -> Result<Walked, Failure> {
    let mut unreadable = false;
    let mut files = Vec::new();
    let mut walked_a_folder = false;
    for input in inputs {
        if input.as_os_str() == "-" {
            files.push(input.clone());
            continue;
        }
        match std::fs::metadata(input) {
            Ok(metadata) if metadata.is_dir() => {
                walked_a_folder = true;
                let before = files.len();
                unreadable |= !collect_assets(input, exclude, &mut files)?;
                if files.len() == before {
                    // A gate that checked nothing must not pass, and says what it passed by.
                    let skipped = match skipped_assets(input) {
                        0 => String::new(),
                        n => format!(" ({n} skipped: under hidden or ignored paths, or excluded; name a file or folder to check it)"),
                    };
                    errln!(
                        "gltfmat: {}: no .gltf or .glb file found{skipped}",
                        shown(input)
                    );
                    unreadable = true;
                }
            }
            // Anything else named is checked, or refused as not a regular file.
            Ok(_) => files.push(input.clone()),
            Err(e) => {
                errln!("gltfmat: {}: {}", shown(input), printable(&e.to_string()));
                unreadable = true;
            }
        }
    }
    Ok(Walked {
        files,
        walked_a_folder,
        unreadable,
    })
}

/// A path as a terminal may show it: a file name is a stranger's text too.
pub fn shown(path: &Path) -> String {
    printable(&path.display().to_string()).into_owned()
}

/// How many asset files under `folder` the walk leaves out (hidden, ignored or excluded): the
/// same walk with no filter, counted.
fn skipped_assets(folder: &Path) -> usize {
    (ignore::WalkBuilder::new(folder)
        .standard_filters(false)
        .build())
    .flatten()
    .filter(|entry| is_asset_name(entry.path()) && entry.path().is_file())
    .count()
}

/// Every .gltf/.glb (in any letter case) below a folder, sorted, as a walk in the style of
/// ripgrep finds them: `.gitignore`d and hidden entries are left out and symlinked folders
/// are not followed. An entry that is not a regular file (a FIFO, a device, or a symlink to
/// one) or a symlink leading out of the folder is skipped with a note; false when a folder
/// could not be read (reported). `exclude` globs (gitignore syntax) leave matching paths out.
fn collect_assets(
    folder: &Path,
    exclude: &[String],
    out: &mut Vec<PathBuf>,
) -> Result<bool, Failure> {
    // Globs are matched from the working folder, as ripgrep matches them and as a CI recipe
    // writes them (`check assets/ --exclude assets/third-party/`); a glob without an inner
    // slash (`third-party/`) matches at any depth, under any folder argument.
    let root = std::env::current_dir().unwrap_or_else(|_| folder.to_path_buf());
    let mut overrides = ignore::overrides::OverrideBuilder::new(root);
    for glob in exclude {
        overrides
            .add(&format!("!{glob}"))
            .map_err(|e| Failure::usage(format!("--exclude {glob}: {e}")))?;
    }
    let overrides = overrides
        .build()
        .map_err(|e| Failure::usage(format!("--exclude: {e}")))?;
    let mut found = Vec::new();
    let mut complete = true;
    // Where the folder itself resolves, against which each link found in it is judged.
    let resolved = std::fs::canonicalize(folder).ok();
    let walk = ignore::WalkBuilder::new(folder)
        .require_git(false)
        .overrides(overrides)
        .build();
    for entry in walk {
        let entry = match entry {
            Ok(entry) => entry,
            Err(e) => {
                errln!("gltfmat: {e}");
                complete = false;
                continue;
            }
        };
        if !is_asset_name(entry.path()) {
            continue;
        }
        match std::fs::metadata(entry.path()) {
            Ok(metadata)
                if metadata.is_file()
                    && entry.path_is_symlink()
                    && !leads_inside(entry.path(), resolved.as_deref()) =>
            {
                errln!(
                "gltfmat: note: skipped {}: a symbolic link leading out of {} (name it to check it)",
                    shown(entry.path()),
                    shown(folder)
                )
            }
            Ok(metadata) if metadata.is_file() => found.push(entry.into_path()),
            Ok(metadata) if metadata.is_dir() => {}
            Ok(_) => errln!(
                "gltfmat: note: skipped {}: not a regular file",
                shown(entry.path())
            ),
            Err(e) => errln!(
                "gltfmat: note: skipped {}: {}",
                shown(entry.path()),
                printable(&e.to_string())
            ),
        }
    }
    found.sort();
    out.extend(found);
    Ok(complete)
}

/// Whether the symbolic link `link` resolves to a file inside the folder resolved to
/// `folder`: a walk checks what the folder holds, and a link a stranger planted there
/// (`scene.gltf` → `~/.docker/config.json`) must not put a file from elsewhere into the report
/// and its snippets.
fn leads_inside(link: &Path, folder: Option<&Path>) -> bool {
    let target = std::fs::canonicalize(link);
    folder
        .zip(target.ok())
        .is_some_and(|(folder, target)| target.starts_with(folder))
}

fn is_asset_name(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}
