//! A short, bounded fuzz run in every `cargo test`: mutated fixtures through check,
//! upgrade, compare and render must never panic. Long runs: `cargo run --release --example fuzz`.

mod fuzz_engine;

#[test]
fn mutated_fixtures_never_panic() {
    if let Err(message) = fuzz_engine::run_parallel(1500, 0x5EED, 1, &[]) {
        panic!("{message}");
    }
}
