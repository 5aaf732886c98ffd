//! `gltfmat compare A B`: ΔE2000 of paired materials, human or JSON, optional heat maps.

use crate::common::{Failure, Outcome};
use gltfmat::heatmap;
use gltfmat::{compare, CompareOptions};
use gltfmat::{Area, DIRECTIONS};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct CompareArgs {
    /// The source asset (glTF 2.0, or glTF 1.0 with PBR-draft materials).
    a: PathBuf,
    /// The asset compared with it (its materials are paired with A's by index).
    b: PathBuf,
    /// Pair material I of A with material J of B (repeatable; default: same index).
    #[arg(long = "material-map", value_name = "I=J")]
    material_map: Vec<String>,
    /// Largest ΔE2000 allowed (1.0 ≈ one just-noticeable difference).
    #[arg(long, default_value_t = gltfmat::DEFAULT_THRESHOLD, value_parser = crate::common::threshold)]
    threshold: f64,
    /// UV grid per side, at most 4096 (0: the finest texture resolution involved, at least
    /// 16 and at most 4096).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=4096))]
    grid: u32,
    /// `human` for people, `json` for scripts.
    #[arg(long, value_enum, default_value = "human")]
    format: CompareFormat,
    /// Write a ΔE heat map per pair (black 0 → red at the threshold, grey off the mesh); `-N`
    /// is added before the extension when several pairs are compared.
    #[arg(long)]
    heatmap: Option<PathBuf>,
    /// How the first asset's glTF 1.0 spec-gloss draft materials are read; the other
    /// readings' distance from it is printed beside.
    #[arg(long, value_enum, default_value = "appendix")]
    draft_reading: crate::common::DraftReadingArg,
    /// Write an HTML page showing each pair side by side with its figures and heat map.
    #[arg(long, value_name = "HTML")]
    report: Option<PathBuf>,
    /// Replace existing heat map and report files.
    #[arg(long)]
    force: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum CompareFormat {
    Human,
    Json,
}

pub fn print_human(outcomes: &[gltfmat::Outcome], threshold: f64) {
    for line in human_lines(outcomes, threshold) {
        outln!("{}", gltfmat::report::printable(&line));
    }
}

/// One line per compared pair: verdict, ΔE2000 max / p99 / mean, and where the worst is.
pub fn human_lines(outcomes: &[gltfmat::Outcome], threshold: f64) -> Vec<String> {
    (outcomes.iter())
        .map(|o| format!("{}: {}", pair(o), figures(o, threshold)))
        .collect()
}

/// The compared pair: `material I (NAME) ↔ J (NAME)`.
pub fn pair(o: &gltfmat::Outcome) -> String {
    format!("material {} ({}) ↔ {} ({})", o.a.0, o.a.1, o.b.0, o.b.1)
}

/// The verdict and the ΔE2000 figures of one comparison.
pub fn figures(o: &gltfmat::Outcome, threshold: f64) -> String {
    let r = &o.result;
    if !o.is_evaluated() {
        return format!("NOT EVALUATED ({})", o.not_evaluated.join("; "));
    }
    let verdict = match (o.not_evaluated.is_empty(), r.max <= threshold) {
        (true, true) => "same".into(),
        (true, false) => "DIFFERENT".into(),
        (false, true) => format!(
            "NOT EVALUATED ({}); of the rest",
            o.not_evaluated.join("; ")
        ),
        (false, false) => format!(
            "DIFFERENT in what is evaluated; NOT EVALUATED ({}); of the rest",
            o.not_evaluated.join("; ")
        ),
    };
    let w = &r.worst;
    let [tv, pv] = w.directions.view;
    let [tl, pl] = w.directions.light;
    let over = match w.background > 0.0 {
        true => ", over white",
        false => "",
    };
    let behind = match w.behind {
        true => ", seen from behind (one material draws its back face, the other culls it)",
        false => "",
    };
    let dominated = r
        .dominant
        .map(|input| format!(" (mostly {input})"))
        .unwrap_or_default();
    // A point on the mesh whose sets differ names its coordinates in each.
    let on_mesh = match w.sets.len() {
        0 | 1 => String::new(),
        _ => {
            let sets = (w.sets.iter().enumerate().skip(1))
                .map(|(n, [u, v])| format!("TEXCOORD_{n} ({u:.4}, {v:.4})"))
                .collect::<Vec<_>>()
                .join(", ");
            format!(" on the mesh, {sets}")
        }
    };
    let blends = match r.blended_corners {
        0 => String::new(),
        n => {
            format!(" ({n} corners, where both are blends of the centres around them, not sampled)")
        }
    };
    let area = match r.area {
        Area::Mesh { texels } => {
            let share = 100.0 * texels as f64 / (f64::from(r.grid) * f64::from(r.grid)).max(1.0);
            // A mesh on a few texels of a large texture is not "0 %".
            let share = match share < 1.0 {
                true => format!("{share:.2}"),
                false => format!("{share:.0}"),
            };
            format!(" on the mesh ({share} % of the UV square)")
        }
        Area::Whole(why) => format!(" over the whole UV square ({why})"),
    };
    let mut line = format!(
        "{verdict}: ΔE2000 max {:.4}{dominated}, p99 {:.4}, mean {:.4}; worst at uv ({:.4}, {:.4}){on_mesh}, view θ {tv:.2}° φ {pv:.2}°, light θ {tl:.2}° φ {pl:.2}°{over}{behind}; {}² texel centres and corners{area}{blends} × {} directions = {} samples, and a dense search of directions where they differ most",
        r.max, r.p99, r.mean, w.uv[0], w.uv[1], r.grid, DIRECTIONS.len(), r.samples
    );
    if let Some(a) = &o.ambiguity {
        line += &format!(
            "; source read as the {}: the drafts' readings differ by up to ΔE2000 {:.2} here (on a {}² grid; furthest: the {}), an ambiguity of the source, not of the conversion",
            a.read_as, a.max, a.grid, a.furthest
        );
    }
    line
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

pub fn run(args: CompareArgs) -> Outcome {
    let mut options = CompareOptions::default();
    options.pairs = parse_map(&args.material_map).map_err(Failure::usage)?;
    options.grid = args.grid;
    options.heat_maps = args.heatmap.is_some() || args.report.is_some();
    options.draft_reading = args.draft_reading.reading();
    if let Some(path) = &args.report {
        gltfmat::may_write(path, &[], args.force).map_err(|e| Failure::usage(e.to_string()))?;
    }
    if let Some(path) = &args.heatmap {
        // Refused before comparing, which can take a while; asked again for every file.
        gltfmat::may_write(path, &[], args.force).map_err(|e| Failure::usage(e.to_string()))?;
    }
    let comparison = compare(&args.a, &args.b, &options)?;
    let outcomes = comparison.outcomes;
    if let Some(path) = &args.heatmap {
        let mut maps = Vec::new();
        // A pair with nothing evaluated has no map (the others keep their numbers).
        let evaluated = (outcomes.iter().enumerate()).filter(|(_, o)| o.is_evaluated());
        for (k, o) in evaluated {
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
            maps.push((target, gltfmat::png(&image)));
        }
        let files: Vec<(&Path, &[u8])> = (maps.iter())
            .map(|(target, png)| (target.as_path(), png.as_slice()))
            .collect();
        gltfmat::write_files(&files, &comparison.inputs, args.force)
            .map_err(|e| Failure::usage(e.to_string()))?;
    }
    if let Some(path) = &args.report {
        write_report(
            path,
            (&args.a, &args.b),
            &outcomes,
            args.threshold,
            &comparison.inputs,
            args.force,
        )?;
    }
    if args.format == CompareFormat::Json {
        let list: Vec<_> = (outcomes.iter())
            .map(|o| o.to_json(args.threshold))
            .collect();
        outln!(
            "{}",
            serde_json::to_string_pretty(&list).unwrap_or_default()
        );
    } else {
        print_human(&outcomes, args.threshold);
    }
    if outcomes.is_empty() {
        return Err(Failure::usage(
            "no material pairs to compare: an asset without materials has none (its primitives draw glTF's default material, which is not compared)",
        ));
    }
    Ok(if outcomes.iter().all(|o| o.same(args.threshold)) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// An HTML page of compared pairs: both balls, the figures and the heat map of each.
pub fn write_report(
    path: &Path,
    assets: (&Path, &Path),
    outcomes: &[gltfmat::Outcome],
    threshold: f64,
    inputs: &[gltfmat::FileId],
    force: bool,
) -> Result<(), Failure> {
    let mut page = gltfmat::Page::new("gltfmat comparison");
    let lines: Vec<String> = outcomes.iter().map(|o| figures(o, threshold)).collect();
    page.add_comparison(assets, outcomes, &lines, threshold);
    gltfmat::write_file(path, page.html().as_bytes(), inputs, force)
        .map(|_| ())
        .map_err(|e| Failure::usage(e.to_string()))
}
