//! `gltfmat upgrade IN -o OUT`: convert, check the exact output, write it atomically, print
//! the conversion report.

use crate::common::{Failure, Outcome};
use gltfmat::folder_of;
use gltfmat::report::{render, Format, Style};
use gltfmat::upgrade_output as output;
use gltfmat::FileId;
use gltfmat::Report;
use gltfmat::{upgrade, CheckOptions, FolderResources, Severity, UpgradeOptions, Upgraded};
use gltfmat::{Items, Note, NoteKind, SpecularGlossiness};
use std::collections::HashMap;
use std::hash::Hash;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct UpgradeArgs {
    /// The glTF 1.0 asset (.gltf, or a KHR_binary_glTF .glb) to upgrade, or a glTF 2.0 asset
    /// (.gltf, .glb) whose KHR_materials_pbrSpecularGlossiness materials are to be converted.
    input: PathBuf,
    /// Output: .glb embeds everything; .gltf writes .bin and images beside it; - writes a
    /// GLB to stdout (the notes then go to stderr).
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
    /// Refuse the output when the proof fails: a converted material differs from its source
    /// by more than --threshold ΔE2000 (without it the proof's figures are printed and a
    /// failure is a warning).
    #[arg(long, conflicts_with = "no_verify")]
    verify: bool,
    /// Skip the proof (every converted material is otherwise evaluated against its source).
    #[arg(long)]
    no_verify: bool,
    /// The reading of a 1.0 PBR draft's spec-gloss text to convert under: the conversion is
    /// exact under it and the proof judges by it; how far the drafts' other readings are
    /// from it is printed beside, as the source's own ambiguity.
    #[arg(long, value_enum, default_value = "appendix")]
    draft_reading: crate::common::DraftReadingArg,
    /// For a glTF 2.0 input: refuse an output with any error, also errors the input had
    /// already (by default those are passed through, reported, and the output is written when
    /// it has no error of its own).
    #[arg(long)]
    strict: bool,
    /// Write an HTML page showing each converted material beside its source, with the
    /// proof's figures and a heat map of where they differ (needs a file output).
    #[arg(long, value_name = "HTML", conflicts_with = "no_verify")]
    report: Option<PathBuf>,
    /// ΔE2000 a converted material may differ from its source by.
    #[arg(long, default_value_t = gltfmat::DEFAULT_THRESHOLD, value_parser = crate::common::threshold)]
    threshold: f64,
    /// Print to stderr how long the conversion, the proof and the output's check and write
    /// each took (wall-clock seconds).
    #[arg(long)]
    timings: bool,
}

/// Wall-clock time of the upgrade's three stages, for `--timings`.
struct Timings {
    enabled: bool,
    since: std::time::Instant,
    stages: Vec<(&'static str, f64)>,
}

impl Timings {
    fn new(enabled: bool) -> Timings {
        Timings {
            enabled,
            since: std::time::Instant::now(),
            stages: Vec::new(),
        }
    }

    /// Ends the stage `name` (begun when the one before ended).
    fn stage(&mut self, name: &'static str) {
        let now = std::time::Instant::now();
        self.stages.push((name, (now - self.since).as_secs_f64()));
        self.since = now;
    }

    fn print(&self) {
        if self.enabled {
            let each = (self.stages.iter()).map(|(name, s)| format!("{name} {s:.3} s"));
            eprintln!("timings: {}", each.collect::<Vec<_>>().join(", "));
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SpecGlossArg {
    MetalRough,
    Extension,
}

pub fn run(args: UpgradeArgs) -> Outcome {
    let destination = Destination::of(&args.output)?;
    let input_id = FileId::of_path(&args.input);
    refuse_unwritable(&args, &destination, input_id)?;
    let bytes = gltfmat::read_file(&args.input)
        .map_err(|e| Failure::usage(format!("{}: {e}", args.input.display())))?;
    let inherited = input_errors(&args.input);
    let tolerated = tolerated_errors(&args, inherited.as_ref());
    let inherited = inherited.map_or(0, |errors| errors.count());
    let options = args.options();
    let loader = FolderResources::beside(&args.input).repairing_letter_case();
    // The bytes go to the upgrade, which lets a `.gltf`'s text go once its tree is built;
    // the proof reads the file again, and proves nothing if it changed in between.
    let read = (!args.no_verify).then(|| Fingerprint::of(&bytes));
    let mut timings = Timings::new(args.timings);
    let mut upgraded = upgrade(bytes, &loader, &options)
        .map_err(|e| Failure::refused(format!("{}: {e}", args.input.display())))?;
    timings.stage("conversion");
    let mut log = Log::to(&destination);
    print_notes(&upgraded.report, &mut log);
    let proving = read.is_some();
    let disproved = read.is_some_and(|read| !proved(read, &args, &upgraded, &mut log));
    if proving {
        timings.stage("proof");
    }
    if disproved {
        if args.verify {
            return Err(Failure::refused(
                "the proof does not show that every converted material renders like its source (the proof lines say which does not, or was not evaluated); nothing was written.",
            ));
        }
        log.line(format_args!("warning: the proof does not show that every converted material renders like its source within ΔE2000 {} (the proof lines say which does not, or was not evaluated; the output is written; --verify refuses it)", args.threshold));
    }
    let (folder, name) = match destination {
        Destination::Stdout => {
            let written = write_to_stdout(&mut upgraded, &args.input, &tolerated, inherited);
            timings.stage("output check and write");
            timings.print();
            return written;
        }
        Destination::File { folder, name } => (folder, name),
    };
    let files = output::layout_releasing_json(&mut upgraded, &name);
    let protected: Vec<FileId> = input_id.into_iter().chain(loader.files_read()).collect();
    if let Some(page) = &args.report {
        // Refused before the asset is written, not after: its side files and the files the
        // input read are known only now.
        for file in std::iter::once(&files.main).chain(&files.side) {
            refuse_report_over_output(page, &folder, &file.name)?;
        }
        gltfmat::may_write(page, &protected, args.force)
            .map_err(|e| Failure::usage(e.to_string()))?;
    }
    let checked = output::write_checked(&files, &folder, &protected, args.force, &tolerated)
        .map_err(|e| Failure::usage(e.to_string()))?;
    timings.stage("output check and write");
    timings.print();
    let report = checked.report;
    if !checked.written {
        return Err(refuse_failed_check(
            report,
            &upgraded,
            &args.input,
            inherited,
        ));
    }
    print_written(&args.output, 1 + files.side.len(), &report);
    if let Some(page) = &args.report {
        write_report(&args, page)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Refuses, before converting (a conversion can take minutes), an output or report file that
/// could not be written: one that exists (without --force) or is the input, or a report
/// asked for beside an output on stdout.
fn refuse_unwritable(
    args: &UpgradeArgs,
    destination: &Destination,
    input_id: Option<FileId>,
) -> Result<(), Failure> {
    if let Some(report) = &args.report {
        if matches!(destination, Destination::Stdout) {
            return Err(Failure::usage(
                "--report needs the output in a file, not on stdout",
            ));
        }
        gltfmat::may_write(report, &[], args.force).map_err(|e| Failure::usage(e.to_string()))?;
        if let Destination::File { folder, name } = destination {
            refuse_report_over_output(report, folder, name)?;
        }
    }
    if let Destination::File { folder, name } = destination {
        let protected: Vec<FileId> = input_id.into_iter().collect();
        gltfmat::may_write(&folder.join(name), &protected, args.force)
            .map_err(|e| Failure::usage(e.to_string()))?;
    }
    Ok(())
}

/// Refuses a `--report` page that names file `name` of the output's `folder`: one would
/// replace the other.
fn refuse_report_over_output(report: &Path, folder: &Path, name: &str) -> Result<(), Failure> {
    let place = |folder: &Path, name: &std::ffi::OsStr| {
        folder.canonicalize().ok().map(|folder| folder.join(name))
    };
    let report_place = report
        .file_name()
        .and_then(|file| place(&folder_of(report), file));
    if report_place.is_some() && report_place == place(folder, name.as_ref()) {
        return Err(Failure::usage(format!(
            "{}: the --report page would replace {name}, a file of the upgraded asset",
            report.display()
        )));
    }
    Ok(())
}

impl UpgradeArgs {
    fn options(&self) -> UpgradeOptions {
        UpgradeOptions::default()
            .with_specular_glossiness(match self.specular_glossiness {
                SpecGlossArg::MetalRough => SpecularGlossiness::MetalRough,
                SpecGlossArg::Extension => SpecularGlossiness::Extension,
            })
            .with_double_sided_default(self.double_sided)
            .with_draft_reading(self.draft_reading.reading())
    }
}

/// The line saying what was written and what its check found.
fn print_written(output: &std::path::Path, files: usize, report: &gltfmat::Report) {
    let (errors, warnings) = (
        report.count(Severity::Error),
        report.count(Severity::Warning),
    );
    let passed = if errors > 0 {
        " (the input's own, passed through)"
    } else {
        ""
    };
    outln!(
        "wrote {} ({files} file(s)); check: {errors} error(s){passed}, {warnings} warning(s)",
        output.display()
    );
}

/// What the upgrade read: its length and hash, to tell whether the proof reads the same.
#[derive(PartialEq)]
struct Fingerprint(usize, u64);

impl Fingerprint {
    fn of(bytes: &[u8]) -> Fingerprint {
        let mut hasher = std::hash::DefaultHasher::new();
        std::hash::Hasher::write(&mut hasher, bytes);
        Fingerprint(bytes.len(), std::hash::Hasher::finish(&hasher))
    }
}

/// Where the output goes: a `.gltf`/`.glb` file, or stdout (`-o -`, as a GLB).
enum Destination {
    Stdout,
    File { folder: PathBuf, name: String },
}

impl Destination {
    fn of(output: &Path) -> Result<Destination, Failure> {
        if output.as_os_str() == "-" {
            return Ok(Destination::Stdout);
        }
        let name = (output.file_name().and_then(|n| n.to_str()))
            .filter(|_| !output.as_os_str().to_string_lossy().ends_with(['/', '\\']))
            .filter(|n| {
                let n = n.to_ascii_lowercase();
                n.ends_with(".gltf") || n.ends_with(".glb")
            });
        let Some(name) = name else {
            return Err(Failure::usage(format!(
                "{}: the output must be a file named *.gltf or *.glb (or - for a GLB on stdout)",
                output.display()
            )));
        };
        // Said before converting, and of the folder the user named, not of a temporary in it.
        let folder = folder_of(output);
        if !folder.is_dir() {
            return Err(Failure::usage(format!(
                "{}: the output folder {} does not exist (or is not a folder)",
                output.display(),
                folder.display()
            )));
        }
        Ok(Destination::File {
            folder,
            name: name.to_string(),
        })
    }
}

/// The conversion's notes: on stdout, or on stderr when stdout carries the asset.
struct Log {
    to_stderr: bool,
}

impl Log {
    fn to(destination: &Destination) -> Log {
        Log {
            to_stderr: matches!(destination, Destination::Stdout),
        }
    }

    fn line(&mut self, line: std::fmt::Arguments) {
        let line = gltfmat::report::printable(&line.to_string()).into_owned();
        if self.to_stderr {
            errln!("{line}");
        } else {
            outln!("{line}");
        }
    }
}

/// How many places a report line names before it only counts the rest.
const PLACES_SHOWN: usize = 3;

/// The conversion report, one line per distinct note in the order first made, naming where
/// it applies: an asset's 10^5 alike materials give one line, not 10^5.
fn print_notes(notes: &[Note], log: &mut Log) {
    let lines = (notes.iter()).map(|note| ((note.kind, &*note.text), note.pointer.as_str()));
    for ((kind, text), pointers) in grouped(lines) {
        let kind = match kind {
            NoteKind::Decision => "decision",
            NoteKind::Dropped => "dropped",
        };
        log.line(format_args!("{kind:<8} {} {text}", places(&pointers)));
    }
}

/// Items by key, in the order each key first comes, each with the places it comes at.
fn grouped<K: Clone + Eq + Hash, P>(items: impl IntoIterator<Item = (K, P)>) -> Vec<(K, Vec<P>)> {
    let mut groups: Vec<(K, Vec<P>)> = Vec::new();
    let mut group_of: HashMap<K, usize> = HashMap::new();
    for (key, place) in items {
        let at = *group_of.entry(key.clone()).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[at].1.push(place);
    }
    groups
}

/// The first few places, then how many more: a line for 10^5 alike materials stays a line.
/// The whole asset (pointer "") is shown as `/`, as the check's findings show it.
fn places<P: AsRef<str>>(places: &[P]) -> String {
    let shown: Vec<&str> = (places.iter().take(PLACES_SHOWN))
        .map(|place| match place.as_ref() {
            "" => "/",
            place => place,
        })
        .collect();
    let mut text = shown.join(", ");
    if places.len() > PLACES_SHOWN {
        text += &format!(" and {} more", places.len() - PLACES_SHOWN);
    }
    text
}

/// `-o -`: the GLB, checked in memory, on stdout.
fn write_to_stdout(
    upgraded: &mut Upgraded,
    input: &Path,
    tolerated: &output::Tolerated,
    inherited: usize,
) -> Outcome {
    let (glb, report) = output::checked_glb(upgraded, "-.glb").map_err(|bytes| {
        Failure::usage(gltfmat::WriteError::GlbTooLarge("stdout".into(), bytes).to_string())
    })?;
    if !tolerated.accepts(&report) {
        return Err(refuse_failed_check(report, upgraded, input, inherited));
    }
    let mut stdout = std::io::stdout().lock();
    glb.write_to(&mut stdout)
        .and_then(|()| stdout.flush())
        .map_err(|e| Failure::usage(format!("stdout: {e}")))?;
    Ok(ExitCode::SUCCESS)
}

/// The refusal of an output that fails its own check: the findings, then for each error the
/// 1.0 object its place was made from, so that the user knows which input construct to fix;
/// of a 2.0 input, whether its own errors are what the upgrade passed through.
fn refuse_failed_check(
    report: Report,
    upgraded: &Upgraded,
    input: &Path,
    inherited: usize,
) -> Failure {
    let mut origins: Vec<String> = (report.diagnostics.iter())
        .filter(|d| d.severity == Severity::Error)
        .filter_map(|d| {
            let at = d.pointer()?;
            Some(format!(
                "  {at} ({}) was made from 1.0 {}",
                d.code,
                upgraded.origin_of(at)?
            ))
        })
        .collect();
    origins.dedup();
    err!("{}", render(Format::Human, &[report], &Style::new(false)));
    if !origins.is_empty() {
        errln!(
            "where the errors come from in the input:\n{}",
            crate::common::printable_lines(&origins.join("\n"))
        );
    }
    if inherited > 0 {
        return Failure::refused(format!("the upgraded asset fails its own check; nothing was written. The input is glTF 2.0 with {inherited} error(s) of its own, which the upgrade passes through unchanged: `gltfmat check {}` lists them in the input.", input.display()));
    }
    Failure::refused("the upgraded asset fails its own check; nothing was written.")
}

/// A glTF 2.0 input's own errors, checked before anything is converted (None for a 1.0
/// input, whose every object is rebuilt and must be valid).
fn input_errors(input: &Path) -> Option<output::Tolerated> {
    let report = gltfmat::check_path(input, &CheckOptions::default()).ok()?;
    let gltf2 = report
        .info
        .version
        .as_deref()
        .is_some_and(|v| v.starts_with("2."));
    gltf2.then(|| output::Tolerated::errors_of(&report))
}

/// The errors an output may keep: a 2.0 input's own, said, unless `--strict`.
fn tolerated_errors(
    args: &UpgradeArgs,
    inherited: Option<&output::Tolerated>,
) -> output::Tolerated {
    match inherited {
        Some(errors) if !args.strict && errors.count() > 0 => {
            outln!(
                "note: the input has {} error(s) of its own (`gltfmat check {}` lists them); they are passed through, and the output is written if it has no other (--strict refuses them).",
                errors.count(),
                args.input.display()
            );
            errors.clone()
        }
        _ => output::Tolerated::none(),
    }
}

/// The proof: every source material that has a model of its own (a 1.0 asset's PBR-draft
/// materials, every material of a 2.0 asset) compared with its conversion, one line each in
/// the log. False when the proof does not hold ([`gltfmat::proof_holds`]).
fn proved(read: Fingerprint, args: &UpgradeArgs, upgraded: &Upgraded, log: &mut Log) -> bool {
    // No material, nothing to compare: the input is not read again.
    if upgraded.json.items("materials").is_none_or(Items::is_empty) {
        return true;
    }
    let bytes = match gltfmat::read_file(&args.input) {
        Ok(bytes) if Fingerprint::of(&bytes) == read => bytes,
        Ok(_) => {
            log.line(format_args!(
                "proof: the input changed while it was upgraded"
            ));
            return false;
        }
        Err(e) => {
            log.line(format_args!("proof: {}: {e}", args.input.display()));
            return false;
        }
    };
    let loader = FolderResources::beside(&args.input).repairing_letter_case();
    let name = args.input.to_string_lossy();
    let outcomes = match gltfmat::prove(bytes, &name, &loader, upgraded) {
        Ok(outcomes) => outcomes,
        Err(why) => {
            log.line(format_args!("proof: {why}"));
            return false;
        }
    };
    let lines = (outcomes.iter()).map(|o| {
        (
            crate::compare::figures(o, args.threshold),
            crate::compare::pair(o),
        )
    });
    // Pairs with the same figures (alike materials, compared once) share one line.
    for (figures, pairs) in grouped(lines) {
        log.line(format_args!("proof: {}: {figures}", places(&pairs)));
    }
    gltfmat::proof_holds(&outcomes, args.threshold)
}

/// The `--report` page: the source and its upgrade compared as the proof compares them, with
/// heat maps, read back from the files just written.
fn write_report(args: &UpgradeArgs, page: &Path) -> Result<(), Failure> {
    let mut options = gltfmat::CompareOptions::default();
    options.heat_maps = true;
    options.draft_reading = args.draft_reading.reading();
    let compared = gltfmat::compare(&args.input, &args.output, &options)?;
    crate::compare::write_report(
        page,
        (&args.input, &args.output),
        &compared.outcomes,
        args.threshold,
        &compared.inputs,
        args.force,
    )?;
    outln!("wrote {}", page.display());
    Ok(())
}
