//! `gltfmat upgrade IN -o OUT`: convert, check the exact output, write it atomically, print
//! the conversion report.

use gltfmat::check::Severity;
use gltfmat::document::uri::FolderResources;
use gltfmat::report::{render, Format, RenderOptions};
use gltfmat::upgrade::{output, upgrade, NoteKind, SpecularGlossiness, UpgradeOptions};
use std::path::{Path, PathBuf};
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

/// The folder external files of `path` are read from.
pub fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

pub fn run(args: UpgradeArgs) -> ExitCode {
    let fail = |message: String| {
        eprintln!("gltfmat: {message}");
        ExitCode::from(2)
    };
    let bytes = match std::fs::read(&args.input) {
        Ok(b) => b,
        Err(e) => return fail(format!("{}: {e}", args.input.display())),
    };
    let options = UpgradeOptions {
        specular_glossiness: match args.specular_glossiness {
            SpecGlossArg::MetalRough => SpecularGlossiness::MetalRough,
            SpecGlossArg::Extension => SpecularGlossiness::Extension,
        },
        double_sided_default: args.double_sided,
    };
    let loader = FolderResources::new(folder_of(&args.input));
    let upgraded = match upgrade(&bytes, &loader, &options) {
        Ok(u) => u,
        Err(e) => {
            eprintln!("gltfmat: {}: {e}", args.input.display());
            return ExitCode::from(1);
        }
    };
    for note in &upgraded.report {
        let kind = match note.kind {
            NoteKind::Decision => "decision",
            NoteKind::Dropped => "dropped",
        };
        println!("{kind:<8} {} {}", note.pointer, note.text);
    }
    if args.verify && !verified(&bytes, &args, &upgraded) {
        eprintln!(
            "gltfmat: a converted material does not render like its source; nothing was written."
        );
        return ExitCode::from(1);
    }
    let Some(name) = args.output.file_name().and_then(|n| n.to_str()) else {
        return fail(format!("{}: not a file name", args.output.display()));
    };
    let files = output::layout(&upgraded, name);
    let checked = match output::write_checked(
        &files,
        &folder_of(&args.output),
        Some(&args.input),
        args.force,
    ) {
        Ok(checked) => checked,
        Err(e) => return fail(e.to_string()),
    };
    let report = checked.report;
    if !checked.written {
        let shown = render(Format::Human, &[report], &RenderOptions { colour: false });
        eprintln!("{shown}gltfmat: the upgraded asset fails its own check; nothing was written.");
        return ExitCode::from(1);
    }
    let warnings = report.count(Severity::Warning);
    println!(
        "wrote {} ({} file(s)); check: 0 errors, {warnings} warning(s)",
        args.output.display(),
        1 + files.side.len()
    );
    ExitCode::SUCCESS
}

/// Compares every 1.0 PBR material with its conversion; prints the results.
fn verified(bytes: &[u8], args: &UpgradeArgs, upgraded: &gltfmat::upgrade::Upgraded) -> bool {
    let loader = FolderResources::new(folder_of(&args.input));
    let Ok(sources) = gltfmat::upgrade::legacy_materials(bytes, &loader) else {
        return false;
    };
    let converted: Vec<crate::cli_compare::Named> = gltfmat::upgrade::converted_materials(upgraded)
        .into_iter()
        .zip(&sources)
        .map(|(m, (name, _))| (name.clone(), Some(m)))
        .collect();
    let pairs: Vec<(usize, usize)> = (0..sources.len()).map(|i| (i, i)).collect();
    let outcomes = crate::cli_compare::compare_pairs(&sources, &converted, &pairs, 0);
    crate::cli_compare::print_human(&outcomes, args.threshold);
    outcomes.iter().all(|o| o.result.max <= args.threshold)
}
