//! The native half of the `gltfmat` Python package: the library's façade, called with the
//! GIL released. Results cross as the JSON the CLI writes (parsed once on the Python side),
//! so that Python sees exactly the CLI's report shapes; the Python half (`gltfmat/`) wraps
//! them in classes.

use gltfmat::upgrade_output as output;
use gltfmat::Bytes;
use gltfmat::FileId;
use gltfmat::{CheckOptions, FolderResources, NoResources, Profile, Severity, UpgradeOptions};
use gltfmat::{Items, NoteKind, SpecularGlossiness};
use gltfmat::{LoadError, ResourceLoader};
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyByteArray, PyBytes};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

pyo3::create_exception!(
    gltfmat,
    GltfmatError,
    PyException,
    "An asset could not be read or used (the CLI's exit status 2)."
);
pyo3::create_exception!(
    gltfmat,
    UpgradeRefused,
    GltfmatError,
    "An upgrade was refused: the input cannot be converted, the proof failed under `verify`, or the output failed its own check. Nothing was written."
);

/// An asset as the caller gave it: a path (its files read from its folder) or its bytes.
enum Source {
    Path(PathBuf),
    Bytes(Vec<u8>),
}

impl Source {
    fn of(object: &Bound<'_, PyAny>) -> PyResult<Source> {
        if let Ok(bytes) = object.cast::<PyBytes>() {
            return Ok(Source::Bytes(bytes.as_bytes().to_vec()));
        }
        if let Ok(bytes) = object.cast::<PyByteArray>() {
            return Ok(Source::Bytes(bytes.to_vec()));
        }
        let path: PathBuf = object.extract().map_err(|_| {
            PyValueError::new_err("an asset is a path (str or os.PathLike) or its bytes")
        })?;
        Ok(Source::Path(path))
    }

    /// The bytes and the name reports give the asset.
    fn read(self, name: Option<String>) -> PyResult<(Vec<u8>, String, Option<PathBuf>)> {
        match self {
            Source::Bytes(bytes) => Ok((bytes, name.unwrap_or_else(|| "<bytes>".into()), None)),
            Source::Path(path) => {
                let bytes = gltfmat::read_file(&path)
                    .map_err(|e| GltfmatError::new_err(format!("{}: {e}", path.display())))?;
                let name = name.unwrap_or_else(|| path.display().to_string());
                Ok((bytes, name, Some(path)))
            }
        }
    }
}

/// External files read through a Python mapping (`{"scene.bin": b"…"}`) or callable
/// (`lambda uri: bytes or None`): assets in object storage need no temporaries. Each file
/// is asked for once and shared by every URI that names it.
struct PythonResources {
    source: Py<PyAny>,
    read: Mutex<HashMap<String, Arc<Bytes>>>,
}

impl PythonResources {
    fn ask(&self, relative: &str) -> Result<Vec<u8>, LoadError> {
        Python::attach(|py| {
            let source = self.source.bind(py);
            let answer = if source.is_callable() {
                source.call1((relative,))
            } else {
                source.get_item(relative)
            };
            let missing = || LoadError::NotFound(relative.to_string());
            let answer = match answer {
                Ok(answer) if answer.is_none() => return Err(missing()),
                Ok(answer) => answer,
                Err(e) if e.is_instance_of::<pyo3::exceptions::PyKeyError>(py) => {
                    return Err(missing())
                }
                Err(e) if e.is_instance_of::<pyo3::exceptions::PyFileNotFoundError>(py) => {
                    return Err(missing())
                }
                Err(e) => return Err(LoadError::Io(format!("{relative}: {e}"))),
            };
            let bytes = if let Ok(bytes) = answer.cast::<PyBytes>() {
                bytes.as_bytes().to_vec()
            } else if let Ok(bytes) = answer.cast::<PyByteArray>() {
                bytes.to_vec()
            } else {
                return Err(LoadError::Io(format!(
                    "{relative}: the resource loader gave {}, not bytes",
                    answer
                        .get_type()
                        .name()
                        .map_or("?".into(), |n| n.to_string())
                )));
            };
            match bytes.len() as u64 {
                n if n > gltfmat::MAX_FILE_BYTES => Err(LoadError::TooLarge(n)),
                _ => Ok(bytes),
            }
        })
    }
}

impl ResourceLoader for PythonResources {
    fn load(&self, relative: &str) -> Result<Arc<Bytes>, LoadError> {
        if let Some(known) = self.read.lock().map_err(|_| poisoned())?.get(relative) {
            return Ok(Arc::clone(known));
        }
        let bytes: Arc<Bytes> = Arc::new(self.ask(relative)?.into());
        (self.read.lock().map_err(|_| poisoned())?).insert(relative.into(), Arc::clone(&bytes));
        Ok(bytes)
    }
}

fn poisoned() -> LoadError {
    LoadError::Io("the resource cache was poisoned by a failed read".into())
}

/// Where an asset's external files come from: the caller's mapping or callable when given,
/// else the asset's own folder (confined to it), else nowhere (bytes).
enum Loader {
    Python(PythonResources),
    Folder(FolderResources),
    Nowhere(NoResources),
}

impl Loader {
    fn of(resources: Option<Py<PyAny>>, path: Option<&Path>) -> Loader {
        match (resources, path) {
            (Some(source), _) => Loader::Python(PythonResources {
                source,
                read: Mutex::default(),
            }),
            (None, Some(path)) => Loader::Folder(FolderResources::beside(path)),
            (None, None) => Loader::Nowhere(NoResources),
        }
    }

    fn get(&self) -> &dyn ResourceLoader {
        match self {
            Loader::Python(python) => python,
            Loader::Folder(folder) => folder,
            Loader::Nowhere(nothing) => nothing,
        }
    }

    /// The files read from the asset's folder so far: an output must not replace them.
    fn files_read(&self) -> Vec<FileId> {
        match self {
            Loader::Folder(folder) => folder.files_read(),
            _ => Vec::new(),
        }
    }
}

fn profile(name: &str) -> PyResult<Profile> {
    match name {
        "default" => Ok(Profile::Default),
        "khronos" => Ok(Profile::Khronos),
        other => Err(PyValueError::new_err(format!(
            "profile '{other}': expected 'default' or 'khronos'"
        ))),
    }
}

/// Where a finding is in the asset's JSON text (1-based), when it is in the text.
type LineColumn = Option<(usize, usize)>;

/// Checks an asset: the Khronos-shaped report as JSON, and each finding's line and column.
#[pyfunction]
#[pyo3(signature = (source, *, name=None, profile="default", deep=false, ignore=Vec::new(), only=Vec::new(), max_issues=0, resources=None))]
#[allow(clippy::too_many_arguments)]
fn check(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    name: Option<String>,
    profile: &str,
    deep: bool,
    ignore: Vec<String>,
    only: Vec<String>,
    max_issues: usize,
    resources: Option<Py<PyAny>>,
) -> PyResult<(String, Vec<LineColumn>)> {
    let mut options = CheckOptions::default()
        .with_profile(self::profile(profile)?)
        .with_deep(deep)
        .with_max_issues(max_issues);
    options.ignore = ignore;
    options.only = only;
    let source = Source::of(source)?;
    py.detach(move || {
        let report = match (source, resources) {
            // As the CLI checks a file: a large GLB's BIN chunk is read as it is walked.
            (Source::Path(path), None) if name.is_none() => gltfmat::check_path(&path, &options)
                .map_err(|e| GltfmatError::new_err(e.to_string()))?,
            (source, resources) => {
                let (bytes, name, path) = source.read(name)?;
                let loader = Loader::of(resources, path.as_deref());
                gltfmat::check_bytes(&name, bytes, loader.get(), &options)
            }
        };
        let json = serde_json::to_string(&gltfmat::report::khronos_report(&report))
            .map_err(|e| GltfmatError::new_err(e.to_string()))?;
        Ok((json, gltfmat::report::line_columns(&report)))
    })
}

/// What an upgrade gives Python: its notes, proof and check as JSON, and the GLB bytes when
/// no output file was asked for.
type UpgradeResult = (String, Option<Vec<u8>>);

/// Upgrades an asset as `gltfmat upgrade` does: converted, proved, checked, and written
/// atomically to `output` (or returned as GLB bytes).
#[pyfunction]
#[pyo3(signature = (source, output=None, *, name=None, force=false, verify=false, prove=true, threshold=gltfmat::DEFAULT_THRESHOLD, specular_glossiness="metal-rough", double_sided=false, draft_reading="appendix", strict=false, resources=None))]
#[allow(clippy::too_many_arguments)]
fn upgrade(
    py: Python<'_>,
    source: &Bound<'_, PyAny>,
    output: Option<PathBuf>,
    name: Option<String>,
    force: bool,
    verify: bool,
    prove: bool,
    threshold: f64,
    specular_glossiness: &str,
    double_sided: bool,
    draft_reading: &str,
    strict: bool,
    resources: Option<Py<PyAny>>,
) -> PyResult<(String, Option<Py<PyBytes>>)> {
    let options = UpgradeOptions::default()
        .with_specular_glossiness(match specular_glossiness {
            "metal-rough" => SpecularGlossiness::MetalRough,
            "extension" => SpecularGlossiness::Extension,
            other => {
                return Err(PyValueError::new_err(format!(
                    "specular_glossiness '{other}': expected 'metal-rough' or 'extension'"
                )))
            }
        })
        .with_double_sided_default(double_sided)
        .with_draft_reading(reading(draft_reading)?);
    if !(threshold.is_finite() && threshold >= 0.0) {
        return Err(PyValueError::new_err("threshold: a finite number ≥ 0"));
    }
    let source = Source::of(source)?;
    let plan = Plan {
        output,
        force,
        verify,
        prove,
        threshold,
        strict,
    };
    let (json, glb) = py.detach(move || -> PyResult<UpgradeResult> {
        let (bytes, name, path) = source.read(name)?;
        // As the CLI converts: a name differing from its file only in letter case reads it.
        let loader = match Loader::of(resources, path.as_deref()) {
            Loader::Folder(folder) => Loader::Folder(folder.repairing_letter_case()),
            other => other,
        };
        plan.run(bytes, &name, path.as_deref(), &loader, &options)
    })?;
    Ok((json, glb.map(|glb| PyBytes::new(py, &glb).unbind())))
}

fn reading(name: &str) -> PyResult<gltfmat::SpecGlossReading> {
    use gltfmat::SpecGlossReading;
    match name {
        "appendix" => Ok(SpecGlossReading::DraftAppendix),
        "appendix-2016" => Ok(SpecGlossReading::DraftAppendix2016),
        "example-shader" => Ok(SpecGlossReading::DraftExampleShader),
        other => Err(PyValueError::new_err(format!(
            "draft_reading '{other}': expected 'appendix', 'appendix-2016' or 'example-shader'"
        ))),
    }
}

/// An upgrade's choices beside the conversion's own options.
struct Plan {
    output: Option<PathBuf>,
    force: bool,
    verify: bool,
    prove: bool,
    threshold: f64,
    strict: bool,
}

impl Plan {
    fn run(
        &self,
        bytes: Vec<u8>,
        name: &str,
        path: Option<&Path>,
        loader: &Loader,
        options: &UpgradeOptions,
    ) -> PyResult<UpgradeResult> {
        let protected: Vec<FileId> = path.and_then(FileId::of_path).into_iter().collect();
        let target = self.output.as_deref().map(target_of).transpose()?;
        if let Some((folder, file)) = &target {
            gltfmat::may_write(&folder.join(file), &protected, self.force)
                .map_err(|e| GltfmatError::new_err(e.to_string()))?;
        }
        let tolerated = self.tolerated(&bytes, name, loader.get());
        let refused = |why: String| UpgradeRefused::new_err(why);
        let mut upgraded = gltfmat::upgrade(bytes.as_slice(), loader.get(), options)
            .map_err(|e| refused(format!("{name}: {e}")))?;
        let notes: Vec<serde_json::Value> = (upgraded.report.iter())
            .map(|note| {
                let kind = match note.kind {
                    NoteKind::Decision => "decision",
                    NoteKind::Dropped => "dropped",
                };
                serde_json::json!({"kind": kind, "pointer": note.pointer, "text": &*note.text})
            })
            .collect();
        let has_materials = upgraded
            .json
            .items("materials")
            .is_some_and(|m| !Items::is_empty(m));
        let proof = match self.prove && has_materials {
            true => gltfmat::prove(bytes, name, loader.get(), &upgraded)
                .map_err(|e| refused(format!("proof: {e}")))?,
            false => Vec::new(),
        };
        if self.verify && !gltfmat::proof_holds(&proof, self.threshold) {
            return Err(refused(format!(
                "the proof does not show that every converted material renders like its source within ΔE2000 {}; nothing was written",
                self.threshold
            )));
        }
        let (report, glb, written) = match &target {
            None => {
                let (glb, report) =
                    output::checked_glb(&mut upgraded, "asset.glb").map_err(|bytes| {
                        GltfmatError::new_err(
                            gltfmat::WriteError::GlbTooLarge("asset.glb".into(), bytes).to_string(),
                        )
                    })?;
                (report, Some(glb.bytes()), Vec::new())
            }
            Some((folder, file)) => {
                let files = output::layout_releasing_json(&mut upgraded, file);
                let protected: Vec<FileId> =
                    protected.into_iter().chain(loader.files_read()).collect();
                let checked =
                    output::write_checked(&files, folder, &protected, self.force, &tolerated)
                        .map_err(|e| GltfmatError::new_err(e.to_string()))?;
                let names = std::iter::once(&files.main).chain(&files.side);
                let written: Vec<String> = names
                    .map(|f| folder.join(&f.name).display().to_string())
                    .collect();
                (
                    checked.report,
                    None,
                    if checked.written { written } else { Vec::new() },
                )
            }
        };
        if !tolerated.accepts(&report) {
            let errors = report.count(Severity::Error);
            return Err(refused(format!(
                "the upgraded asset fails its own check ({errors} error(s)); nothing was written"
            )));
        }
        let json = serde_json::json!({
            "notes": notes,
            "proof": proof.iter().map(|o| o.to_json(self.threshold)).collect::<Vec<_>>(),
            "check": gltfmat::report::khronos_report(&report),
            "written": written,
        });
        Ok((json.to_string(), glb))
    }

    /// The errors the output may keep: a glTF 2.0 input's own, unless `strict`.
    fn tolerated(
        &self,
        bytes: &[u8],
        name: &str,
        loader: &dyn ResourceLoader,
    ) -> output::Tolerated {
        if self.strict {
            return output::Tolerated::none();
        }
        let report = gltfmat::check_bytes(name, bytes.to_vec(), loader, &CheckOptions::default());
        match report.info.version.as_deref() {
            Some(version) if version.starts_with("2.") => output::Tolerated::errors_of(&report),
            _ => output::Tolerated::none(),
        }
    }
}

/// The folder and file name of an output path (`*.gltf` or `*.glb` in an existing folder).
fn target_of(output: &Path) -> PyResult<(PathBuf, String)> {
    let name = (output.file_name().and_then(|n| n.to_str()))
        .filter(|n| {
            let n = n.to_ascii_lowercase();
            n.ends_with(".gltf") || n.ends_with(".glb")
        })
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{}: the output must be a file named *.gltf or *.glb",
                output.display()
            ))
        })?;
    let folder = gltfmat::folder_of(output);
    if !folder.is_dir() {
        return Err(GltfmatError::new_err(format!(
            "{}: the output folder {} does not exist (or is not a folder)",
            output.display(),
            folder.display()
        )));
    }
    Ok((folder, name.to_string()))
}

/// Compares the materials of two assets on disk: each pair's outcome as
/// `compare --format json` writes it.
#[pyfunction]
#[pyo3(signature = (a, b, *, threshold=gltfmat::DEFAULT_THRESHOLD, pairs=Vec::new(), draft_reading="appendix"))]
fn compare(
    py: Python<'_>,
    a: PathBuf,
    b: PathBuf,
    threshold: f64,
    pairs: Vec<(usize, usize)>,
    draft_reading: &str,
) -> PyResult<String> {
    let mut options = gltfmat::CompareOptions::default();
    options.pairs = pairs;
    options.draft_reading = reading(draft_reading)?;
    py.detach(move || {
        let compared =
            gltfmat::compare(&a, &b, &options).map_err(|e| GltfmatError::new_err(e.to_string()))?;
        let list: Vec<_> = (compared.outcomes.iter())
            .map(|o| o.to_json(threshold))
            .collect();
        Ok(serde_json::Value::from(list).to_string())
    })
}

/// Renders a material ball (or every material's contact sheet): the PNG, and for each
/// material drawn its index, name and what is not drawn of it.
#[pyfunction]
#[pyo3(signature = (asset, *, material=None, all=false, size=512))]
#[allow(clippy::type_complexity)]
fn render(
    py: Python<'_>,
    asset: PathBuf,
    material: Option<String>,
    all: bool,
    size: u32,
) -> PyResult<(Py<PyBytes>, Vec<(usize, String, Vec<String>)>)> {
    let mut options = gltfmat::RenderOptions::default();
    options.material = material;
    options.all = all;
    options.size = size;
    let (png, drawn) = py.detach(move || {
        let picture =
            gltfmat::render(&asset, &options).map_err(|e| GltfmatError::new_err(e.to_string()))?;
        let drawn = (picture.drawn.into_iter().zip(picture.not_drawn))
            .map(|((index, name), missing)| (index, name, missing))
            .collect::<Vec<_>>();
        PyResult::Ok((gltfmat::png(&picture.image), drawn))
    })?;
    Ok((PyBytes::new(py, &png).unbind(), drawn))
}

#[pymodule]
fn _gltfmat(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("GltfmatError", m.py().get_type::<GltfmatError>())?;
    m.add("UpgradeRefused", m.py().get_type::<UpgradeRefused>())?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(upgrade, m)?)?;
    m.add_function(wrap_pyfunction!(compare, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    Ok(())
}
