//! A mutation fuzzer for `check` and `upgrade` on the stable toolchain (long runs):
//!
//!     cargo run --release --example fuzz -- [--iterations N] [--seed S]
//!
//! Each input runs through `check` twice (default profile with `--deep`, Khronos profile),
//! `check` as a GLB, and `upgrade` with its own output check. See tests/fuzz_engine.

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
    let started = std::time::Instant::now();
    match fuzz_engine::run(iterations, seed) {
        Ok((seeds, executions)) => println!(
            "fuzz: {iterations} inputs ({executions} executions of check/upgrade), no panic, {:.1} s, {seeds} seeds",
            started.elapsed().as_secs_f64()
        ),
        Err(message) => {
            eprintln!("fuzz: {message}");
            std::process::exit(1);
        }
    }
}
