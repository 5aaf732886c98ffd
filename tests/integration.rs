//! The integration tests, one module per file beside this one, built as one test binary.

mod accessor_data;
mod cli;
mod common;
mod conformance;
mod file_safety;
mod fuzz;
mod fuzz_engine;
mod hostile;
mod khronos_parity;
mod ktx2;
mod precision;
mod real_world_upgrade;
mod report_page;
mod rules;
mod spec_gloss_upgrade;
mod upgrade;
mod wrong_types;
