//! One self-contained HTML page of a run, for the people who act on its findings: a summary
//! of every file, then per asset its findings grouped by the object they concern, each
//! material's ball beside its parameters and texture slots (a thumbnail of each image, the
//! channels the slot reads and their colour space, and what is said of it), and for an
//! upgrade or a comparison both materials side by side with their ΔE and a heat map.
//!
//! Everything is inline (CSS, images as data URIs): the page opens offline and fetches
//! nothing. It works without JavaScript. Each asset is made into its part of the page as it
//! is added, so a run over 10^4 files holds their text, never their documents.

mod html;
mod materials;

use crate::check::registry;
use crate::check::Report;
use crate::diagnostic::{Place, Severity};
use crate::shade::pairing::{Ball, Outcome};
use html::{escape, png_data_uri};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// Which assets get their materials rendered (a render costs time; a thumbnail does not).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Renders {
    /// Only assets with a finding about a material or a texture.
    #[default]
    WithMaterialFindings,
    /// Every asset.
    All,
    /// None: parameters and thumbnails only.
    None,
}

/// How much of each finding list is shown: a page over an asset with 10^5 findings stays
/// readable and small; the counts are always whole.
const FINDINGS_SHOWN: usize = 200;
/// Pixels a side of a material ball on the page.
const BALL: u32 = 96;
/// Texels a side of a texture thumbnail.
const THUMBNAIL: u32 = 64;

/// A page being made.
#[derive(Default)]
pub struct Page {
    title: String,
    rows: Vec<SummaryRow>,
    sections: Vec<String>,
    codes: std::collections::BTreeSet<String>,
}

/// What the page shows of one checked asset, made apart from the page so that many are made
/// in parallel; it holds text, not the asset's document.
pub struct Part {
    uri: String,
    counts: [usize; 4],
    codes: Vec<String>,
    html: String,
}

impl Part {
    /// The part of a checked asset: its findings, and its materials read from `path` (its
    /// files read from its folder), rendered as `renders` says.
    pub fn of_check(report: &Report, path: Option<&Path>, renders: Renders) -> Part {
        let counts = Severity::ALL.map(|s| report.count(s));
        let mut html = format!(
            "<h2>{}</h2><p class=\"counts\">{}</p>",
            escape(&report.uri),
            counts_text(counts)
        );
        let groups = group_findings(report);
        html += &findings_html(report, &groups);
        let draw = match renders {
            Renders::All => true,
            Renders::WithMaterialFindings => groups.keys().any(|k| is_material_group(k)),
            Renders::None => false,
        };
        html += &materials::cards(report, path, &groups, draw, BALL, THUMBNAIL);
        let mut codes: Vec<String> = (report.diagnostics.iter())
            .map(|d| d.code.name().to_string())
            .collect();
        codes.sort();
        codes.dedup();
        Part {
            uri: report.uri.clone(),
            counts,
            codes,
            html,
        }
    }
}

/// One file's line in the summary table.
struct SummaryRow {
    uri: String,
    counts: [usize; 4],
    anchor: String,
    failure: Option<String>,
}

impl Page {
    /// An empty page titled `title`.
    pub fn new(title: &str) -> Page {
        Page {
            title: title.to_string(),
            ..Page::default()
        }
    }

    /// Adds an asset's part, made by [`Part::of_check`] (on any thread).
    pub fn add(&mut self, part: Part) {
        let anchor = format!("asset-{}", self.rows.len());
        self.rows.push(SummaryRow {
            uri: part.uri,
            counts: part.counts,
            anchor: anchor.clone(),
            failure: None,
        });
        self.codes.extend(part.codes);
        self.sections
            .push(format!("<section id=\"{anchor}\">{}</section>", part.html));
    }

    /// Adds a file that could not be checked, with why.
    pub fn add_failure(&mut self, uri: &str, why: &str) {
        self.rows.push(SummaryRow {
            uri: uri.to_string(),
            counts: [0; 4],
            anchor: String::new(),
            failure: Some(why.to_string()),
        });
    }

    /// Adds a comparison (an upgrade's proof, or `compare A B`): for each pair, both
    /// materials' balls, the figures (`lines`, one per outcome, as the CLI words them) and
    /// a heat map of where they differ (black 0 → red at `threshold`).
    pub fn add_comparison(
        &mut self,
        (a, b): (&Path, &Path),
        outcomes: &[Outcome],
        lines: &[String],
        threshold: f64,
    ) {
        let balls = |path: &Path| {
            crate::shade::pairing::render_each(path, BALL, usize::MAX).unwrap_or_default()
        };
        let (balls_a, balls_b) = (balls(a), balls(b));
        let mut section = format!(
            "<section class=\"comparison\"><h2>{} ↔ {}</h2>",
            escape(&a.display().to_string()),
            escape(&b.display().to_string())
        );
        for (outcome, line) in outcomes.iter().zip(lines) {
            let within = outcome.result.max <= threshold;
            let verdict = match (outcome.is_evaluated(), outcome.same(threshold), within) {
                (false, _, _) => "not evaluated",
                (true, true, _) => "same",
                // Evaluated in part, and that part within the threshold.
                (true, false, true) => "not evaluated",
                (true, false, false) => "different",
            };
            let _ = write!(
                section,
                "<div class=\"pair {}\"><h3>material {} ({}) ↔ {} ({}): {verdict}</h3><div class=\"row\">{}{}{}</div><p>{}</p></div>",
                verdict.replace(' ', "-"),
                outcome.a.0,
                escape(&outcome.a.1),
                outcome.b.0,
                escape(&outcome.b.1),
                ball_figure(balls_a.get(outcome.a.0), "source"),
                ball_figure(balls_b.get(outcome.b.0), "compared"),
                heat_map_figure(outcome, threshold),
                escape(line)
            );
        }
        section += "</section>";
        self.sections.push(section);
    }

    /// The page as HTML.
    pub fn html(&self) -> String {
        let mut rows: Vec<&SummaryRow> = self.rows.iter().collect();
        // The files that need attention first: errors, then warnings, then name.
        rows.sort_by(|x, y| {
            (y.failure.is_some(), y.counts[0], y.counts[1])
                .cmp(&(x.failure.is_some(), x.counts[0], x.counts[1]))
                .then_with(|| x.uri.cmp(&y.uri))
        });
        let totals = (self.rows.iter()).fold([0; 4], |mut t, r| {
            (0..4).for_each(|i| t[i] += r.counts[i]);
            t
        });
        let mut body = format!("<h1>{}</h1>", escape(&self.title));
        if !self.rows.is_empty() {
            let _ = write!(
                body,
                "<p>{} file(s): {}</p>",
                self.rows.len(),
                counts_text(totals)
            );
            body += "<table class=\"summary\"><caption>Files, most errors first</caption><thead><tr><th scope=\"col\">file</th><th scope=\"col\">errors</th><th scope=\"col\">warnings</th><th scope=\"col\">infos</th><th scope=\"col\">hints</th></tr></thead><tbody>";
            for row in rows {
                let name = match (&row.failure, row.anchor.is_empty()) {
                    (Some(why), _) => format!(
                        "{} <span class=\"failure\">not checked: {}</span>",
                        escape(&row.uri),
                        escape(why)
                    ),
                    (None, true) => escape(&row.uri),
                    (None, false) => {
                        format!("<a href=\"#{}\">{}</a>", row.anchor, escape(&row.uri))
                    }
                };
                let [e, w, i, h] = row.counts;
                let class = if e > 0 || row.failure.is_some() {
                    " class=\"bad\""
                } else {
                    ""
                };
                let _ = write!(body, "<tr{class}><td>{name}</td><td>{e}</td><td>{w}</td><td>{i}</td><td>{h}</td></tr>");
            }
            body += "</tbody></table>";
        }
        for section in &self.sections {
            body += section;
        }
        if !self.codes.is_empty() {
            body += &glossary(self.codes.iter());
        }
        html::document(&self.title, &body)
    }
}

/// Findings by the object they concern: `materials/0`, `textures/2`, `meshes/1`, … (the
/// first two tokens of the pointer), `asset` for the root, `binary data` for byte offsets.
fn group_findings(report: &Report) -> BTreeMap<String, Vec<usize>> {
    let mut groups: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (i, d) in report.diagnostics.iter().enumerate() {
        groups.entry(group_of(d.location)).or_default().push(i);
    }
    groups
}

fn group_of(location: Place) -> String {
    match location {
        Place::Offset(_) => "binary data".into(),
        Place::Pointer(pointer) => {
            let mut tokens = pointer.split('/').skip(1);
            match (tokens.next(), tokens.next()) {
                (Some(c), Some(i)) if !c.is_empty() && i.parse::<usize>().is_ok() => {
                    format!("{c}/{i}")
                }
                (Some(c), _) if !c.is_empty() => c.to_string(),
                _ => "asset".into(),
            }
        }
    }
}

fn is_material_group(group: &str) -> bool {
    ["materials/", "textures/", "images/", "samplers/"]
        .iter()
        .any(|p| group.starts_with(p))
}

fn counts_text([e, w, i, h]: [usize; 4]) -> String {
    format!("{e} error(s), {w} warning(s), {i} info(s), {h} hint(s)")
}

/// The findings of one asset, grouped, each with its place and a link to its code's
/// explanation.
fn findings_html(report: &Report, groups: &BTreeMap<String, Vec<usize>>) -> String {
    if report.diagnostics.is_empty() {
        return "<p>No findings.</p>".into();
    }
    let places = crate::report::line_columns(report);
    let mut out = String::from("<h3>Findings</h3>");
    for (group, indices) in groups {
        let _ = write!(
            out,
            "<h4 id=\"{}\">{}</h4><ul class=\"findings\">",
            html::anchor_of(&report.uri, group),
            escape(group)
        );
        for &i in indices.iter().take(FINDINGS_SHOWN) {
            out += &finding_item(report, i, places[i]);
        }
        if indices.len() > FINDINGS_SHOWN {
            let _ = write!(
                out,
                "<li>… and {} more (`gltfmat check` lists them all)</li>",
                indices.len() - FINDINGS_SHOWN
            );
        }
        out += "</ul>";
    }
    if report.truncated {
        out += "<p>The list was cut at the run's --max-issues; the counts are whole.</p>";
    }
    out
}

fn finding_item(report: &Report, index: usize, place: Option<(usize, usize)>) -> String {
    let Some(d) = report.diagnostics.get(index) else {
        return String::new();
    };
    let severity = match d.severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Info => "info",
        Severity::Hint => "hint",
    };
    let location = match (d.location, place) {
        (Place::Offset(o), _) => format!("byte {o}"),
        (Place::Pointer(p), Some((line, column))) => {
            format!("{}:{line}:{column} {p}", report.uri)
        }
        (Place::Pointer(p), None) => p.to_string(),
    };
    format!(
        "<li class=\"{severity}\"><span class=\"sev\">{severity}</span> <a class=\"code\" href=\"#code-{code}\">{code}</a> {} <span class=\"where\">{}</span></li>",
        escape(d.message),
        escape(&location),
        code = d.code.name()
    )
}

/// Each code met on the page, explained once.
fn glossary<'a>(codes: impl Iterator<Item = &'a String>) -> String {
    let mut out = String::from("<section class=\"glossary\"><h2>What the codes mean</h2><dl>");
    for code in codes {
        let Some(info) = registry::find(code) else {
            continue;
        };
        let _ = write!(
            out,
            "<dt id=\"code-{code}\">{code}</dt><dd><p>{}</p><details><summary>more</summary><pre>{}</pre></details></dd>",
            escape(&info.description()),
            escape(&info.help_markdown())
        );
    }
    out + "</dl></section>"
}

fn ball_figure(ball: Option<&Ball>, role: &str) -> String {
    match ball {
        Some(Ball {
            material: (i, name),
            image: Some(image),
            not_drawn,
            ..
        }) => {
            let missing = match not_drawn.is_empty() {
                true => String::new(),
                false => format!("; not drawn: {}", not_drawn.join("; ")),
            };
            format!(
                "<figure><img src=\"{}\" width=\"{BALL}\" height=\"{BALL}\" alt=\"{role} material {i} ({}) rendered as a ball{}\"><figcaption>{role}: {}{}</figcaption></figure>",
                png_data_uri(image),
                escape(name),
                escape(&missing),
                escape(name),
                escape(&missing)
            )
        }
        Some(Ball { not_drawn, .. }) => format!(
            "<figure><figcaption>{role}: not drawn ({})</figcaption></figure>",
            escape(&not_drawn.join("; "))
        ),
        None => format!("<figure><figcaption>{role}: not drawn</figcaption></figure>"),
    }
}

fn heat_map_figure(outcome: &Outcome, threshold: f64) -> String {
    if outcome.result.per_texel.is_empty() {
        return String::new();
    }
    let map =
        crate::shade::render::heatmap(&outcome.result.per_texel, outcome.result.grid, threshold);
    format!(
        "<figure><img src=\"{}\" width=\"{BALL}\" height=\"{BALL}\" class=\"pixelated\" alt=\"where the pair differs over the texture square: black is the same, through blue and yellow to red at ΔE2000 {threshold} or more; the largest difference is {:.2}\"><figcaption>ΔE2000 over UV: black 0, blue, yellow, red ≥ {threshold}</figcaption></figure>",
        png_data_uri(&map),
        outcome.result.max
    )
}
