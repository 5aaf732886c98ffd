//! `gltfmat compare A B`, and the proof behind `gltfmat upgrade --verify`.

use gltfmat::document::uri::FolderResources;
use gltfmat::shade::brdf::SheenVisibility;
use gltfmat::shade::compare::{compare, Comparison, DIRECTIONS};
use gltfmat::shade::load::gltf2_materials;
use gltfmat::shade::material::Shader;
use gltfmat::shade::render::heatmap;
use gltfmat::shade::sample::MaterialSource;
use gltfmat::shade::sheen_table::SheenTable;
use gltfmat::upgrade::{legacy_materials, UpgradeError};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct CompareArgs {
    /// Two assets (glTF 2.0, or glTF 1.0 with PBR-draft materials).
    a: PathBuf,
    b: PathBuf,
    /// Pair material I of A with material J of B (repeatable; default: same index).
    #[arg(long = "material-map", value_name = "I=J")]
    material_map: Vec<String>,
    /// Largest ΔE2000 allowed (1.0 ≈ one just-noticeable difference).
    #[arg(long, default_value_t = 1.0)]
    threshold: f64,
    /// UV grid per side (0: the finest texture resolution involved, at least 16).
    #[arg(long, default_value_t = 0)]
    grid: u32,
    #[arg(long, value_enum, default_value = "human")]
    format: CompareFormat,
    /// Write a ΔE heat map per pair (black 0 → red at the threshold); `-N` is added before
    /// the extension when several pairs are compared.
    #[arg(long)]
    heatmap: Option<PathBuf>,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum CompareFormat {
    Human,
    Json,
}

pub type Named = (String, Option<MaterialSource>);

/// A file's materials: a 1.0 asset's PBR-draft materials, otherwise a 2.0 asset's.
pub fn load(path: &Path) -> Result<Vec<Named>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let loader = FolderResources::new(crate::cli_upgrade::folder_of(path));
    match legacy_materials(&bytes, &loader) {
        Ok(materials) => Ok(materials),
        Err(UpgradeError::NotGltf1(_)) => {
            let materials = gltf2_materials(bytes, &path.display().to_string(), &loader)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Ok(materials.into_iter().map(|(n, m)| (n, Some(m))).collect())
        }
        Err(e) => Err(format!("{}: {e}", path.display())),
    }
}

/// A shader whose sheen table covers the materials (a 16² table only when one has sheen).
pub fn shader_for(materials: &[&MaterialSource]) -> Shader {
    let sheen = materials.iter().any(|m| match m {
        MaterialSource::Gltf2(prepared) => prepared.has_sheen,
        MaterialSource::Legacy { .. } => false,
    });
    Shader::new(SheenTable::compute(
        if sheen { 16 } else { 2 },
        SheenVisibility::Charlie,
    ))
}

pub struct Outcome {
    pub a: (usize, String),
    pub b: (usize, String),
    pub result: Comparison,
}

/// Compares each pair; returns the outcomes (pairs with a missing side are skipped).
pub fn compare_pairs(
    a: &[Named],
    b: &[Named],
    pairs: &[(usize, usize)],
    grid: u32,
) -> Vec<Outcome> {
    let present: Vec<&MaterialSource> = a.iter().chain(b).filter_map(|(_, m)| m.as_ref()).collect();
    let shader = shader_for(&present);
    pairs
        .iter()
        .filter_map(|&(i, j)| {
            let (name_a, Some(ma)) = a.get(i)? else {
                return None;
            };
            let (name_b, Some(mb)) = b.get(j)? else {
                return None;
            };
            Some(Outcome {
                a: (i, name_a.clone()),
                b: (j, name_b.clone()),
                result: compare(&shader, ma, mb, grid),
            })
        })
        .collect()
}

pub fn print_human(outcomes: &[Outcome], threshold: f64) {
    for o in outcomes {
        let r = &o.result;
        let verdict = if r.max <= threshold {
            "same"
        } else {
            "DIFFERENT"
        };
        let (tv, tl, phi) = r.worst.directions;
        println!(
            "material {} ({}) ↔ {} ({}): {verdict}: ΔE2000 max {:.4}, p99 {:.4}, mean {:.4}; worst at uv ({:.4}, {:.4}), θv {tv}°, θl {tl}°, φ {phi}°; {}² grid × {} directions = {} samples",
            o.a.0, o.a.1, o.b.0, o.b.1, r.max, r.p99, r.mean, r.worst.uv[0], r.worst.uv[1], r.grid, DIRECTIONS.len(), r.samples
        );
    }
}

fn parse_map(entries: &[String]) -> Result<Vec<(usize, usize)>, String> {
    entries
        .iter()
        .map(|e| {
            let (i, j) = e
                .split_once('=')
                .ok_or_else(|| format!("--material-map expects I=J, got '{e}'"))?;
            let parse = |s: &str| {
                s.trim()
                    .parse::<usize>()
                    .map_err(|_| format!("--material-map: '{s}' is not an index"))
            };
            Ok((parse(i)?, parse(j)?))
        })
        .collect()
}

pub fn run(args: CompareArgs) -> ExitCode {
    let loaded = load(&args.a).and_then(|a| Ok((a, load(&args.b)?)));
    let (a, b) = match loaded {
        Ok(pair) => pair,
        Err(message) => {
            eprintln!("gltfmat: {message}");
            return ExitCode::from(2);
        }
    };
    let pairs = match parse_map(&args.material_map) {
        Ok(p) if p.is_empty() => (0..a.len().min(b.len())).map(|i| (i, i)).collect(),
        Ok(p) => p,
        Err(message) => {
            eprintln!("gltfmat: {message}");
            return ExitCode::from(2);
        }
    };
    let outcomes = compare_pairs(&a, &b, &pairs, args.grid);
    if let Some(path) = &args.heatmap {
        for (k, o) in outcomes.iter().enumerate() {
            let target = if outcomes.len() == 1 {
                path.clone()
            } else {
                path.with_file_name(format!(
                    "{}-{k}.png",
                    path.file_stem()
                        .and_then(|s| s.to_str())
                        .unwrap_or("heatmap")
                ))
            };
            let image = heatmap(&o.result.per_texel, o.result.grid, args.threshold);
            if let Err(e) = image.save(&target) {
                eprintln!("gltfmat: {}: {e}", target.display());
                return ExitCode::from(2);
            }
        }
    }
    if args.format == CompareFormat::Json {
        let list: Vec<_> = outcomes
            .iter()
            .map(|o| {
                json!({"a": o.a.0, "aName": o.a.1, "b": o.b.0, "bName": o.b.1,
                    "max": o.result.max, "p99": o.result.p99, "mean": o.result.mean,
                    "worst": {"uv": o.result.worst.uv, "thetaV": o.result.worst.directions.0,
                              "thetaL": o.result.worst.directions.1, "phi": o.result.worst.directions.2},
                    "grid": o.result.grid, "samples": o.result.samples,
                    "pass": o.result.max <= args.threshold})
            })
            .collect();
        println!(
            "{}",
            serde_json::to_string_pretty(&list).unwrap_or_default()
        );
    } else {
        print_human(&outcomes, args.threshold);
    }
    if outcomes.is_empty() {
        eprintln!("gltfmat: no material pairs to compare");
        return ExitCode::from(2);
    }
    if outcomes.iter().all(|o| o.result.max <= args.threshold) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}

#[derive(clap::Args)]
pub struct RenderArgs {
    asset: PathBuf,
    /// Material index or name (default: the first).
    #[arg(long)]
    material: Option<String>,
    /// Every material on one contact sheet, each with its name (also listed on stdout).
    #[arg(long)]
    all: bool,
    #[arg(short, long, default_value = "material.png")]
    output: PathBuf,
    /// Pixels per side (per material with --all).
    #[arg(long, default_value_t = 512)]
    size: u32,
}

pub fn render(args: RenderArgs) -> ExitCode {
    let materials = match load(&args.asset) {
        Ok(m) => m,
        Err(message) => {
            eprintln!("gltfmat: {message}");
            return ExitCode::from(2);
        }
    };
    let chosen: Vec<(usize, &String, &MaterialSource)> = materials
        .iter()
        .enumerate()
        .filter_map(|(i, (name, m))| Some((i, name, m.as_ref()?)))
        .filter(|(i, name, _)| match (&args.material, args.all) {
            (_, true) | (None, false) => true,
            (Some(wanted), false) => wanted == *name || wanted.parse() == Ok(*i),
        })
        .take(if args.all { usize::MAX } else { 1 })
        .collect();
    if chosen.is_empty() {
        eprintln!(
            "gltfmat: {}: no such material to render",
            args.asset.display()
        );
        return ExitCode::from(2);
    }
    let sources: Vec<&MaterialSource> = chosen.iter().map(|(_, _, m)| *m).collect();
    let shader = shader_for(&sources);
    let size = args.size.clamp(8, 4096);
    let image = if args.all {
        let named: Vec<(&str, &MaterialSource)> = chosen
            .iter()
            .map(|(_, name, m)| (name.as_str(), *m))
            .collect();
        gltfmat::shade::render::contact_sheet(&shader, &named, size)
    } else {
        gltfmat::shade::render::material_ball(&shader, sources[0], size)
    };
    for (k, (i, name, _)) in chosen.iter().enumerate() {
        println!(
            "cell {k} (row {}, column {}): material {i} '{name}'",
            k / 4,
            k % 4
        );
    }
    match image.save(&args.output) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("gltfmat: {}: {e}", args.output.display());
            ExitCode::from(2)
        }
    }
}
