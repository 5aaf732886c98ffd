//! The mutation fuzzer behind `examples/fuzz.rs` (long runs) and `tests/fuzz.rs` (a short
//! bounded run in `cargo test`). It runs on the stable toolchain.
//!
//! Seeds are every file under `fixtures/` (glTF, GLB, 1.0 assets, PNG images), or under the
//! folders given. Each iteration
//! picks a seed, applies a few random mutations (bit flips, byte overwrites with interesting
//! values, range deletion/duplication, splices from another seed, JSON number swaps), or,
//! for a glTF text seed, structural ones on its parsed JSON (numeric extremes into any
//! number, indices permuted, arrays and objects duplicated to 10^3–10^4 elements, path-like
//! strings into URIs, any member given a value of another JSON type: inputs byte mutation
//! almost never makes), and
//! runs the checker (default profile with `--deep`, and the Khronos profile) and the
//! converter on the result. Images are also embedded into a glTF as data URIs so the image
//! decoders are reached. One input in eight is also written to a folder where each file it
//! names is, at random, a seed's bytes (whole or cut), a FIFO, a folder, a symlink to
//! `/dev/zero`, to a file outside the folder or to itself, or missing, and is then checked,
//! upgraded, compared with itself (points on its meshes) and drawn from there: the
//! file-system tricks a stranger's upload can hold, through every reader of the evaluator.
//! The slowest input of each thread is saved to `target/fuzz-slowest/` with its time in its
//! name, so that a long run shows what the bounds let through.
//! A panic is a failure: the input is saved to `target/fuzz-crashes/`
//! and the process exits 1.

use base64::Engine;
use gltfmat::NoResources;
use gltfmat::{check_bytes, CheckOptions, Profile};
use gltfmat::{upgrade, UpgradeOptions};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

/// xorshift64*: deterministic for a seed, so a failure can be replayed.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

const INTERESTING: &[&[u8]] = &[
    b"0",
    b"-1",
    b"4294967295",
    b"2147483648",
    b"1e308",
    b"-0",
    b"NaN",
    b"null",
    b"[]",
    b"{}",
    b"\"\"",
    b"\"../x\"",
    b"\"/etc/passwd\"",
    b"\"data:,\"",
    b"true",
    b"1.5",
    &[0xFF, 0xFF, 0xFF, 0x7F],
    &[0, 0, 0, 0x80],
    &[0xFF; 4],
];

fn seeds(folder: &Path, out: &mut Vec<Vec<u8>>) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            seeds(&path, out);
        } else if let Ok(bytes) = std::fs::read(&path) {
            if bytes.len() < 4 << 20 {
                out.push(bytes);
            }
        }
    }
}

fn mutate(rng: &mut Rng, input: &mut Vec<u8>, corpus: &[Vec<u8>]) {
    for _ in 0..1 + rng.below(4) {
        let len = input.len();
        match rng.below(7) {
            0 if len > 0 => {
                let at = rng.below(len);
                input[at] ^= 1 << rng.below(8);
            }
            1 if len > 0 => {
                let at = rng.below(len);
                input[at] = rng.next() as u8;
            }
            2 if len > 0 => {
                let value = INTERESTING[rng.below(INTERESTING.len())];
                let at = rng.below(len);
                let end = (at + value.len()).min(len);
                input.splice(at..end, value.iter().copied());
            }
            3 if len > 1 => {
                let start = rng.below(len);
                let end = (start + 1 + rng.below(64)).min(len);
                input.drain(start..end);
            }
            4 if len > 1 => {
                let start = rng.below(len);
                let end = (start + 1 + rng.below(64)).min(len);
                let copy: Vec<u8> = input[start..end].to_vec();
                let at = rng.below(len);
                input.splice(at..at, copy);
            }
            5 => {
                let other = &corpus[rng.below(corpus.len())];
                if !other.is_empty() && len > 0 {
                    let from = rng.below(other.len());
                    let take = (1 + rng.below(256)).min(other.len() - from);
                    let at = rng.below(len);
                    input.splice(at..at, other[from..from + take].iter().copied());
                }
            }
            _ => {
                // A number in the JSON replaced by an extreme one.
                let digits: Vec<usize> = (0..len).filter(|&i| input[i].is_ascii_digit()).collect();
                if !digits.is_empty() {
                    let at = digits[rng.below(digits.len())];
                    let value = [&b"99999999999"[..], b"0", b"4294967296", b"1e400"][rng.below(4)];
                    input.splice(at..at + 1, value.iter().copied());
                }
            }
        }
    }
}

/// Numbers byte mutation rarely writes: each limit an offset, count or index can hit.
const EXTREMES: &[f64] = &[
    0.0,
    -1.0,
    2147483648.0,
    4294967296.0,
    9007199254740992.0,
    18446744073709551612.0,
    1e308,
    -0.0,
    1e-320,
];

/// Strings a URI can hold that lead somewhere unexpected.
const PATHS: &[&str] = &[
    "../x.bin",
    "/etc/passwd",
    "..",
    ".",
    "",
    "a/../../b",
    "C:\\x",
    "%2e%2e/x",
    "data:,",
    "data:application/octet-stream;base64,",
    "x.bin?#",
    "\u{0}",
];

/// One value of each JSON type, empty and wrongly shaped containers among them.
const OTHER_TYPES: &[fn() -> serde_json::Value] = &[
    || serde_json::Value::Null,
    || serde_json::json!(true),
    || serde_json::json!(-1.5),
    || serde_json::json!("x"),
    || serde_json::json!([]),
    || serde_json::json!([1, "a", null]),
    || serde_json::json!({}),
    || serde_json::json!({"a": [1]}),
];

/// A structural mutation of a JSON document: one of its values, chosen at random, is
/// replaced by an extreme number, a path, a duplicated container or a permuted array.
fn mutate_json(rng: &mut Rng, root: &mut serde_json::Value) {
    use serde_json::Value;
    // Walk down a few random steps (stopping at a leaf), then change what is there.
    let mut path = String::new();
    let mut walked = &*root;
    for _ in 0..rng.below(6) {
        walked = match walked {
            Value::Array(items) if !items.is_empty() => {
                let i = rng.below(items.len());
                path.push_str(&format!("/{i}"));
                &items[i]
            }
            Value::Object(map) if !map.is_empty() => {
                let Some((key, value)) = map.iter().nth(rng.below(map.len())) else {
                    break;
                };
                path.push('/');
                path.push_str(&key.replace('~', "~0").replace('/', "~1"));
                value
            }
            _ => break,
        };
    }
    let Some(at) = root.pointer_mut(&path) else {
        return;
    };
    match (rng.below(7), &mut *at) {
        (0, Value::Number(_)) | (0, Value::Null) => {
            let extreme = EXTREMES[rng.below(EXTREMES.len())];
            *at = serde_json::json!(extreme);
        }
        (1, Value::String(_)) => *at = Value::String(PATHS[rng.below(PATHS.len())].into()),
        (2, Value::Array(items)) if !items.is_empty() => {
            // Each element is kept: an index permutation makes references point elsewhere.
            for i in (1..items.len()).rev() {
                items.swap(i, rng.below(i + 1));
            }
        }
        (3, Value::Array(items)) if !items.is_empty() => {
            let times = ([1_000, 10_000][rng.below(2)] / items.len()).min(copies_within(items));
            let copy = items.clone();
            for _ in 0..times {
                items.extend(copy.iter().cloned());
            }
        }
        (4, Value::Object(map)) => {
            let copy = Value::Object(map.clone());
            let times = (1 + rng.below(1_000)).min(copies_within(&copy));
            *at = Value::Array(vec![copy; times]);
        }
        // Any member may hold a value of any JSON type: readers that index into what they
        // expect to be an object or array meet a number, a string, a boolean or null.
        (5 | 6, value) => *value = OTHER_TYPES[rng.below(OTHER_TYPES.len())](),
        (_, value) => *value = serde_json::json!(EXTREMES[rng.below(EXTREMES.len())] as i64),
    }
}

/// How many copies of `value` stay within 4 MB of JSON: the inputs stay large in count, not
/// in bytes, and the fuzzer itself in memory.
fn copies_within(value: &impl serde::Serialize) -> usize {
    let bytes = serde_json::to_vec(value).map_or(usize::MAX, |text| text.len().max(1));
    (4 << 20) / bytes
}

/// A glTF text seed mutated structurally, or None for seeds that are not JSON.
fn mutate_structure(rng: &mut Rng, input: &[u8]) -> Option<Vec<u8>> {
    let mut root: serde_json::Value = serde_json::from_slice(input).ok()?;
    for _ in 0..1 + rng.below(3) {
        mutate_json(rng, &mut root);
    }
    serde_json::to_vec(&root)
        .ok()
        .filter(|text| text.len() <= 16 << 20)
}

/// Image bytes become a one-texture glTF, so mutated images reach the decoders (a KTX2
/// through KHR_texture_basisu).
fn as_asset(input: &[u8]) -> Vec<u8> {
    let ktx2 = input.starts_with(b"\xABKTX 20");
    let is_image = ktx2
        || input.starts_with(b"\x89PNG")
        || input.starts_with(&[0xFF, 0xD8])
        || input.starts_with(b"RIFF");
    if !is_image {
        return input.to_vec();
    }
    let uri = format!(
        "data:image/{};base64,{}",
        if ktx2 { "ktx2" } else { "png" },
        base64::engine::general_purpose::STANDARD.encode(input)
    );
    let texture = match ktx2 {
        true => serde_json::json!({"extensions": {"KHR_texture_basisu": {"source": 0}}}),
        false => serde_json::json!({"source": 0}),
    };
    serde_json::to_vec(&serde_json::json!({
        "asset": {"version": "2.0"}, "images": [{"uri": uri}], "textures": [texture],
        "materials": [{"normalTexture": {"index": 0}, "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0},
            "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 1, 1], "sheenRoughnessFactor": 0.5, "sheenRoughnessTexture": {"index": 0}}}}],
        "extensionsUsed": ["KHR_materials_sheen", "KHR_texture_basisu"]
    }))
    .unwrap_or_default()
}

fn exercise(input: &[u8]) {
    let asset = as_asset(input);
    let deep = CheckOptions::default().with_deep(true);
    let khronos = CheckOptions::default().with_profile(Profile::Khronos);
    for options in [&deep, &khronos] {
        let report = check_bytes("fuzz.gltf", asset.clone(), &NoResources, options);
        let _ = gltfmat::report::render(
            gltfmat::report::Format::Human,
            &[report],
            &gltfmat::report::Style::new(false),
        );
    }
    let _ = check_bytes("fuzz.glb", asset.clone(), &NoResources, &deep);
    if let Ok(upgraded) = upgrade(&asset, &NoResources, &UpgradeOptions::default()) {
        let _ =
            gltfmat::upgrade_output::verify(&gltfmat::upgrade_output::layout(&upgraded, "out.glb"));
    }
}

/// Runs `iterations` mutated inputs; `Err` names the saved input of the first panic.
/// Every relative file name a URI in `value` names (data URIs and schemes left out).
fn named_files(value: &serde_json::Value, out: &mut Vec<String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, member) in map {
                match member {
                    serde_json::Value::String(uri) if key == "uri" => {
                        if !uri.contains(':') && !uri.is_empty() && uri.len() < 200 {
                            out.push(uri.clone());
                        }
                    }
                    _ => named_files(member, out),
                }
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|item| named_files(item, out)),
        _ => {}
    }
}

/// Makes `name` in `folder` one of the things a hostile upload can put there.
#[cfg(unix)]
fn plant(rng: &mut Rng, folder: &Path, name: &str, corpus: &[Vec<u8>]) {
    // Only names that stay inside the scratch folder are planted.
    let path = folder.join(name);
    if !path.starts_with(folder) || name.contains("..") {
        return;
    }
    if let Some(parent) = path.parent() {
        let _ = std::fs::create_dir_all(parent);
    }
    let outside = folder.parent().unwrap_or(folder).join("outside.bin");
    let _ = match rng.below(8) {
        0 | 1 => {
            // create_new: a name planted twice may already be a FIFO, which a write would
            // wait on forever.
            let bytes = &corpus[rng.below(corpus.len())];
            std::fs::File::create_new(&path).and_then(|mut file| {
                std::io::Write::write_all(&mut file, &bytes[..rng.below(bytes.len() + 1)])
            })
        }
        2 => {
            let c_path = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).ok();
            // SAFETY: mkfifo reads a NUL-terminated path that outlives the call.
            c_path.map_or(Ok(()), |c| {
                unsafe { libc::mkfifo(c.as_ptr(), 0o600) };
                Ok(())
            })
        }
        3 => std::fs::create_dir(&path),
        4 => std::os::unix::fs::symlink("/dev/zero", &path),
        5 => std::os::unix::fs::symlink(&outside, &path),
        6 => std::os::unix::fs::symlink(&path, &path),
        _ => Ok(()),
    };
}

/// `input` checked and upgraded from a folder of planted files; returns the executions run.
#[cfg(unix)]
fn exercise_on_disk(rng: &mut Rng, input: &[u8], corpus: &[Vec<u8>], scratch: &Path) -> u64 {
    let folder = scratch.join("asset");
    let _ = std::fs::remove_dir_all(&folder);
    if std::fs::create_dir_all(&folder).is_err() {
        return 0;
    }
    let asset = as_asset(input);
    let name = if asset.starts_with(b"glTF") {
        "a.glb"
    } else {
        "a.gltf"
    };
    let path = folder.join(name);
    if std::fs::write(&path, &asset).is_err() {
        return 0;
    }
    let mut files = Vec::new();
    if let Ok(root) = serde_json::from_slice::<serde_json::Value>(&asset) {
        named_files(&root, &mut files);
    }
    files.sort();
    files.dedup();
    for file in files.iter().take(8) {
        plant(rng, &folder, file, corpus);
    }
    let _ = gltfmat::check_path(&path, &CheckOptions::default().with_deep(true));
    let resources = gltfmat::FolderResources::beside(&path);
    let _ = upgrade(&asset, &resources, &UpgradeOptions::default());
    // The evaluator's readers: every material with itself (points on its meshes), and drawn.
    let _ = gltfmat::compare(&path, &path, &gltfmat::CompareOptions::default());
    let mut drawn = gltfmat::RenderOptions::default();
    drawn.size = 16;
    let _ = gltfmat::render(&path, &drawn);
    let _ = gltfmat::render_each(&path, 16, 4);
    4
}

#[cfg(not(unix))]
fn exercise_on_disk(_: &mut Rng, _: &[u8], _: &[Vec<u8>], _: &Path) -> u64 {
    0
}

/// Runs `iterations` mutated inputs on `threads` threads, each with its own share of the
/// iterations and its own seed derived from `seed`, the seeds being the files under
/// `folders` (`fixtures/` when empty); `Ok` is the number of seeds and of executions of
/// check, upgrade, compare or render (summed), `Err` names the saved input of a panic.
pub fn run_parallel(
    iterations: u64,
    seed: u64,
    threads: u64,
    folders: &[PathBuf],
) -> Result<(usize, u64), String> {
    let fixtures = [PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fixtures")];
    let folders = if folders.is_empty() {
        &fixtures[..]
    } else {
        folders
    };
    let mut corpus = Vec::new();
    for folder in folders {
        seeds(folder, &mut corpus);
    }
    if corpus.is_empty() {
        return Err(format!("no seeds under {folders:?}"));
    }
    // Panics are caught and reported by input: the default hook's message would only
    // interleave with the progress lines.
    let previous_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let threads = threads.max(1);
    let outcomes: Vec<Result<u64, String>> = std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|t| {
                let share = iterations / threads + u64::from(t < iterations % threads);
                let seed = seed.wrapping_add(t.wrapping_mul(0x9E37_79B9_7F4A_7C15));
                let corpus = &corpus;
                scope.spawn(move || run_one(share, seed, corpus))
            })
            .collect();
        workers
            .into_iter()
            .map(|w| {
                w.join()
                    .unwrap_or_else(|_| Err("a fuzz thread died".into()))
            })
            .collect()
    });
    std::panic::set_hook(previous_hook);
    let mut executions = 0;
    for outcome in outcomes {
        executions += outcome?;
    }
    Ok((corpus.len(), executions))
}

/// One thread's run: `iterations` inputs from `seed`; the executions, or the saved input of
/// the first panic.
fn run_one(iterations: u64, seed: u64, corpus: &[Vec<u8>]) -> Result<u64, String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut rng = Rng(seed | 1);
    let mut failure = None;
    let mut executions = 0;
    let mut slowest = (0.0, Vec::new());
    let scratch =
        std::env::temp_dir().join(format!("gltfmat-fuzz-{}-{seed:x}", std::process::id()));
    let _ = std::fs::create_dir_all(&scratch);
    let _ = std::fs::write(scratch.join("outside.bin"), b"outside the asset's folder");
    for i in 0..iterations {
        let mut input = corpus[rng.below(corpus.len())].clone();
        match rng.below(2) {
            0 => mutate(&mut rng, &mut input, corpus),
            _ => match mutate_structure(&mut rng, &input) {
                Some(mutated) => input = mutated,
                None => mutate(&mut rng, &mut input, corpus),
            },
        }
        let on_disk = rng.below(8) == 0;
        let started = std::time::Instant::now();
        let ran = catch_unwind(AssertUnwindSafe(|| {
            exercise(&input);
            match on_disk {
                true => 4 + exercise_on_disk(&mut rng, &input, corpus, &scratch),
                false => 4,
            }
        }));
        let took = started.elapsed().as_secs_f64();
        if took > slowest.0 {
            slowest = (took, input.clone());
        }
        if let Ok(count) = ran {
            executions += count;
            if (i + 1) % 100_000 == 0 {
                eprintln!(
                    "fuzz ({seed:x}): {} inputs, {executions} executions, no panic",
                    i + 1
                );
            }
        } else {
            let folder = root.join("target/fuzz-crashes");
            let _ = std::fs::create_dir_all(&folder);
            let path = folder.join(format!("crash-{seed:x}-{i}.bin"));
            let _ = std::fs::write(&path, &input);
            failure = Some(format!(
                "panic at iteration {i}; input saved to {}",
                path.display()
            ));
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&scratch);
    let folder = root.join("target/fuzz-slowest");
    let _ = std::fs::create_dir_all(&folder);
    let name = format!("slowest-{seed:x}-{:.2}s.bin", slowest.0);
    let _ = std::fs::write(folder.join(name), &slowest.1);
    failure.map_or(Ok(executions), Err)
}
