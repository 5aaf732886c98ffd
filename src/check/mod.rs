//! The validator: schema pass, link passes in the Khronos order, then gltfmat's own rules.

mod code_info;
pub mod registry;

pub(crate) mod rules;
pub(crate) mod schema;

pub(crate) mod animated;
mod collector;
pub(crate) mod context;
mod khronos;
pub(crate) use khronos::is_trs_decomposable;
mod pass_codes;
pub(crate) mod profile;

pub(crate) use crate::diagnostic::{Diagnostic, Finding, Findings, Place, Severity};
pub(crate) use context::Context;
pub use context::{AssetInfo, ResourceInfo};

use crate::diagnostic::Sink;
use crate::document::file::FileId;
use crate::document::uri::{FolderResources, ResourceLoader};
use crate::document::{self, Container, Document, Node, Tree};
use collector::Collector;
use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

/// Which issues to report.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Profile {
    /// Khronos codes plus gltfmat's rules; rules may supersede a Khronos code they correct.
    #[default]
    Default,
    /// Exactly the issues the Khronos glTF-Validator reports (the drop-in mode).
    Khronos,
}

/// What to report and how much.
#[derive(Debug, Clone, Default)]
#[non_exhaustive]
pub struct CheckOptions {
    /// Khronos parity only, or also gltfmat's rules.
    pub profile: Profile,
    /// Codes never reported.
    pub ignore: Vec<String>,
    /// When not empty, the only codes reported.
    pub only: Vec<String>,
    /// Severity per code (case-insensitive names), replacing the default.
    pub severity_overrides: HashMap<String, Severity>,
    /// Stop collecting after this many issues (0 = unlimited); sets `truncated`.
    pub max_issues: usize,
    /// Findings less severe than this are counted but not kept (`None`: all kept). A report
    /// that will not list infos and hints then holds none: 10^5 of them cost no memory.
    pub lowest_kept: Option<Severity>,
    /// Decode textures for the pixel rules.
    pub deep: bool,
    /// Skip rule groups by name (e.g. "materials").
    pub disabled_groups: Vec<String>,
    /// Run these opt-in rule groups too (e.g. "plausibility"; see
    /// [`rules::OPT_IN_GROUPS`]), unless they are also disabled.
    pub enabled_groups: Vec<String>,
}

impl CheckOptions {
    /// These options with `profile`.
    pub fn with_profile(mut self, profile: Profile) -> Self {
        self.profile = profile;
        self
    }

    /// These options with texture decoding for the pixel rules on or off.
    pub fn with_deep(mut self, deep: bool) -> Self {
        self.deep = deep;
        self
    }

    /// These options with the rule groups `groups` skipped.
    pub fn with_disabled_groups(mut self, groups: Vec<String>) -> Self {
        self.disabled_groups = groups;
        self
    }

    /// These options with the opt-in rule groups `groups` run.
    pub fn with_enabled_groups(mut self, groups: Vec<String>) -> Self {
        self.enabled_groups = groups;
        self
    }

    /// These options keeping at most `max_issues` findings (0 = all).
    pub fn with_max_issues(mut self, max_issues: usize) -> Self {
        self.max_issues = max_issues;
        self
    }

    /// These options keeping no finding less severe than `lowest` (all are still counted).
    pub fn with_lowest_kept(mut self, lowest: Severity) -> Self {
        self.lowest_kept = Some(lowest);
        self
    }
}

/// The result of checking one asset.
#[derive(Debug)]
pub struct Report {
    /// The name the asset was checked under (its path, or `-`).
    pub uri: String,
    /// The document as read (bytes, container, JSON), for locating findings.
    pub(crate) document: Document,
    /// The findings, in pass order (or, cut by `max_issues`, in report order).
    pub diagnostics: Findings,
    /// True when `max_issues` cut the list.
    pub truncated: bool,
    /// Findings per severity (error, warning, info, hint), counted before `max_issues` cut
    /// the list: a truncated report still says how many errors the asset has.
    counts: [usize; 4],
    /// The report's `info` section (version, extensions, resources, counts).
    pub info: AssetInfo,
    /// Every file the asset was read from, by identity (the asset's own and the files its
    /// URIs name; none for [`check_bytes`]): what an output must not replace.
    pub inputs: Vec<FileId>,
}

impl Report {
    /// How many findings have `severity`.
    /// Counted before `max_issues` cut the list.
    pub fn count(&self, severity: Severity) -> usize {
        self.counts[severity as usize]
    }

    /// Whether any finding is an error.
    pub fn has_errors(&self) -> bool {
        self.count(Severity::Error) > 0
    }

    /// The media type of the container (`model/gltf+json` or `model/gltf-binary`).
    pub fn mime_type(&self) -> &'static str {
        self.document.container.mime_type()
    }
}

/// Checks the asset at `path`, reading its external files from its folder (never outside it).
/// An unreadable file is an [`Error`](crate::error::Error); problems in the asset are diagnostics.
pub fn check_path(
    path: impl AsRef<Path>,
    options: &CheckOptions,
) -> Result<Report, crate::error::Error> {
    let path = path.as_ref();
    let mut diagnostics = Collector::new(options);
    // A large GLB's BIN chunk stays in the file: its views are read as they are walked.
    let document =
        document::read_path(path, &mut diagnostics).map_err(|source| crate::error::Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
    let loader = FolderResources::beside(path);
    let uri = path.display().to_string();
    let mut report = check_document(&uri, document, &loader, options, diagnostics);
    report.inputs = FileId::of_path(path).into_iter().collect();
    report.inputs.extend(loader.files_read());
    Ok(report)
}

/// Checks an asset given as bytes. `uri` names it in reports; external files come from `loader`.
pub fn check_bytes(
    uri: &str,
    bytes: impl Into<document::Bytes>,
    loader: &dyn ResourceLoader,
    options: &CheckOptions,
) -> Report {
    check_shared_bytes(uri, Arc::new(bytes.into()), loader, options)
}

/// [`check_bytes`] of bytes shared with their owner: an upgrade's output, checked while it
/// is written.
pub(crate) fn check_shared_bytes(
    uri: &str,
    bytes: Arc<document::Bytes>,
    loader: &dyn ResourceLoader,
    options: &CheckOptions,
) -> Report {
    let mut diagnostics = Collector::new(options);
    let document = document::read_shared(bytes, uri, &mut diagnostics);
    check_document(uri, document, loader, options, diagnostics)
}

/// Checks a GLB given as its head (everything before its BIN chunk's data) and that data in
/// pieces: an upgrade's output, checked without joining it into one copy first.
pub(crate) fn check_glb_pieces(
    uri: &str,
    head: Arc<document::Bytes>,
    data: document::Pieces,
    loader: &dyn ResourceLoader,
    options: &CheckOptions,
) -> Report {
    let mut diagnostics = Collector::new(options);
    let document = document::read_glb_pieces(head, data, &mut diagnostics);
    check_document(uri, document, loader, options, diagnostics)
}

/// Checks a document read by [`check_bytes`] or [`check_path`], whose reading's findings
/// are already in `diagnostics`.
fn check_document(
    uri: &str,
    mut document: Document,
    loader: &dyn ResourceLoader,
    options: &CheckOptions,
    diagnostics: Collector,
) -> Report {
    // Rebound so that its lifetime may shrink to the document's, which the passes borrow.
    let mut diagnostics = diagnostics;
    let filters = profile::Filters::of(options.profile);
    let mut info = context::AssetInfo::default();
    let khronos_extensions_only = !options.profile.knows_extensions_beyond_khronos();
    // 2.0 passes on a 1.0 document only bury the one fix: upgrading it.
    let gltf1 = document.major_version() == Some(1) && options.profile.checks_gltf1();
    match &mut document.root {
        Some(tree) if !tree.root().is_object() => {
            diagnostics.push(Diagnostic::at(
                crate::diagnostic::khronos::TYPE_MISMATCH,
                "",
                format!(
                    "Type mismatch. Property value {} is not a 'object'.",
                    short(tree.root())
                ),
            ));
        }
        Some(tree) => {
            let as_written = match options.profile.counts_extensions_as_written() && !gltf1 {
                true => khronos::extensions_as_written(tree.root()),
                false => Default::default(),
            };
            let left_to_extensions = match options.profile.reads_images_with_extensions() {
                false => {
                    khronos::images_with_extensions(tree.root(), &declared_extensions(tree.root()))
                }
                true => Default::default(),
            };
            let stopped_at = (options.profile.stops_where_the_validator_stops() && !gltf1)
                .then(|| khronos::stops_at_data_uri(tree.root()))
                .flatten();
            let undeclared = if gltf1 {
                Default::default()
            } else {
                schema_pass(tree, khronos_extensions_only, stopped_at, &mut diagnostics)
            };
            let root = document.root.as_ref().expect("matched above").root();
            let mut ctx = Context::new(root, &document, loader, options, diagnostics, &filters);
            ctx.undeclared_extensions = undeclared;
            ctx.extensions_as_written = as_written;
            ctx.images_left_to_extensions = left_to_extensions;
            ctx.stopped_at = stopped_at;
            if options.profile.names_link_findings_as_the_validator() && !gltf1 {
                ctx.link_path = khronos::LinkPath::of(root);
            }
            if gltf1 {
                rules::gltf1::check(&mut ctx);
            } else {
                run_passes(&mut ctx);
            }
            info = ctx.info();
            diagnostics = ctx.diagnostics;
        }
        None => {}
    }
    let (diagnostics, counts, truncated) = diagnostics.finish();
    Report {
        uri: uri.to_string(),
        document,
        diagnostics,
        truncated,
        counts,
        info,
        inputs: Vec::new(),
    }
}

fn short(value: Node) -> String {
    let text = value.to_string();
    text.chars().take(40).collect()
}

/// The schema pass, before the others, and what the Khronos validator does not read taken
/// out of the tree: members of the wrong type, arrays a wrongly typed element or a wrong
/// length made unreadable (a `translation` holding a null is no translation; an accessor's
/// `min` of the wrong length for its type, or any bounds of an accessor without a valid
/// type, taken out before the schema pass) and the
/// extension objects `extensionsUsed` does not declare (returned, for the extensions pass
/// to report). Of a document that does not claim
/// glTF 2.x, or one whose data URI `stopped_at` stops the Khronos profile, only what the
/// Khronos validator reads before it stops (see [`khronos::read_before_asset`] and
/// [`khronos::read_before_data_uri`]).
fn schema_pass(
    tree: &mut Tree,
    khronos: bool,
    stopped_at: Option<(&'static str, usize)>,
    sink: &mut dyn Sink,
) -> khronos::Undeclared {
    if !khronos::has_supported_version(tree.root()) {
        let read = khronos::read_before_asset(tree.root());
        let absent = schema::validate(tree.root(), khronos, &mut Only(sink, read));
        let (nulls, emptied) = remove_all(tree, absent);
        // Read anew: an `asset` that was null is now missing.
        let read = khronos::read_before_asset(tree.root());
        schema::required_members(
            tree.root(),
            khronos,
            &nulls,
            &emptied,
            &mut Only(sink, read),
        );
        return Default::default();
    }
    if let Some(at) = stopped_at {
        let read = |d: &Diagnostic| {
            (d.pointer()).is_some_and(|p| khronos::read_before_data_uri(at, d.code, p))
        };
        let mut read = Only(sink, read);
        return schema_pass_of_2x(tree, khronos, &mut read);
    }
    schema_pass_of_2x(tree, khronos, sink)
}

/// [`schema_pass`] of a document that claims glTF 2.x.
fn schema_pass_of_2x(tree: &mut Tree, khronos: bool, sink: &mut dyn Sink) -> khronos::Undeclared {
    khronos::take_unread_bounds(tree, sink);
    khronos::take_unread_offsets(tree, sink);
    khronos::take_unread_projections(tree, sink);
    let root = tree.root();
    let mut undeclared = khronos::undeclared_extensions(root, &declared_extensions(root));
    // Out before the schema pass, which then finds nothing in them. One that is no object
    // stays for the schema pass to say so, and goes after it.
    undeclared.remove_where(tree, |value| value.is_object());
    khronos::take_unread_spots(tree, sink);
    let absent = schema::validate(tree.root(), khronos, sink);
    // One inside a member the validator does not read is not seen either.
    undeclared.retain_hosts(|host| !schema::at_or_inside(&absent, host));
    let (nulls, emptied) = remove_all(tree, absent);
    undeclared.remove_where(tree, |_| true);
    schema::required_members(tree.root(), khronos, &nulls, &emptied, sink);
    khronos::take_unread_sparse(tree);
    undeclared
}

/// The names `extensionsUsed` declares; none when it is not a list of names (the schema
/// pass reports it, and the Khronos validator then reads no declaration).
fn declared_extensions(root: Node<'_>) -> hashbrown::HashSet<&str> {
    let names = root.get("extensionsUsed").and_then(Node::as_array);
    (names.into_iter().flatten())
        .map(Node::as_str)
        .collect::<Option<hashbrown::HashSet<&str>>>()
        .unwrap_or_default()
}

/// Takes the members at `pointers` out of the tree (those inside arrays stay: only members of
/// objects are ever unread), but for those the Khronos validator reads otherwise (below).
/// Returns those that were `null`, and the extension objects made empty.
fn remove_all(tree: &mut Tree, pointers: HashSet<String>) -> (HashSet<String>, HashSet<String>) {
    let mut nulls = HashSet::new();
    let mut emptied = HashSet::new();
    for pointer in pointers {
        // An extension object that is no object is read as an empty one: its required
        // members are then missing (reported by `schema::required_members`).
        let extension = pointer
            .rsplit_once('/')
            .is_some_and(|(parent, _)| parent.ends_with("/extensions"));
        if extension {
            if tree.empty(&pointer) {
                emptied.insert(pointer);
            }
            continue;
        }
        // A byteOffset, a primitive's mode, a material's emissiveFactor, texCoord or
        // alphaCutoff, an animation sampler's interpolation, a camera's projection or a spot
        // light's cone angle that is invalid (other than null) stays, unreadable: the Khronos
        // validator reads it as invalid, not as absent (the default 0, TRIANGLES, black, set
        // 0, LINEAR, a missing projection or the default angle): it reads no data through
        // such an offset (`gltf::byte_offset`), matches no count to such a mode, finds no
        // black in such a factor, needs no set for such a texCoord, counts no keys for such
        // an interpolation and compares no such angle; an alphaCutoff is there, whatever it
        // holds, for the mode it needs.
        let invalid_not_absent = pointer.ends_with("/byteOffset")
            || (pointer.starts_with("/meshes/") && pointer.ends_with("/mode"))
            || (pointer.starts_with("/materials/")
                && (pointer.ends_with("/emissiveFactor")
                    || pointer.ends_with("/texCoord")
                    || pointer.ends_with("/alphaCutoff")))
            || (pointer.starts_with("/animations/") && pointer.ends_with("/interpolation"))
            || (pointer.starts_with("/cameras/")
                && (pointer.ends_with("/perspective") || pointer.ends_with("/orthographic")))
            || (pointer.starts_with("/extensions/KHR_lights_punctual/lights/")
                && (pointer.ends_with("/spot/innerConeAngle")
                    || pointer.ends_with("/spot/outerConeAngle")));
        // An alphaCutoff is there even as null: the validator asks whether the key is.
        let there_even_null =
            pointer.starts_with("/materials/") && pointer.ends_with("/alphaCutoff");
        let kept = there_even_null
            || invalid_not_absent && (tree.root().pointer(&pointer)).is_some_and(|v| !v.is_null());
        if !kept && tree.remove(&pointer) == Some(true) {
            nulls.insert(pointer);
        }
    }
    (nulls, emptied)
}

fn run_passes(ctx: &mut Context) {
    if !khronos::has_supported_version(ctx.root) {
        // The Khronos validator reads the extension lists and `asset` and stops when that
        // is missing or not 2.x: what it would say of the rest assumes a format the file
        // does not claim.
        khronos::check_extension_lists(ctx);
        khronos::check_asset(ctx);
        return;
    }
    if let Some((collection, index)) = ctx.stopped_at {
        // What the validator says of the rest assumes data it could not decode.
        khronos::check_extension_lists(ctx);
        khronos::check_asset(ctx);
        let undeclared = crate::diagnostic::khronos::UNDECLARED_EXTENSION;
        let at = (collection, index);
        khronos::report_undeclared(ctx, |p| khronos::read_before_data_uri(at, undeclared, p));
        khronos::resources::check_parsed_before_stop(ctx, at);
        ctx.emit(
            crate::diagnostic::khronos::INVALID_JSON,
            "",
            format!("Invalid JSON data. Parser output: the base64 of /{collection}/{index}/uri ends in bits past its data, which the Khronos validator's decoder refuses; it reads the file no further."),
        );
        return;
    }
    for (_, pass) in khronos::PASSES {
        pass(ctx);
    }
    if ctx.options.profile.runs_rules() {
        rules::run_all(ctx);
    }
}

/// A sink passing on only the findings `keep` accepts.
struct Only<'s, F>(&'s mut dyn Sink, F);

impl<F: Fn(&Diagnostic) -> bool> Sink for Only<'_, F> {
    fn push(&mut self, diagnostic: Diagnostic) {
        if (self.1)(&diagnostic) {
            self.0.push(diagnostic);
        }
    }
}

/// Whether the container is binary (used by passes that treat GLB specially).
pub(crate) fn is_glb(doc: &Document) -> bool {
    doc.container == Container::Glb
}
