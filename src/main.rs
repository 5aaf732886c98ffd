//! The `gltfmat` command line.

mod cli_compare;
mod cli_config;
mod cli_lut;
mod cli_upgrade;

use clap::{Parser, Subcommand};
use gltfmat::check::{check_bytes, codes, CheckOptions, Profile, Report};
use gltfmat::document::uri::{FolderResources, NoResources};
use gltfmat::report::{render, Format, RenderOptions};
use rayon::prelude::*;
use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "gltfmat",
    version,
    about = "glTF material checker, 1.0 upgrader and shading evaluator"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Check .gltf/.glb files or folders (use `-` for stdin).
    Check(CheckArgs),
    /// Convert a glTF 1.0 asset (with WEB3D/KHR/FRAUNHOFER/EXT PBR materials) to glTF 2.0.
    Upgrade(cli_upgrade::UpgradeArgs),
    /// Render a material ball (or --all materials) to PNG.
    Render(cli_compare::RenderArgs),
    /// Do two materials render the same? ΔE2000 over a UV grid and a set of directions.
    Compare(cli_compare::CompareArgs),
    /// Export a lookup table of the shading evaluator (the sheen albedo E).
    Lut(cli_lut::LutArgs),
    /// List every code gltfmat can report.
    Rules,
    /// Show the full documentation of one code.
    Explain { code: String },
}

#[derive(clap::Args)]
struct CheckArgs {
    /// Files or folders; folders are walked for .gltf and .glb.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    #[arg(long, value_enum, default_value = "human")]
    format: Format,
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
    /// Skip a rule group, e.g. `plausibility` (repeatable; groups are listed by `gltfmat rules`).
    #[arg(long = "disable-group")]
    disabled_groups: Vec<String>,
    /// No progress bar (it is shown only on a terminal, on stderr).
    #[arg(long, short)]
    quiet: bool,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum ProfileArg {
    Default,
    Khronos,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Check(args) => run_check(args),
        Command::Upgrade(args) => cli_upgrade::run(args),
        Command::Lut(args) => cli_lut::run(args),
        Command::Compare(args) => cli_compare::run(args),
        Command::Render(args) => cli_compare::render(args),
        Command::Rules => {
            let mut out = String::new();
            for info in codes::all() {
                out.push_str(&format!(
                    "{:<58} {:<8} {}\n",
                    info.code,
                    info.severity.name(),
                    info.summary
                ));
            }
            print(&out);
            ExitCode::SUCCESS
        }
        Command::Explain { code } => match codes::find(&code) {
            Some(info) => {
                let body = if info.doc.is_empty() {
                    info.summary
                } else {
                    info.doc
                };
                print(&format!(
                    "# {} ({}, {})\n\n{}\n",
                    info.code,
                    info.severity.name(),
                    info.group,
                    body
                ));
                ExitCode::SUCCESS
            }
            None => {
                eprintln!("gltfmat: unknown code '{code}' (see `gltfmat rules`)");
                ExitCode::from(2)
            }
        },
    }
}

fn print(text: &str) {
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

fn run_check(args: CheckArgs) -> ExitCode {
    let options = match build_options(&args) {
        Ok(o) => o,
        Err(message) => {
            eprintln!("gltfmat: {message}");
            return ExitCode::from(2);
        }
    };
    let mut unreadable = false;
    let mut files = Vec::new();
    for input in &args.inputs {
        if input.as_os_str() == "-" || input.is_file() {
            files.push(input.clone());
        } else if input.is_dir() {
            collect_assets(input, &mut files);
        } else {
            eprintln!("gltfmat: {}: no such file or folder", input.display());
            unreadable = true;
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
    let colour = args.format == Format::Human
        && std::io::stdout().is_terminal()
        && std::env::var_os("NO_COLOR").is_none();
    print(&render(args.format, &reports, &RenderOptions { colour }));
    if unreadable {
        ExitCode::from(2)
    } else if reports.iter().any(Report::has_errors) {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

fn check_file(path: &Path, options: &CheckOptions) -> Result<Report, String> {
    if path.as_os_str() == "-" {
        let mut bytes = Vec::new();
        std::io::stdin()
            .read_to_end(&mut bytes)
            .map_err(|e| e.to_string())?;
        return Ok(check_bytes("-", bytes, &NoResources, options));
    }
    let bytes = gltfmat::document::Bytes::open(path).map_err(|e| e.to_string())?;
    let loader = FolderResources::new(cli_upgrade::folder_of(path));
    Ok(check_bytes(
        &path.display().to_string(),
        bytes,
        &loader,
        options,
    ))
}

/// Every .gltf/.glb below a folder, sorted, without following symlinked folders.
fn collect_assets(folder: &Path, out: &mut Vec<PathBuf>) {
    let mut stack = vec![folder.to_path_buf()];
    let mut found = Vec::new();
    while let Some(dir) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                stack.push(path);
            } else if matches!(
                path.extension().and_then(|e| e.to_str()),
                Some("gltf" | "glb")
            ) {
                found.push(path);
            }
        }
    }
    found.sort();
    out.extend(found);
}

fn build_options(args: &CheckArgs) -> Result<CheckOptions, String> {
    let config = match &args.config {
        Some(path) => cli_config::load(path)?,
        None => match cli_config::find_upward() {
            Some(path) => cli_config::load(&path)?,
            None => cli_config::Config::default(),
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
        let (code, level) = cli_config::parse_severity(pair)?;
        options.severity_overrides.insert(code, level);
    }
    if let Some(n) = args.max_issues {
        options.max_issues = n;
    }
    options.deep |= args.deep;
    options
        .disabled_groups
        .extend(args.disabled_groups.iter().cloned());
    for code in options
        .ignore
        .iter()
        .chain(&options.only)
        .chain(options.severity_overrides.keys())
    {
        if codes::find(code).is_none() {
            return Err(format!("unknown code '{code}' (see `gltfmat rules`)"));
        }
    }
    Ok(options)
}
