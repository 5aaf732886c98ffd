//! A report's findings cost a few tens of bytes each, whatever the format they are written in:
//! a file of 10^6 findings must stay within twice its size plus 100 MB (issue 49).
//!
//! Heap use is counted by this binary's allocator; this file holds one test, so nothing else
//! allocates while it measures.

use gltfmat::report::{write, Format, Style};
use gltfmat::{check_bytes, CheckOptions, NoResources};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(live, Ordering::Relaxed);
        System.alloc(layout)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() {
            let live = LIVE.fetch_add(new_size - layout.size(), Ordering::Relaxed) + new_size
                - layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        } else {
            LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most heap `work` holds at once beyond what was live before it.
fn peak_of(work: impl FnOnce()) -> usize {
    let before = LIVE.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    work();
    PEAK.load(Ordering::Relaxed) - before
}

/// `nodes` nodes, each with a rotation that is not a unit quaternion and nothing else: three
/// findings each (ROTATION_NON_UNIT, NODE_EMPTY, UNUSED_OBJECT), pretty-printed.
fn asset(nodes: usize) -> Vec<u8> {
    let node = r#"{"rotation": [1, 1, 1, 1]}"#;
    let nodes = vec![node; nodes].join(",\n  ");
    format!("{{\n \"asset\": {{\"version\": \"2.0\"}},\n \"nodes\": [\n  {nodes}\n ]\n}}\n")
        .into_bytes()
}

/// A finding's entry (24 bytes) and pointer (about 20), both in vectors that grow by
/// doubling, and what a writer adds: its place (four bytes, eight more per distinct pointer)
/// and, in the human format, its sort key (sixteen). Each finding of a `Diagnostic` of its
/// own cost 180–530 bytes.
const BYTES_PER_FINDING: usize = 120;

#[test]
fn every_format_holds_a_report_of_many_findings_in_a_few_tens_of_bytes_each() {
    let text = asset(100_000);
    let options = CheckOptions::default();
    let lean = CheckOptions::default().with_max_issues(1);
    // What checking costs without keeping the findings: the document and the passes.
    let checking = peak_of(|| drop(check_bytes("a.gltf", text.clone(), &NoResources, &lean)));
    let formats = [
        (Format::Json, false),
        (Format::Jsonl, false),
        (Format::Sarif, false),
        (Format::Github, true),
        (Format::Human, false),
        (Format::Human, true),
    ];
    let mut over = Vec::new();
    for (format, all_findings) in formats {
        let mut findings = 0;
        let peak = peak_of(|| {
            let report = check_bytes("a.gltf", text.clone(), &NoResources, &options);
            findings = report.diagnostics.len();
            let style = Style::new(false).with_all_findings(all_findings);
            write(format, &[report], &style, &mut std::io::sink()).unwrap();
        });
        assert_eq!(findings, 300_000, "{format:?}");
        let per_finding = peak.saturating_sub(checking) / findings;
        if per_finding > BYTES_PER_FINDING {
            over.push(format!(
                "{format:?} (all findings: {all_findings}): {per_finding} bytes a finding \
                 ({peak} bytes at most, {checking} to check alone)"
            ));
        }
    }
    assert!(over.is_empty(), "{over:#?}");
}
