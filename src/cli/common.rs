//! What every subcommand shares: how a failure becomes a message and an exit status.

use std::process::ExitCode;

/// Why a subcommand stopped: printed as `gltfmat: MESSAGE` on stderr.
pub struct Failure {
    message: String,
    status: u8,
}

impl Failure {
    /// A usage error or an unreadable input: exit status 2.
    pub fn usage(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            status: 2,
        }
    }

    /// The input was read but the job was refused (the asset fails, a proof fails): status 1.
    pub fn refused(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            status: 1,
        }
    }

    /// Prints the message and returns the exit status.
    pub fn report(self) -> ExitCode {
        errln!("gltfmat: {}", printable_lines(&self.message));
        ExitCode::from(self.status)
    }
}

impl From<gltfmat::Error> for Failure {
    fn from(error: gltfmat::Error) -> Failure {
        Failure::usage(error.to_string())
    }
}

/// What a subcommand returns.
pub type Outcome = Result<ExitCode, Failure>;

/// Text of gltfmat's own lines that may quote an asset or a path: each line as a terminal may
/// show it (see [`gltfmat::report::printable`]).
pub fn printable_lines(text: &str) -> String {
    let lines: Vec<_> = text.split('\n').map(gltfmat::report::printable).collect();
    lines.join("\n")
}

/// A ΔE threshold: a finite number ≥ 0 (NaN would make every comparison fail).
pub fn threshold(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .parse()
        .map_err(|_| format!("'{text}' is not a number"))?;
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(format!("'{text}' is not a finite number ≥ 0"))
    }
}

/// How a glTF 1.0 PBR draft's specular-glossiness text is read (`--draft-reading`).
#[derive(Clone, Copy, Default, clap::ValueEnum)]
pub enum DraftReadingArg {
    /// The drafts' Appendix (diffuse balanced by 1 − F per channel, scaled by 1 − max
    /// specular): the reading the ratified KHR_materials_pbrSpecularGlossiness kept.
    #[default]
    Appendix,
    /// The 2016 drafts' Appendix alone: the diffuse colour not scaled.
    #[value(name = "appendix-2016")]
    Appendix2016,
    /// The January 2017 example shader: diffuse · (1 − max specular), no 1 − F.
    ExampleShader,
}

impl DraftReadingArg {
    pub fn reading(self) -> gltfmat::SpecGlossReading {
        use gltfmat::SpecGlossReading;
        match self {
            DraftReadingArg::Appendix => SpecGlossReading::DraftAppendix,
            DraftReadingArg::Appendix2016 => SpecGlossReading::DraftAppendix2016,
            DraftReadingArg::ExampleShader => SpecGlossReading::DraftExampleShader,
        }
    }
}
