//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses its own subset

use std::path::{Path, PathBuf};

/// `bytes` as a data URI of media type `mime`.
pub fn data_uri(mime: &str, bytes: &[u8]) -> String {
    use base64::Engine;
    let encoded = base64::engine::general_purpose::STANDARD.encode(bytes);
    format!("data:{mime};base64,{encoded}")
}

/// Runs the gltfmat binary from the repository root (no colour): its exit code and stdout.
pub fn gltfmat(args: &[&str]) -> (i32, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_gltfmat"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NO_COLOR", "1")
        .output()
        .expect("gltfmat runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// CRC-32 (ISO-HDLC), as PNG chunks need.
pub fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

pub fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    let body: Vec<u8> = kind.iter().chain(data).copied().collect();
    out.extend(&body);
    out.extend(crc32(&body).to_be_bytes());
    out
}

/// A corpus folder below `../shared` (or below `$GLTFMAT_SHARED` when set). Missing, the test
/// is skipped with a loud message, except under CI (`CI` set), where a missing corpus fails.
pub fn shared(relative: &str, test: &str) -> Option<PathBuf> {
    let root = std::env::var_os("GLTFMAT_SHARED").map_or_else(
        || Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared"),
        PathBuf::from,
    );
    let path = root.join(relative);
    if path.is_dir() {
        return Some(path);
    }
    let message = format!(
        "*** {test}: ../shared/{relative} is MISSING ({}; `scripts/fetch-corpora.sh` fetches it, or set GLTFMAT_SHARED to the folder holding it): this test did not run.",
        path.display()
    );
    assert!(std::env::var_os("CI").is_none(), "\n{message}\n");
    // Straight to the process's stderr: the test harness captures `eprintln!` of a passing
    // test, and a skip must be seen.
    let _ = std::io::Write::write_all(
        &mut std::io::stderr(),
        format!("\n{message}\n\n").as_bytes(),
    );
    None
}

/// IEC 61966-2-1 decoding, written here from the standard so that tests do not reuse the
/// code they check.
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.04045 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

/// IEC 61966-2-1 encoding.
pub fn linear_to_srgb(linear: f64) -> f64 {
    if linear <= 0.0031308 {
        linear * 12.92
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// A GLB of a JSON chunk and, when given, a BIN chunk (each padded to 4 bytes with spaces).
pub fn glb(json: &[u8], bin: Option<&[u8]>) -> Vec<u8> {
    let chunk = |kind: &[u8; 4], data: &[u8]| {
        let mut padded = data.to_vec();
        padded.resize(data.len().div_ceil(4) * 4, b' ');
        let mut chunk = (padded.len() as u32).to_le_bytes().to_vec();
        chunk.extend(kind);
        chunk.extend(padded);
        chunk
    };
    let mut chunks = chunk(b"JSON", json);
    if let Some(bin) = bin {
        chunks.extend(chunk(b"BIN\0", bin));
    }
    let mut glb = b"glTF\x02\0\0\0".to_vec();
    glb.extend(((12 + chunks.len()) as u32).to_le_bytes());
    glb.extend(chunks);
    glb
}

/// A node matrix the Khronos validator calls NODE_MATRIX_NON_TRS (recorded from it): a rotation
/// and a scale of about 4000, which its single-precision recomposition cannot give back.
pub const LARGE_SCALE_MATRIX: [f64; 16] = [
    912.7795587304951,
    31.039033519971312,
    -3912.4999751812566,
    0.0,
    2790.6016780864275,
    4220.354149104466,
    684.5239358991782,
    0.0,
    3369.4692482889354,
    -2352.4494684724755,
    767.428732204424,
    0.0,
    -1.2636329459581064,
    -112.69371148489978,
    5806.86561226066,
    1.0,
];

/// A 4×4 KTX2 file: the header gltfmat and viewers read (VK_FORMAT_R8G8B8A8_UNORM, not
/// Basis Universal; one level, one layer, one face) and zeros for the rest.
pub fn ktx2() -> Vec<u8> {
    let mut ktx2 = b"\xABKTX 20\xBB\r\n\x1A\n".to_vec();
    for word in [37u32, 1, 4, 4, 0, 0, 1, 1, 0] {
        ktx2.extend(word.to_le_bytes());
    }
    ktx2.extend([0; 64]);
    ktx2
}
