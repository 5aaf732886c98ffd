//! The `gltfmat` command line: one file per subcommand, all on top of the library's façade.
#![deny(unsafe_code)]

/// Writes to a standard stream (`print!` / `eprint!` for the CLI). A reader that went away
/// (`gltfmat … | head`) is ignored: it ends nothing in the middle (an upgrade still writes
/// its files) and is no panic. Any other failure (a full disk) is kept by
/// [`streams::note`] and makes the run exit 2 when it ends.
macro_rules! write_std {
    ($stream:expr, $($arg:tt)*) => {{
        use std::io::Write as _;
        crate::streams::note(write!($stream.lock(), $($arg)*));
    }};
}

/// `print!`, on the terms of [`write_std!`].
macro_rules! out {
    ($($arg:tt)*) => { write_std!(std::io::stdout(), $($arg)*) };
}

/// `eprint!`, on the terms of [`write_std!`].
macro_rules! err {
    ($($arg:tt)*) => { write_std!(std::io::stderr(), $($arg)*) };
}

/// `println!`, on the terms of [`write_std!`].
macro_rules! outln {
    ($($arg:tt)*) => { out!("{}\n", format_args!($($arg)*)) };
}

/// `eprintln!`, on the terms of [`write_std!`].
macro_rules! errln {
    ($($arg:tt)*) => { err!("{}\n", format_args!($($arg)*)) };
}

mod check;
mod common;
mod compare;
mod config;
mod lut;
mod render;
mod report;
mod rules;
mod shard;
mod shell;
mod signals;
mod streams;
mod upgrade;
mod walk;

use clap::{CommandFactory, Parser, Subcommand};
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
    Check(check::CheckArgs),
    /// Convert a glTF 1.0 asset (with WEB3D/KHR/FRAUNHOFER/EXT PBR materials) to glTF 2.0, or
    /// a glTF 2.0 asset's KHR_materials_pbrSpecularGlossiness materials to metallic-roughness.
    Upgrade(upgrade::UpgradeArgs),
    /// Render a material ball (or --all materials) to PNG.
    Render(render::RenderArgs),
    /// Do two materials render the same? ΔE2000 over a UV grid and a set of directions.
    Compare(compare::CompareArgs),
    /// Write one HTML page of the findings, the materials rendered and the textures shown.
    Report(report::ReportArgs),
    /// Export a lookup table of the shading evaluator (the sheen albedo E).
    ///
    /// Row i holds sheenRoughness (i + 0.5)/N, column j NdotV (j + 0.5)/N. E is not bounded
    /// by 1: KHR_materials_sheen's Charlie lobe is not energy-normalised, and at low
    /// sheenRoughness and grazing NdotV its albedo exceeds 1 (the 32² table's first row
    /// peaks at 3.24). The evaluator clamps the base layer's scaling 1 − max(sheenColor)·E
    /// at 0, and below the first row it interpolates towards E = 0, the lobe's limit at
    /// sheenRoughness 0. The CSV holds E as computed; the PNG stores round(E · 65535) in 16
    /// bits, so every E above 1 is written as 65535.
    Lut(lut::LutArgs),
    /// List every code gltfmat can report, with its severity and group.
    Rules {
        /// `table` for people, `json` for scripts.
        #[arg(long, value_enum, default_value = "table")]
        format: rules::ListFormat,
    },
    /// Show the full documentation of one code.
    Explain {
        /// A code as `gltfmat rules` lists it, e.g. TEXTURE_ALPHA_MISSING.
        code: String,
    },
    /// Print a shell completion script (e.g. `gltfmat completions bash > /etc/bash_completion.d/gltfmat`).
    Completions { shell: clap_complete::Shell },
    /// Print the manual page (roff), e.g. `gltfmat man > gltfmat.1`, or write one page per
    /// subcommand with --dir.
    Man {
        /// Write gltfmat.1 and a page per subcommand (gltfmat-check.1, …) into this folder.
        #[arg(long, value_name = "FOLDER")]
        dir: Option<std::path::PathBuf>,
        /// Replace existing pages.
        #[arg(long, requires = "dir")]
        force: bool,
    },
}

fn main() -> ExitCode {
    gltfmat::return_large_blocks_when_freed();
    signals::remove_temporaries_when_ended();
    let outcome = match Cli::parse().command {
        Command::Check(args) => check::run(args),
        Command::Upgrade(args) => upgrade::run(args),
        Command::Lut(args) => lut::run(args),
        Command::Compare(args) => compare::run(args),
        Command::Render(args) => render::run(args),
        Command::Report(args) => report::run(args),
        Command::Rules { format } => rules::list(format),
        Command::Explain { code } => rules::explain(&code),
        Command::Completions { shell } => shell::completions(Cli::command(), shell),
        Command::Man { dir, force } => shell::man(Cli::command(), dir.as_deref(), force),
    };
    let status = outcome.unwrap_or_else(common::Failure::report);
    streams::status_after_flushing(status)
}
