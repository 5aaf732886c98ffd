//! File-system attacks on `check` and `upgrade` (issue 13, findings 2–9 and 19), each input
//! generated here: a stranger's file swapped, truncated or replaced by a FIFO while it is
//! read, symlinks planted in the output folder, concurrent runs, kills mid-write. The
//! promise each test states: a diagnostic or a clean refusal (exit 0, 1 or 2, never a
//! signal), nothing outside the output folder touched, the input's files byte-identical.

mod common;

use gltfmat::{check_path, CheckOptions};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

fn gltfmat(folder: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(args)
        .current_dir(folder)
        .env("NO_COLOR", "1")
        .output()
        .expect("gltfmat runs")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// A glTF 1.0 triangle soup of `triangles` triangles whose positions are in `model.bin`.
fn write_gltf1(folder: &Path, name: &str, triangles: usize) {
    let vertices = 3 * triangles;
    let mut bin = Vec::with_capacity(vertices * 12);
    for i in 0..vertices {
        for c in [i % 7, i % 5, i % 3] {
            bin.extend((c as f32).to_le_bytes());
        }
    }
    let gltf = json!({
        "asset": {"version": "1.0"},
        "buffers": {"b": {"uri": "model.bin", "byteLength": bin.len()}},
        "bufferViews": {"v": {"buffer": "b", "byteOffset": 0, "byteLength": bin.len(), "target": 34962}},
        "accessors": {"p": {"bufferView": "v", "byteOffset": 0, "componentType": 5126,
            "count": vertices, "type": "VEC3", "min": [0, 0, 0], "max": [6, 4, 2]}},
        "meshes": {"m": {"primitives": [{"attributes": {"POSITION": "p"}, "mode": 4}]}},
        "nodes": {"n": {"meshes": ["m"]}},
        "scenes": {"s": {"nodes": ["n"]}},
        "scene": "s"
    });
    std::fs::write(folder.join(name), serde_json::to_vec(&gltf).unwrap()).unwrap();
    std::fs::write(folder.join("model.bin"), bin).unwrap();
}

/// A glTF 2.0 asset whose one buffer is the file `uri` of `length` bytes.
fn gltf2_with_buffer(uri: &str, length: usize) -> Vec<u8> {
    serde_json::to_vec(&json!({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": uri, "byteLength": length}]
    }))
    .unwrap()
}

fn snapshot(folder: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .flatten()
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .map(|e| (e.path(), std::fs::read(e.path()).unwrap()))
        .collect();
    files.sort();
    files
}

fn temporaries(folder: &Path) -> Vec<String> {
    std::fs::read_dir(folder)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".gltfmat-"))
        .collect()
}

#[test]
fn a_large_input_truncated_while_it_is_checked_gives_an_exit_status_not_a_signal() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("big.glb");
    let json = br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":8388608}]}"#;
    let glb = common::glb(json, Some(&vec![7u8; 8 << 20]));
    for _ in 0..5 {
        truncate_while_checked(&path, &glb, Duration::ZERO);
    }
}

/// A large buffer file truncated by another process mid-upgrade: that process never waits on
/// gltfmat (no lease holds it up), and the upgrade ends with an exit status, never a signal
/// (nothing is mapped that could fault), and leaves no temporary.
#[cfg(unix)]
#[test]
fn a_large_buffer_truncated_while_it_is_upgraded_neither_waits_nor_kills() {
    let folder = tempfile::tempdir().unwrap();
    for run in 0..5 {
        write_gltf1(folder.path(), "big.gltf", 500_000); // 18 MB of positions
        let output = format!("out{run}.glb");
        let child = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
            .args(["upgrade", "big.gltf", "-o", &output, "--no-verify"])
            .current_dir(folder.path())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        // Truncated once the output's temporary appears (the buffer was read, and the output
        // is being written and checked), or at once on the first run.
        while run > 0
            && temporaries(folder.path()).is_empty()
            && !folder.path().join(&output).exists()
        {
            std::thread::yield_now();
        }
        let started = std::time::Instant::now();
        let buffer = std::fs::OpenOptions::new()
            .write(true)
            .open(folder.path().join("model.bin"));
        buffer.unwrap().set_len(100).unwrap();
        let waited = started.elapsed();
        assert!(
            waited < Duration::from_secs(2),
            "the writer waited {waited:?}"
        );
        let finished = child.wait_with_output().unwrap();
        assert!(
            finished.status.code().is_some(),
            "killed by a signal: {:?}",
            finished.status
        );
        assert!(temporaries(folder.path()).is_empty());
    }
}

/// Writes `glb` to `path`, starts `gltfmat check` on it, truncates the file after `delay`,
/// and asserts that the check ends with an exit status, not a signal.
fn truncate_while_checked(path: &Path, glb: &[u8], delay: Duration) {
    std::fs::write(path, glb).unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["check", "--quiet"])
        .arg(path)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(delay);
    std::fs::OpenOptions::new()
        .write(true)
        .open(path)
        .unwrap()
        .set_len(100)
        .unwrap();
    let status = child.wait_with_output().unwrap().status;
    assert!(status.code().is_some(), "killed by a signal: {status:?}");
}

#[cfg(unix)]
#[test]
fn symlinks_planted_for_the_temporaries_are_never_written_through() {
    let root = tempfile::tempdir().unwrap();
    let (folder, outside) = (root.path().join("out"), root.path().join("victim.txt"));
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(&outside, b"precious").unwrap();
    write_gltf1(&folder, "in.gltf", 4);
    // Names of the form temporaries take, for the next thousand processes.
    let next = std::process::id();
    for pid in next..next + 1000 {
        for name in ["out.gltf", "out.bin"] {
            let planted = folder.join(format!(".{name}.gltfmat-{pid}.0-x.tmp"));
            std::os::unix::fs::symlink(&outside, planted).unwrap();
        }
    }
    let output = gltfmat(&folder, &["upgrade", "in.gltf", "-o", "out.gltf"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_eq!(std::fs::read(&outside).unwrap(), b"precious");
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(folder.join("out.gltf")).unwrap()).unwrap();
    assert_eq!(written["asset"]["version"], "2.0");
}

#[cfg(unix)]
#[test]
fn a_resource_swapped_for_a_symlink_leading_out_is_never_read() {
    let root = tempfile::tempdir().unwrap();
    let folder = root.path().join("asset");
    std::fs::create_dir(&folder).unwrap();
    // The outside file is longer than the declared buffer: had it been read, the check would
    // report its length.
    std::fs::write(root.path().join("secret"), vec![1u8; 100]).unwrap();
    std::fs::write(folder.join("a.gltf"), gltf2_with_buffer("x.bin", 12)).unwrap();
    let (regular, link) = (folder.join("regular"), folder.join("link"));
    std::fs::write(&regular, [0u8; 12]).unwrap();
    std::os::unix::fs::symlink(root.path().join("secret"), &link).unwrap();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let swapper = {
        let (stop, folder) = (stop.clone(), folder.clone());
        std::thread::spawn(move || {
            let target = folder.join("x.bin");
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                let _ = std::fs::hard_link(&regular, folder.join("x.tmp"));
                let _ = std::fs::rename(folder.join("x.tmp"), &target);
                let copy = folder.join("l.tmp");
                let _ = std::fs::remove_file(&copy);
                let _ = std::os::unix::fs::symlink(std::fs::read_link(&link).unwrap(), &copy);
                let _ = std::fs::rename(&copy, &target);
            }
        })
    };
    for _ in 0..2000 {
        let report = check_path(folder.join("a.gltf"), &CheckOptions::default()).unwrap();
        let read_outside = report.diagnostics.iter().any(|d| d.message.contains("100"));
        assert!(!read_outside, "{:?}", report.diagnostics);
    }
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    swapper.join().unwrap();
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let name = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path; mkfifo only creates the node.
    assert_eq!(unsafe { libc::mkfifo(name.as_ptr(), 0o600) }, 0);
}

#[cfg(unix)]
#[test]
fn fifos_and_devices_are_refused_at_once_never_read() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    mkfifo(&folder.join("pipe.bin"));
    mkfifo(&folder.join("pipe.gltf"));
    std::os::unix::fs::symlink("/dev/zero", folder.join("zero.glb")).unwrap();
    std::fs::write(folder.join("a.gltf"), gltf2_with_buffer("pipe.bin", 4)).unwrap();
    let started = Instant::now();
    let report = check_path(folder.join("a.gltf"), &CheckOptions::default()).unwrap();
    let refusal = report
        .diagnostics
        .iter()
        .find(|d| d.code == "IO_ERROR")
        .expect("the FIFO is reported");
    assert!(
        refusal.message.contains("not a regular file (a FIFO)"),
        "{}",
        refusal.message
    );

    // Named directly, each is refused with what it is; walked, each is skipped with a note.
    for (name, kind) in [("pipe.gltf", "a FIFO"), ("zero.glb", "a device")] {
        let output = gltfmat(folder, &["check", name]);
        assert_eq!(output.status.code(), Some(2));
        assert!(stderr(&output).contains(&format!("not a regular file ({kind})")));
    }
    let output = gltfmat(folder, &["check", ".", "--format", "json"]);
    let reports: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(
        reports,
        serde_json::json!([reports[0]]),
        "a walked folder gives an array: here of one report"
    );
    assert_eq!(reports[0]["uri"], "./a.gltf", "of a.gltf only");
    assert!(stderr(&output).contains("skipped ./pipe.gltf: not a regular file"));
    assert!(stderr(&output).contains("skipped ./zero.glb: not a regular file"));
    let output = gltfmat(folder, &["check", "/dev/null"]);
    assert!(stderr(&output).contains("/dev/null: not a regular file (a device)"));
    assert!(
        started.elapsed() < Duration::from_secs(60),
        "nothing waited on a FIFO"
    );
}

#[test]
fn force_never_replaces_a_file_the_input_reads() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "scene.gltf", 4);
    let before = snapshot(folder);
    // model.gltf would write model.bin: the input's own buffer.
    for output in ["model.gltf", "scene.gltf", "scene.glb"] {
        if output == "scene.glb" {
            #[cfg(unix)]
            std::os::unix::fs::symlink("scene.gltf", folder.join("scene.glb")).unwrap();
            #[cfg(not(unix))]
            continue;
        }
        let run = gltfmat(folder, &["upgrade", "scene.gltf", "-o", output, "--force"]);
        assert_eq!(run.status.code(), Some(2), "{output}");
        assert!(
            stderr(&run).contains("is the input or a file it reads"),
            "{}",
            stderr(&run)
        );
        let now: Vec<_> = snapshot(folder);
        assert_eq!(now, before, "{output}: the input's files are unchanged");
    }
}

#[test]
fn a_side_file_that_cannot_be_placed_leaves_the_old_output_whole() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "in.gltf", 4);
    std::fs::write(folder.join("out.gltf"), b"old output").unwrap();
    std::fs::create_dir(folder.join("out.bin")).unwrap();
    let run = gltfmat(folder, &["upgrade", "in.gltf", "-o", "out.gltf", "--force"]);
    assert_eq!(run.status.code(), Some(2), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("out.bin is a folder"),
        "{}",
        stderr(&run)
    );
    assert_eq!(
        std::fs::read(folder.join("out.gltf")).unwrap(),
        b"old output"
    );
    assert!(temporaries(folder).is_empty());
}

#[test]
fn of_two_runs_writing_the_same_new_output_exactly_one_succeeds() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "in.gltf", 20_000);
    for round in 0..4 {
        let out = format!("out-{round}.glb");
        let start = || {
            Command::new(env!("CARGO_BIN_EXE_gltfmat"))
                .args(["upgrade", "in.gltf", "-o", &out])
                .current_dir(folder)
                .output()
        };
        let (a, b) = std::thread::scope(|s| {
            let a = s.spawn(start);
            let b = s.spawn(start);
            (a.join().unwrap().unwrap(), b.join().unwrap().unwrap())
        });
        let successes = [&a, &b].iter().filter(|o| o.status.success()).count();
        assert_eq!(successes, 1, "{}\n{}", stderr(&a), stderr(&b));
        let loser = if a.status.success() { &b } else { &a };
        assert!(stderr(loser).contains("exists"), "{}", stderr(loser));
    }
}

/// Starts an upgrade of a large asset, waits until its temporary exists, and stops it with
/// `signal`; None when the run finished before a temporary was seen.
#[cfg(unix)]
fn interrupt_mid_write(folder: &Path, output: &str, signal: i32) -> Option<()> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["upgrade", "in.gltf", "-o", output])
        .current_dir(folder)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    loop {
        if child.try_wait().unwrap().is_some() {
            let _ = std::fs::remove_file(folder.join(output));
            return None;
        }
        if !temporaries(folder).is_empty() {
            // SAFETY: kill sends a signal to our own child; it has no memory effects here.
            unsafe { libc::kill(child.id() as i32, signal) };
            child.wait().unwrap();
            return Some(());
        }
        std::thread::yield_now();
    }
}

#[cfg(unix)]
#[test]
fn interrupted_runs_leave_no_temporary_and_killed_ones_are_cleaned_by_the_next() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "in.gltf", 1_000_000);
    let mut interrupted = 0;
    for signal in [libc::SIGTERM, libc::SIGINT, libc::SIGTERM, libc::SIGINT] {
        if interrupt_mid_write(folder, "out.glb", signal).is_some() {
            interrupted += 1;
            assert_eq!(temporaries(folder), Vec::<String>::new(), "signal {signal}");
        }
    }
    assert!(interrupted > 0, "no run was caught mid-write");
    let mut killed = false;
    for _ in 0..4 {
        if interrupt_mid_write(folder, "out.glb", libc::SIGKILL).is_some() {
            killed = true;
            break;
        }
    }
    assert!(killed, "no run was caught mid-write");
    assert!(
        !temporaries(folder).is_empty(),
        "a killed run cannot clean up"
    );
    let run = gltfmat(folder, &["upgrade", "in.gltf", "-o", "out.glb", "--force"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(temporaries(folder), Vec::<String>::new());
}

#[test]
fn outputs_that_are_not_an_asset_file_are_refused_before_converting() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "in.gltf", 4);
    std::fs::create_dir(folder.join("dir")).unwrap();
    std::fs::write(folder.join("taken.glb"), b"x").unwrap();
    for (output, says) in [
        ("x.bin", "must be a file named *.gltf or *.glb"),
        ("dir/", "must be a file named *.gltf or *.glb"),
        ("taken.glb", "taken.glb exists"),
    ] {
        let run = gltfmat(folder, &["upgrade", "in.gltf", "-o", output]);
        assert_eq!(run.status.code(), Some(2), "{output}");
        assert!(stderr(&run).contains(says), "{output}: {}", stderr(&run));
        // Refused before converting: no conversion note was printed.
        assert!(run.stdout.is_empty(), "{output}");
    }
    let run = gltfmat(folder, &["upgrade", "in.gltf", "-o", "-"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(&run.stdout[..4], b"glTF", "a GLB on stdout");
    assert!(!folder.join("-").exists() && !folder.join("-.bin").exists());
}

/// A link a stranger planted in a checked folder (`scene.gltf` → a credentials file) does not
/// put that file into the report or its snippets; a link within the folder is followed, and a
/// link named on the command line is the user's to follow.
#[cfg(unix)]
#[test]
fn a_folder_walk_never_follows_a_link_out_of_the_folder() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    std::fs::create_dir_all(root.join("outside")).unwrap();
    std::fs::create_dir_all(root.join("assets")).unwrap();
    let secret = br#"{"asset": {"version": "2.0"}, "auths": {"registry": "s3cr3t-t0ken"}}"#;
    std::fs::write(root.join("outside/config.json"), secret).unwrap();
    std::fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/fixtures/valid/sheen-triangle.gltf"
        ),
        root.join("assets/real.gltf"),
    )
    .unwrap();
    let link = std::os::unix::fs::symlink;
    link("../outside/config.json", root.join("assets/scene.gltf")).unwrap();
    link("real.gltf", root.join("assets/alias.gltf")).unwrap();
    let run = gltfmat(root, &["check", "assets", "--all-findings"]);
    let printed = format!("{}{}", String::from_utf8_lossy(&run.stdout), stderr(&run));
    assert!(!printed.contains("s3cr3t"), "{printed}");
    assert!(
        printed.contains("skipped assets/scene.gltf: a symbolic link leading out of assets"),
        "{printed}"
    );
    assert!(printed.contains("2 file(s) checked"), "{printed}");
    let named = gltfmat(root, &["check", "assets/scene.gltf", "--all-findings"]);
    assert!(
        String::from_utf8_lossy(&named.stdout).contains("auths"),
        "{}",
        stderr(&named)
    );
}

#[test]
fn a_folder_walk_finds_assets_in_any_case_and_leaves_out_what_the_user_excludes() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    let valid = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/valid/sheen-triangle.gltf"
    ))
    .unwrap();
    for name in [
        "A.GLTF",
        "ignored/b.gltf",
        ".hidden/c.gltf",
        "excluded/d.gltf",
        "kept/e.Gltf",
    ] {
        let path = folder.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, &valid).unwrap();
    }
    std::fs::write(folder.join(".gitignore"), "ignored/\n").unwrap();
    let run = gltfmat(
        folder,
        &["check", ".", "--format", "json", "--exclude", "excluded/"],
    );
    assert_eq!(run.status.code(), Some(0), "{}", stderr(&run));
    let reports: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let uris: Vec<&str> = (reports.as_array().unwrap().iter())
        .map(|r| r["uri"].as_str().unwrap())
        .collect();
    assert_eq!(uris, ["./A.GLTF", "./kept/e.Gltf"]);

    // A folder with no asset is not a pass.
    std::fs::create_dir(folder.join("empty")).unwrap();
    let run = gltfmat(folder, &["check", "empty"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run).contains("empty: no .gltf or .glb file found"),
        "{}",
        stderr(&run)
    );
    // Nor is one whose assets are all hidden, and it says it skipped them.
    std::fs::create_dir_all(folder.join("only-hidden/.cache")).unwrap();
    std::fs::write(folder.join("only-hidden/.cache/f.gltf"), &valid).unwrap();
    let run = gltfmat(folder, &["check", "only-hidden"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr(&run)
            .contains("no .gltf or .glb file found (1 skipped: under hidden or ignored paths"),
        "{}",
        stderr(&run)
    );
}

#[test]
fn render_does_not_replace_a_file_without_force() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    std::fs::write(folder.join("material.png"), b"mine").unwrap();
    let asset = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/valid/sheen-triangle.gltf"
    );
    let run = gltfmat(folder, &["render", asset, "--size", "8"]);
    assert_eq!(run.status.code(), Some(2));
    assert!(stderr(&run).contains("material.png exists (use --force to replace it)"));
    assert_eq!(std::fs::read(folder.join("material.png")).unwrap(), b"mine");
    let run = gltfmat(folder, &["render", asset, "--size", "8", "--force"]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert_eq!(
        &std::fs::read(folder.join("material.png")).unwrap()[1..4],
        b"PNG"
    );
}

/// Past 32 MiB (the size from which gltfmat leaves a file's data in the file and reads it in
/// parts; `document`'s unit tests hold that it does) of float VEC3 data with a few NaNs and
/// non-unit normals in it
/// (data findings only a walk over it finds), and the JSON of an asset drawing it from
/// buffer 0 (`uri`: its file, or none for a GLB's BIN chunk).
fn large_data_with_findings(uri: Option<&str>) -> (String, Vec<u8>) {
    let count = ((32usize << 20) + (1 << 20)) / 12;
    let mut data: Vec<u8> = (0..count)
        .flat_map(|_| [0f32, 0.0, 1.0])
        .flat_map(f32::to_le_bytes)
        .collect();
    for i in [3, count / 2, count - 1] {
        data[i * 12..i * 12 + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    }
    for i in 100..140 {
        data[i * 12 + 8..i * 12 + 12].copy_from_slice(&2f32.to_le_bytes());
    }
    let mut buffer = json!({"byteLength": data.len()});
    if let Some(uri) = uri {
        buffer["uri"] = uri.into();
    }
    let json = json!({
        "asset": {"version": "2.0"},
        "buffers": [buffer],
        "bufferViews": [{"buffer": 0, "byteLength": data.len(), "byteStride": 12, "target": 34962}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                       "min": [0, 0, 0], "max": [0, 0, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 0}, "mode": 0}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0
    });
    (json.to_string(), data)
}

/// A GLB past 32 MiB (see [`large_data_with_findings`]).
fn large_glb_with_data_findings() -> Vec<u8> {
    let (json, data) = large_data_with_findings(None);
    common::glb(json.as_bytes(), Some(&data))
}

/// Its findings, sorted, with a check that the walk over the data made them.
fn data_findings(report: &gltfmat::Report) -> Vec<String> {
    let mut found: Vec<String> = (report.diagnostics.iter())
        .map(|d| format!("{} {:?} {}", d.code, d.location, d.message))
        .collect();
    found.sort();
    assert!(
        found
            .iter()
            .any(|f| f.starts_with("ACCESSOR_INVALID_FLOAT")),
        "{found:?}"
    );
    assert!(
        found
            .iter()
            .any(|f| f.starts_with("ACCESSOR_VECTOR3_NON_UNIT")),
        "{found:?}"
    );
    found
}

#[test]
fn a_large_glb_checked_from_its_file_reports_what_its_bytes_in_memory_do() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("large.glb");
    let glb = large_glb_with_data_findings();
    std::fs::write(&path, &glb).unwrap();
    let options = CheckOptions::default().with_max_issues(0);
    let from_file = check_path(&path, &options).unwrap();
    let in_memory = gltfmat::check_bytes("large.glb", glb, &gltfmat::NoResources, &options);
    assert_eq!(data_findings(&from_file), data_findings(&in_memory));
    for severity in [gltfmat::Severity::Error, gltfmat::Severity::Warning] {
        assert_eq!(from_file.count(severity), in_memory.count(severity));
    }
}

#[test]
fn a_large_external_buffer_checked_from_its_file_reports_what_its_bytes_in_memory_do() {
    let folder = tempfile::tempdir().unwrap();
    let (json, data) = large_data_with_findings(Some("large.bin"));
    std::fs::write(folder.path().join("large.gltf"), &json).unwrap();
    std::fs::write(folder.path().join("large.bin"), &data).unwrap();
    let options = CheckOptions::default().with_max_issues(0);
    let from_file = check_path(folder.path().join("large.gltf"), &options).unwrap();
    let mut loader = gltfmat::MemoryResources::default();
    loader
        .files
        .insert("large.bin".into(), std::sync::Arc::new(data.into()));
    let in_memory = gltfmat::check_bytes("large.gltf", json, &loader, &options);
    assert_eq!(data_findings(&from_file), data_findings(&in_memory));
    // The folder loader left the file in place; the memory one has it read.
    let folder_loader = gltfmat::FolderResources::new(folder.path());
    let kept = gltfmat::ResourceLoader::load_buffer(&folder_loader, "large.bin");
    assert!(matches!(kept, Ok(gltfmat::Kept::File(_))), "{kept:?}");
}

#[test]
fn a_large_glb_truncated_while_it_is_checked_gives_an_exit_status_not_a_signal() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("large.glb");
    let glb = large_glb_with_data_findings();
    for _ in 0..3 {
        truncate_while_checked(&path, &glb, Duration::from_millis(20));
    }
}

/// A folder with the sheen-triangle fixture and its texture-like neighbour `texture.png`,
/// which the asset does not read, and an outside folder with a file a link may point at.
fn render_scene() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let root = tempfile::tempdir().unwrap();
    let folder = root.path().join("work");
    std::fs::create_dir(&folder).unwrap();
    std::fs::copy(
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/fixtures/valid/sheen-triangle.gltf"
        ),
        folder.join("asset.gltf"),
    )
    .unwrap();
    let victim = root.path().join("victim.txt");
    std::fs::write(&victim, b"precious").unwrap();
    (root, folder, victim)
}

/// The commands that write one output file besides `upgrade`, each writing to `OUT`.
const WRITERS: &[&[&str]] = &[
    &["render", "asset.gltf", "--size", "8", "-o", "OUT"],
    &[
        "compare",
        "asset.gltf",
        "asset.gltf",
        "--grid",
        "4",
        "--heatmap",
        "OUT",
    ],
    &["lut", "sheen", "--size", "4", "-o", "OUT"],
];

/// Runs one of [`WRITERS`] onto `out` with `--force`, which must succeed (exit 0 or 1).
fn forced(folder: &Path, args: &[&str], out: &str) {
    let mut forced = with_output(args, out);
    forced.push("--force");
    let run = gltfmat(folder, &forced);
    assert!(
        run.status.code().is_some_and(|c| c < 2),
        "{args:?}: {}",
        stderr(&run)
    );
}

fn with_output<'a>(args: &[&'a str], out: &'a str) -> Vec<&'a str> {
    args.iter()
        .map(|a| if *a == "OUT" { out } else { a })
        .collect()
}

#[test]
fn render_compare_and_lut_replace_an_existing_file_only_with_force() {
    let (_root, folder, _) = render_scene();
    for args in WRITERS {
        std::fs::write(folder.join("taken.png"), b"mine").unwrap();
        let run = gltfmat(&folder, &with_output(args, "taken.png"));
        assert_eq!(run.status.code(), Some(2), "{args:?}: {}", stderr(&run));
        assert!(
            stderr(&run).contains("taken.png exists (use --force"),
            "{}",
            stderr(&run)
        );
        assert_eq!(std::fs::read(folder.join("taken.png")).unwrap(), b"mine");
        forced(&folder, args, "taken.png");
        assert_ne!(std::fs::read(folder.join("taken.png")).unwrap(), b"mine");
        assert!(temporaries(&folder).is_empty(), "{args:?}");
    }
}

#[cfg(unix)]
#[test]
fn render_compare_and_lut_never_write_through_a_symlink() {
    let (root, folder, victim) = render_scene();
    for args in WRITERS {
        // A dangling link: without --force the name is taken, and nothing appears outside.
        let outside_new = root.path().join("created-outside.png");
        let _ = std::fs::remove_file(folder.join("dangling.png"));
        std::os::unix::fs::symlink(&outside_new, folder.join("dangling.png")).unwrap();
        let run = gltfmat(&folder, &with_output(args, "dangling.png"));
        assert_eq!(run.status.code(), Some(2), "{args:?}: {}", stderr(&run));
        assert!(
            !outside_new.exists(),
            "{args:?} wrote through a dangling link"
        );
        // A link to a file, replaced with --force: the link goes, the file stays.
        let _ = std::fs::remove_file(folder.join("link.png"));
        std::os::unix::fs::symlink(&victim, folder.join("link.png")).unwrap();
        forced(&folder, args, "link.png");
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious", "{args:?}");
        let link = folder.join("link.png").symlink_metadata().unwrap();
        assert!(
            !link.file_type().is_symlink(),
            "{args:?}: the link was replaced"
        );
    }
}

/// Every writer but `lut` (which reads no asset) is refused a file the asset reads — its
/// buffer, a texture — with or without --force, and writes nothing else either; so is a file
/// the asset names that the run has no need to read (a 1.0 asset's buffer, when only its
/// materials are drawn or compared).
#[test]
fn no_page_picture_or_heat_map_replaces_a_file_the_asset_reads_even_with_force() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures");
    for name in [
        "spec-gloss/textured.gltf",
        "spec-gloss/quad.bin",
        "spec-gloss/diffuse16.png",
        "spec-gloss/specgloss16.png",
        "spec-gloss/normal.png",
        "gltf1/pbr-sg-textured-ext.gltf",
        "gltf1/box.bin",
        "gltf1/diffuse.png",
        "gltf1/spec_gloss.png",
    ] {
        let file = Path::new(name).file_name().unwrap();
        std::fs::copy(fixtures.join(name), folder.join(file)).unwrap();
    }
    let before = snapshot(folder);
    for args in [
        vec![
            "compare",
            "textured.gltf",
            "textured.gltf",
            "--grid",
            "4",
            "--heatmap",
            "diffuse16.png",
            "--force",
        ],
        vec![
            "render",
            "textured.gltf",
            "--size",
            "8",
            "-o",
            "specgloss16.png",
            "--force",
        ],
        vec!["report", "textured.gltf", "-o", "quad.bin", "--force"],
        vec![
            "render",
            "pbr-sg-textured-ext.gltf",
            "--size",
            "8",
            "-o",
            "box.bin",
            "--force",
        ],
        vec![
            "compare",
            "pbr-sg-textured-ext.gltf",
            "pbr-sg-textured-ext.gltf",
            "--grid",
            "4",
            "--report",
            "box.bin",
            "--force",
        ],
        vec![
            "upgrade",
            "textured.gltf",
            "-o",
            "upgraded.glb",
            "--report",
            "normal.png",
            "--force",
        ],
    ] {
        let run = gltfmat(folder, &args);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {}", stderr(&run));
        assert!(
            stderr(&run).contains("is the input or a file it reads"),
            "{}",
            stderr(&run)
        );
        assert_eq!(snapshot(folder), before, "{args:?}");
    }
}

#[test]
fn an_upgrade_report_naming_a_file_of_the_output_is_refused_before_anything_is_written() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "scene.gltf", 4);
    let before = snapshot(folder);
    // The GLB itself, by another spelling, and the `.bin` a `.gltf` output writes beside it.
    for (output, page) in [
        ("out.glb", "out.glb"),
        ("out.glb", "./out.glb"),
        ("out.gltf", "out.bin"),
    ] {
        let run = gltfmat(
            folder,
            &[
                "upgrade",
                "scene.gltf",
                "-o",
                output,
                "--report",
                page,
                "--force",
            ],
        );
        assert_eq!(run.status.code(), Some(2), "{page}: {}", stderr(&run));
        assert!(
            stderr(&run).contains("would replace"),
            "{page}: {}",
            stderr(&run)
        );
        assert_eq!(snapshot(folder), before, "{output} with --report {page}");
    }
}

/// Two `upgrade --force` runs of different inputs into one multi-file output, raced many
/// times: what is left is always one run's whole set of files, never some of each.
#[test]
fn two_forced_upgrades_into_one_output_leave_one_runs_files_never_a_mix() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    let (a, b) = (folder.join("a"), folder.join("b"));
    std::fs::create_dir(&a).unwrap();
    std::fs::create_dir(&b).unwrap();
    write_gltf1(&a, "in.gltf", 3_000);
    write_gltf1(&b, "in.gltf", 3_001);
    let out = folder.join("out");
    std::fs::create_dir(&out).unwrap();
    // Each run's own set, written alone.
    let alone = |input: &Path, name: &str| {
        let target = folder.join(name);
        std::fs::create_dir(&target).unwrap();
        let run = gltfmat(
            &target,
            &[
                "upgrade",
                input.join("in.gltf").to_str().unwrap(),
                "-o",
                "x.gltf",
                "--no-verify",
            ],
        );
        assert!(run.status.success(), "{}", stderr(&run));
        snapshot(&target)
            .into_iter()
            .map(|(_, bytes)| bytes)
            .collect::<Vec<_>>()
    };
    let (set_a, set_b) = (alone(&a, "alone-a"), alone(&b, "alone-b"));
    assert_ne!(set_a, set_b);
    for round in 0..12 {
        let start = |input: &Path| {
            Command::new(env!("CARGO_BIN_EXE_gltfmat"))
                .args([
                    "upgrade",
                    input.join("in.gltf").to_str().unwrap(),
                    "-o",
                    "x.gltf",
                    "--force",
                    "--no-verify",
                ])
                .current_dir(&out)
                .output()
                .unwrap()
        };
        let (ra, rb) = std::thread::scope(|s| {
            let ra = s.spawn(|| start(&a));
            let rb = s.spawn(|| start(&b));
            (ra.join().unwrap(), rb.join().unwrap())
        });
        assert!(
            ra.status.success() && rb.status.success(),
            "{}{}",
            stderr(&ra),
            stderr(&rb)
        );
        let left: Vec<Vec<u8>> = snapshot(&out).into_iter().map(|(_, bytes)| bytes).collect();
        assert!(left == set_a || left == set_b, "round {round}: a mixed set");
    }
}

/// A report cut short by a full disk or a file-size limit is exit 2 with a message, never a
/// silent success; a reader that goes away (`| head`) is not an error.
#[cfg(unix)]
#[test]
fn a_report_that_cannot_be_written_whole_is_exit_2() {
    let folder = tempfile::tempdir().unwrap();
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/broken/bad-material.gltf"
    );
    let full = Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(["check", fixture, "--format", "sarif"])
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_eq!(full.status.code(), Some(2), "{}", stderr(&full));
    assert!(
        stderr(&full).contains("writing the output failed"),
        "{}",
        stderr(&full)
    );
    // A limit of one 512-byte block on the files this process writes; a reader that goes
    // away early is no failure.
    let shell = |line: String| Command::new("sh").arg("-c").arg(line).output().unwrap();
    let gltfmat_check = format!(
        "'{}' check '{fixture}' --format sarif",
        env!("CARGO_BIN_EXE_gltfmat")
    );
    let report = folder.path().join("report.sarif");
    let limited = shell(format!(
        "ulimit -f 1; exec {gltfmat_check} > '{}'",
        report.display()
    ));
    assert_eq!(limited.status.code(), Some(2), "{}", stderr(&limited));
    assert!(
        stderr(&limited).contains("writing the output failed"),
        "{}",
        stderr(&limited)
    );
    let closed = shell(format!("{gltfmat_check} | head -c 10 > /dev/null"));
    assert!(stderr(&closed).is_empty(), "{}", stderr(&closed));
}

/// Every terminating signal a process can catch leaves no temporary behind.
#[cfg(unix)]
#[test]
fn every_catchable_terminating_signal_leaves_no_temporary() {
    let folder = tempfile::tempdir().unwrap();
    let folder = folder.path();
    write_gltf1(folder, "in.gltf", 1_000_000);
    let mut interrupted = 0;
    for signal in [
        libc::SIGUSR1,
        libc::SIGALRM,
        libc::SIGXCPU,
        libc::SIGHUP,
        libc::SIGUSR2,
        libc::SIGQUIT,
    ] {
        if interrupt_mid_write(folder, "out.glb", signal).is_some() {
            interrupted += 1;
            assert_eq!(temporaries(folder), Vec::<String>::new(), "signal {signal}");
        }
    }
    assert!(interrupted > 0, "no run was caught mid-write");
}
