//! `gltfmat completions SHELL` and `gltfmat man`: generated from the command-line definition,
//! so they never disagree with `--help`.

use crate::common::{Failure, Outcome};
use std::path::Path;
use std::process::ExitCode;

pub fn completions(mut command: clap::Command, shell: clap_complete::Shell) -> Outcome {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut command, "gltfmat", &mut script);
    out!("{}", &String::from_utf8_lossy(&script));
    Ok(ExitCode::SUCCESS)
}

/// The manual: `gltfmat.1` on stdout, or with `dir` one page per subcommand beside it
/// (`gltfmat-check.1`, …), which the main page's SEE ALSO names.
pub fn man(command: clap::Command, dir: Option<&Path>, force: bool) -> Outcome {
    let Some(dir) = dir else {
        out!("{}", &String::from_utf8_lossy(&page_of(command)?));
        return Ok(ExitCode::SUCCESS);
    };
    let mut pages = vec![(dir.join("gltfmat.1"), page_of(command.clone())?)];
    for sub in command.get_subcommands().filter(|s| s.get_name() != "help") {
        let name = format!("gltfmat-{}", sub.get_name());
        let page = page_of(sub.clone().name(name.clone()).bin_name(name.clone()))?;
        pages.push((dir.join(format!("{name}.1")), page));
    }
    let files: Vec<(&Path, &[u8])> = (pages.iter())
        .map(|(p, b)| (p.as_path(), b.as_slice()))
        .collect();
    gltfmat::write_files(&files, &[], force).map_err(|e| Failure::usage(e.to_string()))?;
    outln!("wrote {} pages into {}", pages.len(), dir.display());
    Ok(ExitCode::SUCCESS)
}

fn page_of(command: clap::Command) -> Result<Vec<u8>, Failure> {
    let mut page = Vec::new();
    clap_mangen::Man::new(command)
        .render(&mut page)
        .map_err(|e| Failure::usage(e.to_string()))?;
    Ok(page)
}
