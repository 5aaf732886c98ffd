//! `gltfmat render ASSET`: a material ball, or a contact sheet of every material, to PNG.

use crate::common::{Failure, Outcome};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct RenderArgs {
    /// The asset whose material to draw (glTF 2.0, or glTF 1.0 with PBR-draft materials).
    asset: PathBuf,
    /// Material index or name (default: the first).
    #[arg(long)]
    material: Option<String>,
    /// Every material on one contact sheet, each with its name (also listed on stdout).
    #[arg(long)]
    all: bool,
    /// The PNG to write (never over an existing file without --force).
    #[arg(short, long, default_value = "material.png")]
    output: PathBuf,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
    /// Pixels per side (per material with --all), 8 to 1024: a picture's time grows with its
    /// pixels, and a contact sheet holds at most 1024² of them.
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u32).range(8..=i64::from(gltfmat::MAX_SIZE)))]
    size: u32,
}

pub fn run(args: RenderArgs) -> Outcome {
    // Refused before rendering, which can take a while; asked again when writing.
    gltfmat::may_write(&args.output, &[], args.force).map_err(|e| Failure::usage(e.to_string()))?;
    let mut options = gltfmat::RenderOptions::default();
    options.material = args.material.clone();
    options.all = args.all;
    options.size = args.size;
    let picture = gltfmat::render(&args.asset, &options)?;
    use gltfmat::report::printable;
    for (k, ((i, name), missing)) in picture.drawn.iter().zip(&picture.not_drawn).enumerate() {
        let (row, column) = picture.layout.place(k);
        let name = printable(name);
        outln!("cell {k} (row {row}, column {column}): material {i} '{name}'");
        for what in missing {
            outln!("  not drawn: {}", printable(what));
        }
    }
    for (i, name) in &picture.skipped {
        let name = printable(name);
        outln!("material {i} '{name}': not drawn: {}", gltfmat::NO_MODEL);
    }
    if picture.layout.cell < args.size {
        outln!(
            "cells drawn at {} pixels, not {}: a sheet holds at most {} pixels",
            picture.layout.cell,
            args.size,
            gltfmat::MAX_PIXELS
        );
    }
    let png = gltfmat::png(&picture.image);
    gltfmat::write_file(&args.output, &png, &picture.inputs, args.force)
        .map_err(|e| Failure::usage(e.to_string()))?;
    Ok(ExitCode::SUCCESS)
}
