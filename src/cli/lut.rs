//! `gltfmat lut sheen`: the sheen albedo table the evaluator uses, exported for engines.

use crate::common::{Failure, Outcome};
use gltfmat::SheenTable;
use gltfmat::SheenVisibility;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct LutArgs {
    /// The table: only `sheen` exists.
    #[arg(value_enum)]
    table: TableArg,
    /// Texels per side (rows: sheenRoughness, columns: NdotV, at texel centres).
    #[arg(long, default_value_t = 32)]
    size: usize,
    /// The sheen visibility term the table is computed for.
    #[arg(long, value_enum, default_value = "charlie")]
    visibility: VisibilityArg,
    /// `csv` (E as computed) or `png` (16-bit, E above 1 written as 65535).
    #[arg(long, value_enum, default_value = "csv")]
    format: LutFormat,
    /// Output file (default: standard output for csv; required for png).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum TableArg {
    Sheen,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum VisibilityArg {
    Charlie,
    Ashikhmin,
    /// Charlie with Conty-Kulla terminator softening.
    CharlieSoftened,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum LutFormat {
    Csv,
    Png,
}

pub fn run(args: LutArgs) -> Outcome {
    let TableArg::Sheen = args.table;
    if !(2..=1024).contains(&args.size) {
        return Err(Failure::usage("--size must be between 2 and 1024"));
    }
    let visibility = match args.visibility {
        VisibilityArg::Charlie => SheenVisibility::Charlie,
        VisibilityArg::Ashikhmin => SheenVisibility::Ashikhmin,
        VisibilityArg::CharlieSoftened => SheenVisibility::CharlieSoftened,
    };
    let table = SheenTable::compute(args.size, visibility);
    let bytes = match args.format {
        LutFormat::Csv => table.to_csv().into_bytes(),
        LutFormat::Png => table.to_png(),
    };
    let written = match &args.output {
        Some(path) => gltfmat::write_file(path, &bytes, &[], args.force)
            .map(drop)
            .map_err(|e| e.to_string()),
        None if args.format == LutFormat::Png => Err("--format png needs -o PATH".to_string()),
        None => std::io::stdout()
            .lock()
            .write_all(&bytes)
            .map_err(|e| e.to_string()),
    };
    written.map_err(Failure::usage)?;
    Ok(ExitCode::SUCCESS)
}
