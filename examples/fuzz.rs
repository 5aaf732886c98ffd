//! A mutation fuzzer for `check`, `upgrade`, `compare` and `render` on the stable toolchain
//! (long runs):
//!
//!     cargo run --release --example fuzz -- [--iterations N] [--seed S] [--threads T] [--seeds DIR]…
//!
//! Each input runs through `check` twice (default profile with `--deep`, Khronos profile),
//! `check` as a GLB, and `upgrade` with its own output check; one in eight, written to a
//! folder of planted files, also through `compare` with itself and `render`. Seeds are the
//! files under each `--seeds` folder (`fixtures/` without one). See tests/fuzz_engine.

#[path = "../tests/fuzz_engine/mod.rs"]
mod fuzz_engine;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let flag = |name: &str, default: u64| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1)?.parse().ok())
            .unwrap_or(default)
    };
    let iterations = flag("--iterations", 100_000);
    let seed = flag("--seed", 0x9E37_79B9_7F4A_7C15);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u64);
    let threads = flag("--threads", cores);
    let folders: Vec<std::path::PathBuf> = (args.windows(2))
        .filter(|pair| pair[0] == "--seeds")
        .map(|pair| pair[1].clone().into())
        .collect();
    let started = std::time::Instant::now();
    match fuzz_engine::run_parallel(iterations, seed, threads, &folders) {
        Ok((seeds, executions)) => println!(
            "fuzz: {iterations} inputs ({executions} executions) on {threads} threads, no panic, {:.1} s, {seeds} seeds; each thread's slowest input in target/fuzz-slowest/",
            started.elapsed().as_secs_f64()
        ),
        Err(message) => {
            eprintln!("fuzz: {message}");
            std::process::exit(1);
        }
    }
}
