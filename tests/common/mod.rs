//! Helpers shared by the integration tests.
#![allow(dead_code)] // each test binary uses its own subset

use std::path::{Path, PathBuf};

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

/// A corpus folder below `../shared`. Missing, the test is skipped with a loud message, except
/// under CI (`CI` set), where a missing corpus fails.
pub fn shared(relative: &str, test: &str) -> Option<PathBuf> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared")
        .join(relative);
    if path.is_dir() {
        return Some(path);
    }
    let message = format!(
        "*** {test}: ../shared/{relative} is MISSING ({}): this test did not run.",
        path.display()
    );
    assert!(std::env::var_os("CI").is_none(), "\n{message}\n");
    eprintln!("\n{message}\n");
    None
}
