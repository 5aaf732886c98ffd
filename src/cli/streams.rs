//! Failures writing stdout and stderr. A report cut short by a full disk must not look like a
//! clean run, so the first failure is kept and makes the exit status 2; a reader that went
//! away on purpose (`gltfmat check … | head`) is not a failure.

use std::io::Write;
use std::process::ExitCode;
use std::sync::Mutex;

static FIRST_FAILURE: Mutex<Option<String>> = Mutex::new(None);

/// Keeps the first failure of a write to a standard stream.
pub fn note(written: std::io::Result<()>) {
    match written {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            let mut first = FIRST_FAILURE.lock().unwrap_or_else(|p| p.into_inner());
            first.get_or_insert_with(|| e.to_string());
        }
        _ => {}
    }
}

/// `status`, or 2 when stdout cannot be flushed or a write failed earlier (the message on
/// stderr, if stderr can still take it).
pub fn status_after_flushing(status: ExitCode) -> ExitCode {
    note(std::io::stdout().lock().flush());
    let failure = FIRST_FAILURE
        .lock()
        .unwrap_or_else(|p| p.into_inner())
        .take();
    match failure {
        Some(message) => {
            let _ = writeln!(
                std::io::stderr(),
                "gltfmat: writing the output failed: {message}"
            );
            ExitCode::from(2)
        }
        None => status,
    }
}
