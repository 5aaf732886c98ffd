//! `gltfmat.toml`: the same keys as the command-line options. Each file is checked with the
//! nearest gltfmat.toml in its folder or a parent (input from stdin: from the current
//! folder), unless `--config` names one for all or `--isolated` reads none; command-line
//! options add to it.
//!
//! ```toml
//! profile = "default"      # or "khronos"
//! ignore = ["UNUSED_OBJECT"]
//! only = []
//! max-issues = 100
//! deep = false
//! all-findings = false     # human output lists infos and hints too
//! disabled-groups = ["materials"]
//! enabled-groups = ["plausibility"]   # opt-in groups, off by default
//! [severity]
//! IMAGE_NPOT_DIMENSIONS = "warning"
//! ```

use gltfmat::{CheckOptions, Profile, Severity};
use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields, rename_all = "kebab-case")]
pub struct Config {
    profile: Option<String>,
    #[serde(default)]
    ignore: Vec<String>,
    #[serde(default)]
    only: Vec<String>,
    #[serde(default)]
    severity: HashMap<String, String>,
    max_issues: Option<usize>,
    #[serde(default)]
    deep: bool,
    #[serde(default)]
    disabled_groups: Vec<String>,
    #[serde(default)]
    enabled_groups: Vec<String>,
    #[serde(default)]
    all_findings: bool,
}

pub const FILE_NAME: &str = "gltfmat.toml";

/// The nearest gltfmat.toml in `dir` or one of its parents.
pub fn find_upward(dir: &Path) -> Option<PathBuf> {
    let mut dir = std::path::absolute(dir).ok()?;
    loop {
        let candidate = dir.join(FILE_NAME);
        if candidate.is_file() {
            return Some(candidate);
        }
        if !dir.pop() {
            return None;
        }
    }
}

/// The largest gltfmat.toml read: a config is a few lines, and one found by the upward search
/// may be a stranger's (a link to a large file).
const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Reads a config: a regular file of at most [`MAX_CONFIG_BYTES`]. A parse error names its
/// line, column and reason, never the file's text: the file may be a link a stranger planted
/// beside an asset, leading to a credentials file whose lines must not reach a CI log.
pub fn load(path: &Path) -> Result<Config, String> {
    let failed = |why: String| format!("{}: {why}", path.display());
    let size = std::fs::metadata(path)
        .map_err(|e| failed(e.to_string()))?
        .len();
    if size > MAX_CONFIG_BYTES {
        return Err(failed(format!(
            "{size} bytes; a gltfmat.toml is at most {MAX_CONFIG_BYTES}"
        )));
    }
    let bytes = gltfmat::read_file(path).map_err(|e| failed(e.to_string()))?;
    let text = std::str::from_utf8(&bytes).map_err(|_| failed("not UTF-8 text".into()))?;
    toml::from_str(text).map_err(|e| {
        let at = e.span().map_or(0, |span| span.start).min(text.len());
        let before = &text.as_bytes()[..at];
        let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
        let column = 1 + before.iter().rev().take_while(|&&b| b != b'\n').count();
        failed(format!(
            "line {line}, column {column}: {}",
            e.message().trim_end()
        ))
    })
}

pub fn parse_severity(pair: &str) -> Result<(String, Severity), String> {
    let (code, level) = pair
        .split_once('=')
        .ok_or_else(|| format!("expected CODE=LEVEL, got '{pair}'"))?;
    let level = Severity::parse(level)
        .ok_or_else(|| format!("unknown severity '{level}' (error, warning, info, hint)"))?;
    Ok((code.to_string(), level))
}

impl Config {
    /// Whether human output lists infos and hints.
    pub fn all_findings(&self) -> bool {
        self.all_findings
    }

    pub fn into_options(self) -> Result<CheckOptions, String> {
        let profile = match self.profile.as_deref() {
            None | Some("default") => Profile::Default,
            Some("khronos") => Profile::Khronos,
            Some(other) => return Err(format!("unknown profile '{other}' in {FILE_NAME}")),
        };
        let mut severity_overrides = HashMap::new();
        for (code, level) in self.severity {
            let (code, level) = parse_severity(&format!("{code}={level}"))?;
            severity_overrides.insert(code, level);
        }
        let mut options = CheckOptions::default()
            .with_profile(profile)
            .with_deep(self.deep)
            .with_max_issues(self.max_issues.unwrap_or(0))
            .with_disabled_groups(self.disabled_groups)
            .with_enabled_groups(self.enabled_groups);
        options.ignore = self.ignore;
        options.only = self.only;
        options.severity_overrides = severity_overrides;
        Ok(options)
    }
}
