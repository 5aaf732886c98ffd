//! `gltfmat upgrade IN -o OUT`: convert, check the exact output, write it atomically, print
//! the conversion report.

use crate::common::{Failure, Outcome};
use gltfmat::document::uri::folder_of;
use gltfmat::report::{render, Format, Style};
use gltfmat::shade::pairing::compare_pairs;
use gltfmat::upgrade::{legacy_materials, output, NoteKind, SpecularGlossiness};
use gltfmat::{upgrade, FolderResources, Severity, UpgradeOptions, Upgraded};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct UpgradeArgs {
    /// The glTF 1.0 asset (.gltf, or a KHR_binary_glTF .glb).
    input: PathBuf,
    /// Output: .glb embeds everything; .gltf writes .bin and images beside it.
    #[arg(short, long)]
    output: PathBuf,
    /// How spec-gloss materials are written.
    #[arg(long, value_enum, default_value = "metal-rough")]
    specular_glossiness: SpecGlossArg,
    /// Materials whose 1.0 form says nothing about culling become double-sided.
    #[arg(long)]
    double_sided: bool,
    /// Replace an existing output (never the input).
    #[arg(long)]
    force: bool,
    /// Prove with the shading evaluator that each converted material renders like its 1.0
    /// source (ΔE2000 ≤ --threshold); otherwise nothing is written.
    #[arg(long)]
    verify: bool,
    /// ΔE2000 allowed by --verify.
    #[arg(long, default_value_t = 1.0)]
    threshold: f64,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SpecGlossArg {
    MetalRough,
    Extension,
}

pub fn run(args: UpgradeArgs) -> Outcome {
    let bytes = std::fs::read(&args.input)
        .map_err(|e| Failure::usage(format!("{}: {e}", args.input.display())))?;
    let options = UpgradeOptions::default()
        .with_specular_glossiness(match args.specular_glossiness {
            SpecGlossArg::MetalRough => SpecularGlossiness::MetalRough,
            SpecGlossArg::Extension => SpecularGlossiness::Extension,
        })
        .with_double_sided_default(args.double_sided);
    let loader = FolderResources::beside(&args.input);
    let upgraded = upgrade(&bytes, &loader, &options)
        .map_err(|e| Failure::refused(format!("{}: {e}", args.input.display())))?;
    for note in &upgraded.report {
        let kind = match note.kind {
            NoteKind::Decision => "decision",
            NoteKind::Dropped => "dropped",
        };
        println!("{kind:<8} {} {}", note.pointer, note.text);
    }
    if args.verify && !verified(&bytes, &args, &upgraded) {
        return Err(Failure::refused(
            "a converted material does not render like its source; nothing was written.",
        ));
    }
    let Some(name) = args.output.file_name().and_then(|n| n.to_str()) else {
        return Err(Failure::usage(format!(
            "{}: not a file name",
            args.output.display()
        )));
    };
    let files = output::layout(&upgraded, name);
    let checked = output::write_checked(
        &files,
        &folder_of(&args.output),
        Some(&args.input),
        args.force,
    )
    .map_err(|e| Failure::usage(e.to_string()))?;
    let report = checked.report;
    if !checked.written {
        eprint!("{}", render(Format::Human, &[report], &Style::new(false)));
        return Err(Failure::refused(
            "the upgraded asset fails its own check; nothing was written.",
        ));
    }
    let warnings = report.count(Severity::Warning);
    println!(
        "wrote {} ({} file(s)); check: 0 errors, {warnings} warning(s)",
        args.output.display(),
        1 + files.side.len()
    );
    Ok(ExitCode::SUCCESS)
}

/// Compares every 1.0 PBR material with its conversion; prints the results.
fn verified(bytes: &[u8], args: &UpgradeArgs, upgraded: &Upgraded) -> bool {
    let loader = FolderResources::beside(&args.input);
    let Ok(sources) = legacy_materials(bytes, &loader) else {
        return false;
    };
    let converted: Vec<_> = gltfmat::upgrade::converted_materials(upgraded)
        .into_iter()
        .zip(&sources)
        .map(|(m, (name, _))| (name.clone(), Some(m)))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..sources.len()).map(|i| (i, i)).collect();
    let outcomes = compare_pairs(&sources, &converted, &pairs, 0);
    crate::compare::print_human(&outcomes, args.threshold);
    outcomes.iter().all(|o| o.result.max <= args.threshold)
}
