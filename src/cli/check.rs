//! `gltfmat check FILES-OR-FOLDERS…`: options from flags and gltfmat.toml, files checked in
//! parallel, one rendering of all reports.

use crate::common::{Failure, Outcome};
use crate::config;
use crate::rules::print;
use gltfmat::check::registry;
use gltfmat::report::{render, Format, Style};
use gltfmat::{check_bytes, check_path, CheckOptions, NoResources, Profile, Report};
use rayon::prelude::*;
use std::io::{IsTerminal, Read};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct CheckArgs {
    /// Files or folders; folders are walked for .gltf and .glb.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    #[arg(long, value_enum, default_value = "human")]
    format: FormatArg,
    /// `khronos` reports exactly what the Khronos glTF-Validator reports.
    #[arg(long, value_enum)]
    profile: Option<ProfileArg>,
    /// Never report this code (repeatable).
    #[arg(long)]
    ignore: Vec<String>,
    /// Report only this code (repeatable).
    #[arg(long)]
    only: Vec<String>,
    /// Override a severity: CODE=error|warning|info|hint (repeatable).
    #[arg(long = "severity")]
    severities: Vec<String>,
    /// Stop after N issues per file and mark the report truncated.
    #[arg(long)]
    max_issues: Option<usize>,
    /// A gltfmat.toml to use instead of the one found upward from the current folder.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Decode textures for the pixel rules.
    #[arg(long)]
    deep: bool,
    /// Skip a rule group, e.g. `materials` (repeatable; groups are listed by `gltfmat rules`).
    #[arg(long = "disable-group", value_name = "GROUP")]
    disabled_groups: Vec<String>,
    /// Also run an opt-in rule group, e.g. `plausibility` (repeatable).
    #[arg(long = "enable-group", value_name = "GROUP")]
    enabled_groups: Vec<String>,
    /// Leave out walked files and folders matching this glob (gitignore syntax, relative
    /// to each folder argument; repeatable).
    #[arg(long, value_name = "GLOB")]
    exclude: Vec<String>,
    /// No progress bar (it is shown only on a terminal, on stderr).
    #[arg(long, short)]
    quiet: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum FormatArg {
    /// `path:line:col: severity[CODE]: message` with a source snippet.
    Human,
    /// Khronos validation report shape (an array for several inputs).
    Json,
    /// One Khronos-shaped report per line.
    Jsonl,
    /// SARIF 2.1.0.
    Sarif,
    /// GitHub Actions workflow commands (`::error file=…`).
    Github,
}

impl FormatArg {
    fn format(self) -> Format {
        match self {
            FormatArg::Human => Format::Human,
            FormatArg::Json => Format::Json,
            FormatArg::Jsonl => Format::Jsonl,
            FormatArg::Sarif => Format::Sarif,
            FormatArg::Github => Format::Github,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum ProfileArg {
    Default,
    Khronos,
}

pub fn run(args: CheckArgs) -> Outcome {
    let options = build_options(&args).map_err(Failure::usage)?;
    let mut unreadable = false;
    let mut files = Vec::new();
    for input in &args.inputs {
        if input.as_os_str() == "-" {
            files.push(input.clone());
            continue;
        }
        match std::fs::metadata(input) {
            Ok(metadata) if metadata.is_dir() => {
                let before = files.len();
                unreadable |= !collect_assets(input, &args.exclude, &mut files)?;
                if files.len() == before {
                    // A gate that checked nothing must not pass.
                    eprintln!("gltfmat: {}: no .gltf or .glb file found", input.display());
                    unreadable = true;
                }
            }
            // Anything else named is checked, or refused as not a regular file.
            Ok(_) => files.push(input.clone()),
            Err(e) => {
                eprintln!("gltfmat: {}: {e}", input.display());
                unreadable = true;
            }
        }
    }
    // Files are checked in parallel; reports keep the input order. The progress bar goes to
    // stderr, only on a terminal and without --quiet.
    let progress = if args.quiet || !std::io::stderr().is_terminal() || files.len() < 2 {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new(files.len() as u64)
    };
    let results: Vec<Result<Report, String>> = files
        .par_iter()
        .map(|file| {
            let result = check_file(file, &options);
            progress.inc(1);
            result
        })
        .collect();
    progress.finish_and_clear();
    let mut reports = Vec::new();
    for (file, result) in files.iter().zip(results) {
        match result {
            Ok(report) => reports.push(report),
            Err(message) => {
                eprintln!("gltfmat: {}: {message}", file.display());
                unreadable = true;
            }
        }
    }
    let colour = args.format == FormatArg::Human
        && std::io::stdout().is_terminal()
        && std::env::var_os("NO_COLOR").is_none();
    print(&render(args.format.format(), &reports, &Style::new(colour)));
    Ok(if unreadable {
        ExitCode::from(2)
    } else if reports.iter().any(Report::has_errors) {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

fn check_file(path: &Path, options: &CheckOptions) -> Result<Report, String> {
    if path.as_os_str() == "-" {
        let mut bytes = Vec::new();
        std::io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| e.to_string())?;
        return Ok(check_bytes("-", bytes, &NoResources, options));
    }
    check_path(path, options).map_err(|e| match e {
        gltfmat::Error::Io { source, .. } => source.to_string(),
        other => other.to_string(),
    })
}

/// Every .gltf/.glb (in any letter case) below a folder, sorted, as a walk in the style of
/// ripgrep finds them: `.gitignore`d and hidden entries are left out and symlinked folders
/// are not followed. An entry that is not a regular file (a FIFO, a device, or a symlink to
/// one) is skipped with a note; false when a folder could not be read (reported). `exclude`
/// globs (gitignore syntax) leave matching paths out.
fn collect_assets(
    folder: &Path,
    exclude: &[String],
    out: &mut Vec<PathBuf>,
) -> Result<bool, Failure> {
    let mut overrides = ignore::overrides::OverrideBuilder::new(folder);
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
    let walk = ignore::WalkBuilder::new(folder)
        .require_git(false)
        .overrides(overrides)
        .build();
    for entry in walk {
        let entry = match entry {
            Ok(entry) => entry,
            Err(e) => {
                eprintln!("gltfmat: {e}");
                complete = false;
                continue;
            }
        };
        if !is_asset_name(entry.path()) {
            continue;
        }
        match std::fs::metadata(entry.path()) {
            Ok(metadata) if metadata.is_file() => found.push(entry.into_path()),
            Ok(metadata) if metadata.is_dir() => {}
            Ok(_) => eprintln!(
                "gltfmat: note: skipped {}: not a regular file",
                entry.path().display()
            ),
            Err(e) => eprintln!("gltfmat: note: skipped {}: {e}", entry.path().display()),
        }
    }
    found.sort();
    out.extend(found);
    Ok(complete)
}

fn is_asset_name(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf") || e.eq_ignore_ascii_case("glb"))
}

fn build_options(args: &CheckArgs) -> Result<CheckOptions, String> {
    let config = match &args.config {
        Some(path) => config::load(path)?,
        None => match config::find_upward() {
            Some(path) => config::load(&path)?,
            None => config::Config::default(),
        },
    };
    let mut options = config.into_options()?;
    if let Some(profile) = args.profile {
        options.profile = match profile {
            ProfileArg::Default => Profile::Default,
            ProfileArg::Khronos => Profile::Khronos,
        };
    }
    options.ignore.extend(args.ignore.iter().cloned());
    options.only.extend(args.only.iter().cloned());
    for pair in &args.severities {
        let (code, level) = config::parse_severity(pair)?;
        options.severity_overrides.insert(code, level);
    }
    if let Some(n) = args.max_issues {
        options.max_issues = n;
    }
    options.deep |= args.deep;
    options
        .disabled_groups
        .extend(args.disabled_groups.iter().cloned());
    options
        .enabled_groups
        .extend(args.enabled_groups.iter().cloned());
    for group in options
        .disabled_groups
        .iter()
        .chain(&options.enabled_groups)
    {
        if !registry::is_rule_group(group) {
            return Err(format!(
                "unknown rule group '{group}' (see `gltfmat rules`)"
            ));
        }
    }
    for code in options
        .ignore
        .iter()
        .chain(&options.only)
        .chain(options.severity_overrides.keys())
    {
        if registry::find(code).is_none() {
            return Err(format!("unknown code '{code}' (see `gltfmat rules`)"));
        }
    }
    Ok(options)
}
