//! `gltfmat check FILES-OR-FOLDERS…`: options from flags and gltfmat.toml, files checked in
//! parallel, one rendering of all reports.

use crate::common::{Failure, Outcome};
use crate::config;
use gltfmat::registry;
use gltfmat::report::{write_each, Format, Style};
use gltfmat::FolderResources;
use gltfmat::{check_bytes, check_path, CheckOptions, NoResources, Profile, Report, Severity};
use rayon::prelude::*;
use std::cell::Cell;
use std::collections::HashMap;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

#[derive(clap::Args)]
pub struct CheckArgs {
    /// Files or folders; folders are walked for .gltf and .glb.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// How the report is written: `human`, `json` (the Khronos validator's shape), `jsonl`,
    /// `sarif` (code scanning), `github` (workflow annotations).
    #[arg(long, value_enum, default_value = "human")]
    format: FormatArg,
    /// `default`: the Khronos findings and gltfmat's material rules; `khronos`: exactly what
    /// the released Khronos glTF-Validator reports [default: default, or gltfmat.toml's].
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
    /// A gltfmat.toml for every file, instead of the nearest one above each file.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Read no gltfmat.toml: the command line's options alone. For gates over files strangers
    /// upload, whose folders may hold a gltfmat.toml that silences the checks.
    #[arg(long, conflicts_with = "config")]
    isolated: bool,
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
    /// to the working folder, as ripgrep's --glob: `--exclude assets/third-party/`; a glob
    /// without an inner slash, `third-party/`, matches at any depth; repeatable).
    #[arg(long, value_name = "GLOB")]
    exclude: Vec<String>,
    /// List infos and hints in human output too (they are counted in the summary otherwise).
    #[arg(long)]
    all_findings: bool,
    /// In human output over several files, a summary line for every file (by default only
    /// files with findings listed have one, and the run ends with one total line).
    #[arg(long)]
    verbose: bool,
    /// Colour in human output: `auto` follows the terminal, NO_COLOR, CLICOLOR_FORCE,
    /// FORCE_COLOR and TERM=dumb.
    #[arg(long, value_enum, default_value = "auto", value_name = "WHEN")]
    color: ColorArg,
    /// Exit 1 when a finding is at least this severe (`never`: only unreadable input fails).
    #[arg(long, value_enum, default_value = "error", value_name = "SEVERITY")]
    fail_on: FailOn,
    /// The name of the asset read from stdin (`-`): shown in reports, and the folder its
    /// gltfmat.toml and relative resources are found from.
    #[arg(long, value_name = "PATH")]
    stdin_filename: Option<PathBuf>,
    /// No progress bar (it is shown only on a terminal, on stderr).
    #[arg(long, short)]
    quiet: bool,
    /// Check only part K of N of the files (1 ≤ K ≤ N): a CI matrix of N jobs, each given
    /// its own K and the same other arguments, checks every file exactly once, and their
    /// jsonl outputs concatenate into the whole run's. A file's part is fixed by its path
    /// as the run names it, not by the order the file system lists it in.
    #[arg(long, value_name = "K/N", value_parser = crate::shard::Shard::parse)]
    shard: Option<crate::shard::Shard>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum FailOn {
    Error,
    Warning,
    Info,
    Hint,
    Never,
}

impl FailOn {
    fn fails(self, report: &Report) -> bool {
        let least = match self {
            FailOn::Error => Severity::Error,
            FailOn::Warning => Severity::Warning,
            FailOn::Info => Severity::Info,
            FailOn::Hint => Severity::Hint,
            FailOn::Never => return false,
        };
        Severity::ALL
            .iter()
            .any(|&s| s <= least && report.count(s) > 0)
    }
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum ColorArg {
    Auto,
    Always,
    Never,
}

impl ColorArg {
    /// Whether to colour standard output. `auto` asks anstream, which follows the terminal,
    /// NO_COLOR (when not empty), CLICOLOR, CLICOLOR_FORCE and TERM; FORCE_COLOR (not empty,
    /// not 0), which anstream does not read, forces colour as CLICOLOR_FORCE does.
    fn wanted(self) -> bool {
        match self {
            ColorArg::Always => true,
            ColorArg::Never => false,
            ColorArg::Auto => {
                let forced =
                    std::env::var_os("FORCE_COLOR").is_some_and(|v| !v.is_empty() && v != "0");
                let no_color = std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty());
                let choice = anstream::AutoStream::choice(&std::io::stdout());
                (forced && !no_color) || choice != anstream::ColorChoice::Never
            }
        }
    }
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
    let mut settings = Settings::new(&args);
    // The configuration that applies here decides the human output's shape (and a broken
    // one stops the run before any file is read).
    let here = settings.for_folder(Path::new("."))?;
    let all_findings = args.all_findings || here.1;
    let crate::walk::Walked {
        mut files,
        walked_a_folder,
        unreadable,
    } = crate::walk::assets(&args.inputs, &args.exclude)?;
    if let Some(shard) = args.shard {
        files.retain(|file| shard.contains(file));
    }
    // Files are checked in parallel; reports keep the input order.
    let progress = progress_bar(&args, files.len());
    let stdin_name = args.stdin_filename.as_deref();
    let options = options_per_file(&args, &mut settings, &files, all_findings)?;
    let colour = args.format == FormatArg::Human && args.color.wanted();
    let style = Style::new(colour)
        .with_all_findings(all_findings)
        .with_list(walked_a_folder || args.inputs.len() > 1)
        .with_verbose(args.verbose);
    let failed = Cell::new(false);
    let unreadable = Cell::new(unreadable);
    let check_one = |(file, options): (&PathBuf, &Arc<CheckOptions>)| {
        let result = check_file(file, stdin_name, options);
        progress.inc(1);
        result
    };
    // Each report is written, then dropped with its document: only a window of them is
    // ever held, however many files the folder has.
    let reports = in_order_by_windows(files.iter().zip(&options), check_one)
        .zip(&files)
        .filter_map(|(result, file)| match result {
            Ok(report) => {
                failed.set(failed.get() || args.fail_on.fails(&report));
                Some(report)
            }
            Err(message) => {
                let message = gltfmat::report::printable(&message).into_owned();
                let file = crate::walk::shown(file);
                progress.suspend(|| errln!("gltfmat: {file}: {message}"));
                unreadable.set(true);
                None
            }
        });
    // Written as rendered; a reader that went away (`| head`) is not an error, a full disk is.
    let mut stdout = std::io::BufWriter::new(std::io::stdout().lock());
    crate::streams::note(
        write_each(args.format.format(), reports, &style, &mut stdout)
            .and_then(|()| stdout.flush()),
    );
    progress.finish_and_clear();
    Ok(if unreadable.get() {
        ExitCode::from(2)
    } else if failed.get() {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The progress bar: on stderr, only on a terminal, without --quiet, never in CI, and only
/// when the report does not go to that terminal too (its lines would be broken by the bar's
/// redraws; they show the progress themselves).
fn progress_bar(args: &CheckArgs, files: usize) -> indicatif::ProgressBar {
    let bar_wanted = std::io::stderr().is_terminal()
        && !std::io::stdout().is_terminal()
        && std::env::var_os("CI").is_none();
    if args.quiet || !bar_wanted || files < 2 {
        indicatif::ProgressBar::hidden()
    } else {
        indicatif::ProgressBar::new(files as u64)
    }
}

/// Each file's options, from the configuration that applies to it (stdin's by its
/// --stdin-filename). Infos and hints that the report will not list are only counted:
/// 10^5 of them cost no memory.
fn options_per_file(
    args: &CheckArgs,
    settings: &mut Settings,
    files: &[PathBuf],
    all_findings: bool,
) -> Result<Vec<Arc<CheckOptions>>, Failure> {
    let stdin_name = args.stdin_filename.as_deref();
    let lists_all = args.format != FormatArg::Human || all_findings;
    (files.iter())
        .map(|file| {
            let named = (file.as_os_str() == "-").then_some(stdin_name).flatten();
            let (options, _) = settings.for_file(named.unwrap_or(file))?;
            Ok(match lists_all {
                true => options,
                false => Arc::new((*options).clone().with_lowest_kept(Severity::Warning)),
            })
        })
        .collect()
}

/// `work` done on every item, in parallel a window at a time, the results given in the
/// items' order: at most a window of results exists at once.
fn in_order_by_windows<T: Send, R: Send>(
    items: impl Iterator<Item = T>,
    work: impl Fn(T) -> R + Sync,
) -> impl Iterator<Item = R> {
    let window = 4 * rayon::current_num_threads();
    let mut items = items.peekable();
    std::iter::from_fn(move || {
        items.peek()?;
        let batch: Vec<T> = items.by_ref().take(window).collect();
        Some(batch.into_par_iter().map(&work).collect::<Vec<R>>())
    })
    .flatten()
}

/// Checks one file; `-` is stdin, named `stdin_name` when given (its resources are then
/// read beside that name, as they would be beside the file).
fn check_file(
    path: &Path,
    stdin_name: Option<&Path>,
    options: &CheckOptions,
) -> Result<Report, String> {
    if path.as_os_str() == "-" {
        let bytes =
            gltfmat::read_stream(std::io::stdin().lock()).map_err(|e| format!("stdin: {e}"))?;
        return Ok(match stdin_name {
            Some(name) => {
                let loader = FolderResources::beside(name);
                check_bytes(&name.to_string_lossy(), bytes, &loader, options)
            }
            None => check_bytes("-", bytes, &NoResources, options),
        });
    }
    check_path(path, options).map_err(|e| match e {
        gltfmat::Error::Io { source, .. } => source.to_string(),
        other => other.to_string(),
    })
}

/// The check options of each file: its gltfmat.toml (or `--config`'s) with the command-line
/// options added, each configuration read and validated once.
struct Settings<'a> {
    args: &'a CheckArgs,
    /// By configuration file (None: no file).
    resolved: HashMap<Option<PathBuf>, (Arc<CheckOptions>, bool)>,
}

impl<'a> Settings<'a> {
    fn new(args: &'a CheckArgs) -> Self {
        Settings {
            args,
            resolved: HashMap::new(),
        }
    }

    fn for_file(&mut self, file: &Path) -> Result<(Arc<CheckOptions>, bool), Failure> {
        // stdin (`-`) and a bare file name are both in the current folder.
        let folder = (file.parent())
            .filter(|parent| file.as_os_str() != "-" && !parent.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        self.for_folder(folder)
    }

    fn for_folder(&mut self, folder: &Path) -> Result<(Arc<CheckOptions>, bool), Failure> {
        let path = match &self.args.config {
            Some(path) => Some(path.clone()),
            None if self.args.isolated => None,
            None => config::find_upward(folder),
        };
        if let Some(known) = self.resolved.get(&path) {
            return Ok(known.clone());
        }
        let config = match &path {
            Some(path) => config::load(path),
            None => Ok(config::Config::default()),
        };
        let all_findings = config.as_ref().is_ok_and(config::Config::all_findings);
        let options = config
            .and_then(|c| build_options(self.args, c))
            .map_err(Failure::usage)?;
        let resolved = (Arc::new(options), all_findings);
        self.resolved.insert(path, resolved.clone());
        Ok(resolved)
    }
}

fn build_options(args: &CheckArgs, config: config::Config) -> Result<CheckOptions, String> {
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

#[cfg(test)]
mod window_tests {
    use super::in_order_by_windows;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn results_come_in_order_and_only_a_window_ahead_of_the_reader() {
        let pulled = AtomicUsize::new(0);
        let items = (0..1000).inspect(|_| {
            pulled.fetch_add(1, Ordering::Relaxed);
        });
        let mut results = in_order_by_windows(items, |i: i32| i * 2);
        assert_eq!(results.next(), Some(0));
        let window = 4 * rayon::current_num_threads();
        assert!(
            pulled.load(Ordering::Relaxed) <= window,
            "all items taken at once"
        );
        let rest: Vec<i32> = results.collect();
        assert_eq!(rest, (1..1000).map(|i| i * 2).collect::<Vec<_>>());
    }
}
