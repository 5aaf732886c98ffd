//! Terminating signals end the run without leaving temporaries: an upgrade's can be as large
//! as its output. A signal that cannot be caught (SIGKILL) leaves them to the next run into
//! the same folder, which removes every temporary whose creator is gone.

/// Every signal whose default action ends the process and that a handler may catch.
#[cfg(unix)]
const ENDING: &[i32] = &[
    signal_hook::consts::SIGHUP,
    signal_hook::consts::SIGINT,
    signal_hook::consts::SIGQUIT,
    signal_hook::consts::SIGTERM,
    signal_hook::consts::SIGUSR1,
    signal_hook::consts::SIGUSR2,
    signal_hook::consts::SIGALRM,
    signal_hook::consts::SIGVTALRM,
    signal_hook::consts::SIGPROF,
    signal_hook::consts::SIGXCPU,
    signal_hook::consts::SIGIO,
    signal_hook::consts::SIGSYS,
    signal_hook::consts::SIGTRAP,
];

/// On any of [`ENDING`], a thread removes the unplaced temporaries and exits with 128 plus
/// the signal's number, as a shell reports a process the signal ended. SIGXFSZ (a file-size
/// limit reached) is caught and does nothing, so that the write fails with EFBIG and is
/// reported as the failed write it is (exit 2, with a message).
pub fn remove_temporaries_when_ended() {
    #[cfg(unix)]
    {
        let reached = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
        let _ = signal_hook::flag::register(signal_hook::consts::SIGXFSZ, reached);
        let Ok(mut signals) = signal_hook::iterator::Signals::new(ENDING) else {
            return;
        };
        std::thread::spawn(move || {
            if let Some(signal) = signals.forever().next() {
                gltfmat::exit_removing_unfinished(128 + signal);
            }
        });
    }
}
