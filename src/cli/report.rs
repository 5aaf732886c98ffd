//! `gltfmat report ASSETS… -o report.html`: one self-contained HTML page of the findings,
//! the materials rendered and the textures shown.

use crate::common::{Failure, Outcome};
use gltfmat::FileId;
use gltfmat::{check_path, CheckOptions, Profile};
use gltfmat::{Page, Part, Renders};
use rayon::prelude::*;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args)]
pub struct ReportArgs {
    /// Files or folders; folders are walked for .gltf and .glb as `check` walks them.
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// The HTML file to write (never over an existing file without --force).
    #[arg(short, long)]
    output: PathBuf,
    /// Whose materials are rendered: `findings` (assets with a finding about a material,
    /// texture or image), `all`, or `none` (parameters and thumbnails only).
    #[arg(long, value_enum, default_value = "findings")]
    render: RenderArg,
    /// `default`: the Khronos findings and gltfmat's material rules; `khronos`: exactly what
    /// the released Khronos glTF-Validator reports. (gltfmat.toml is not read: the page shows
    /// what a plain `gltfmat check` reports.)
    #[arg(long, value_enum, default_value = "default")]
    profile: ProfileArg,
    /// Decode textures for the pixel rules.
    #[arg(long)]
    deep: bool,
    /// Leave out walked files and folders matching this glob (as `check --exclude`).
    #[arg(long, value_name = "GLOB")]
    exclude: Vec<String>,
    /// Replace an existing output file.
    #[arg(long)]
    force: bool,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum RenderArg {
    Findings,
    All,
    None,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum ProfileArg {
    Default,
    Khronos,
}

pub fn run(args: ReportArgs) -> Outcome {
    gltfmat::may_write(&args.output, &[], args.force).map_err(|e| Failure::usage(e.to_string()))?;
    let walked = crate::walk::assets(&args.inputs, &args.exclude)?;
    let files: Vec<PathBuf> = (walked.files.into_iter())
        .filter(|f| f.as_os_str() != "-")
        .collect();
    let options = CheckOptions::default()
        .with_profile(match args.profile {
            ProfileArg::Default => Profile::Default,
            ProfileArg::Khronos => Profile::Khronos,
        })
        .with_deep(args.deep);
    let renders = match args.render {
        RenderArg::Findings => Renders::WithMaterialFindings,
        RenderArg::All => Renders::All,
        RenderArg::None => Renders::None,
    };
    let mut page = Page::new("gltfmat report");
    let mut unreadable = walked.unreadable;
    // Every file the assets were read from (their buffers and images too): the page never
    // replaces one, --force or not.
    let mut read: Vec<FileId> = files.iter().filter_map(|f| FileId::of_path(f)).collect();
    // A window of files at a time: each asset's document is dropped once its part is made.
    for window in files.chunks(4 * rayon::current_num_threads()) {
        let parts: Vec<Result<(Part, Vec<FileId>), String>> = (window.par_iter())
            .map(|file| {
                let report = check_path(file, &options).map_err(|e| e.to_string())?;
                Ok((Part::of_check(&report, Some(file), renders), report.inputs))
            })
            .collect();
        for (part, file) in parts.into_iter().zip(window) {
            match part {
                Ok((part, inputs)) => {
                    page.add(part);
                    read.extend(inputs);
                }
                Err(why) => {
                    errln!("gltfmat: {}", gltfmat::report::printable(&why));
                    page.add_failure(&file.display().to_string(), &why);
                    unreadable = true;
                }
            }
        }
    }
    gltfmat::write_file(&args.output, page.html().as_bytes(), &read, args.force)
        .map_err(|e| Failure::usage(e.to_string()))?;
    outln!("wrote {} ({} file(s))", args.output.display(), files.len());
    Ok(if unreadable {
        ExitCode::from(2)
    } else {
        ExitCode::SUCCESS
    })
}
