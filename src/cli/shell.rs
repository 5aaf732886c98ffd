//! `gltfmat completions SHELL` and `gltfmat man`: generated from the command-line definition,
//! so they never disagree with `--help`.

use crate::common::{Failure, Outcome};
use std::process::ExitCode;

pub fn completions(mut command: clap::Command, shell: clap_complete::Shell) -> Outcome {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut command, "gltfmat", &mut script);
    out!("{}", &String::from_utf8_lossy(&script));
    Ok(ExitCode::SUCCESS)
}

pub fn man(command: clap::Command) -> Outcome {
    let mut page = Vec::new();
    clap_mangen::Man::new(command)
        .render(&mut page)
        .map_err(|e| Failure::usage(e.to_string()))?;
    out!("{}", &String::from_utf8_lossy(&page));
    Ok(ExitCode::SUCCESS)
}
