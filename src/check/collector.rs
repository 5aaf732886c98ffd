//! The findings of one check as they are made: the user's filters applied (ignore, only,
//! severity overrides), every finding counted per severity, and, with `max_issues`, only the
//! first N kept in report order (errors first, then by emission), so that a file with 10^6
//! findings costs the memory of N; with `lowest_kept`, the less severe ones are only counted.
//! It also hands each data pass its [`WalkBudget`]: how many findings the pass's walks over
//! accessor data may list before the collector sees them.

use super::CheckOptions;
use crate::diagnostic::{Diagnostic, Findings, Severity, Sink};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

pub(crate) struct Collector<'o> {
    options: &'o CheckOptions,
    /// The kept findings.
    kept: Kept,
    counts: [usize; 4],
    emitted: usize,
    truncated: bool,
}

/// Without a limit every finding is kept as it comes, compactly and already in emission order
/// (no ranks, no sort and its scratch: a report of 10^6 findings costs their own memory
/// only); with one, a max-heap whose top is the one to drop first.
enum Kept {
    All(Box<Findings>),
    Best(BinaryHeap<Ranked>),
}

/// A finding with its place in report order: severity, then emission.
struct Ranked(Diagnostic, usize);

impl Ranked {
    fn key(&self) -> (Severity, usize) {
        (self.0.severity, self.1)
    }
}

impl PartialEq for Ranked {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for Ranked {}

impl PartialOrd for Ranked {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ranked {
    fn cmp(&self, other: &Self) -> Ordering {
        self.key().cmp(&other.key())
    }
}

impl<'o> Collector<'o> {
    pub(crate) fn new(options: &'o CheckOptions) -> Self {
        let kept = match options.max_issues {
            0 => Kept::All(Box::default()),
            _ => Kept::Best(BinaryHeap::new()),
        };
        Collector {
            options,
            kept,
            counts: [0; 4],
            emitted: 0,
            truncated: false,
        }
    }

    /// The kept findings (in emission order, or in report order when some were dropped),
    /// the full per-severity counts, and whether some were dropped.
    pub(crate) fn finish(self) -> (Findings, [usize; 4], bool) {
        let kept = match self.kept {
            Kept::All(all) => *all,
            Kept::Best(best) => {
                // Ranks are unique, so the unstable sort is the order, without scratch memory.
                let mut best = best.into_vec();
                if self.truncated {
                    best.sort_unstable();
                } else {
                    best.sort_unstable_by_key(|r| r.1);
                }
                best.into_iter().map(|r| r.0).collect()
            }
        };
        (kept, self.counts, self.truncated)
    }

    fn wanted(&self, code: &str) -> bool {
        let listed = |list: &[String]| list.iter().any(|c| c.eq_ignore_ascii_case(code));
        !listed(&self.options.ignore)
            && (self.options.only.is_empty() || listed(&self.options.only))
    }
}

/// At most this many findings of one walk over an accessor's (or a skinned primitive's) data
/// are listed: a corrupt buffer of millions of elements must not turn into millions of
/// diagnostics in memory. The rest are counted. Real assets stay below it (an exporter's 10^3
/// slightly non-normalised weights are all listed, as the Khronos validator lists them).
const LISTED_PER_WALK: usize = 10_000;

/// At most this many findings are listed by one data pass over all its walks: accessors that
/// alias one corrupt view (10^3 accessors × 10^4 elements in a 300 KB file) must not add up
/// to 10^7 diagnostics either.
const LISTED_PER_PASS: usize = 100_000;

/// What a data pass may still list, handed out so that the report does not depend on which
/// walk finishes first: each walk of a batch may list an equal share of what is left.
pub(crate) struct WalkBudget {
    left: usize,
    per_walk: usize,
}

impl WalkBudget {
    /// How many findings each of `walks` walks run together may list.
    pub(crate) fn share(&self, walks: usize) -> usize {
        self.per_walk.min(self.left / walks.max(1))
    }

    /// Takes what a walk listed from the budget.
    pub(crate) fn spend(&mut self, listed: usize) {
        self.left = self.left.saturating_sub(listed);
    }
}

impl Collector<'_> {
    /// The budget of one data pass: [`LISTED_PER_PASS`] and [`LISTED_PER_WALK`] when the
    /// profile caps data findings, otherwise every finding (`max_issues` still holds).
    pub(crate) fn walk_budget(&self) -> WalkBudget {
        match self.options.profile.caps_data_findings() {
            true => WalkBudget {
                left: LISTED_PER_PASS,
                per_walk: LISTED_PER_WALK,
            },
            false => WalkBudget {
                left: usize::MAX,
                per_walk: usize::MAX,
            },
        }
    }

    /// The severity a finding is reported with, or `None` when the user's filters drop it.
    /// The one place a finding's severity is decided: the user's override, else its code's.
    fn severity(&self, diagnostic: &Diagnostic) -> Option<Severity> {
        let code = diagnostic.code.name();
        if !self.wanted(code) {
            return None;
        }
        let overridden =
            (self.options.severity_overrides.iter()).find(|(c, _)| c.eq_ignore_ascii_case(code));
        Some(overridden.map_or(diagnostic.code.default_severity(), |(_, s)| *s))
    }

    /// Counts `n` findings like `diagnostic` that are not listed.
    pub(crate) fn count_unlisted(&mut self, diagnostic: &Diagnostic, n: u64) {
        if let Some(severity) = self.severity(diagnostic) {
            let count = &mut self.counts[severity as usize];
            *count = count.saturating_add(usize::try_from(n).unwrap_or(usize::MAX));
        }
    }
}

impl Sink for Collector<'_> {
    fn push(&mut self, mut diagnostic: Diagnostic) {
        let Some(severity) = self.severity(&diagnostic) else {
            return;
        };
        diagnostic.severity = severity;
        self.counts[diagnostic.severity as usize] += 1;
        if (self.options.lowest_kept).is_some_and(|lowest| diagnostic.severity > lowest) {
            return;
        }
        let heap = match &mut self.kept {
            Kept::All(all) => return all.push(diagnostic),
            Kept::Best(heap) => heap,
        };
        let ranked = Ranked(diagnostic, self.emitted);
        self.emitted += 1;
        if heap.len() < self.options.max_issues {
            heap.push(ranked);
            return;
        }
        self.truncated = true;
        if heap.peek().is_some_and(|worst| ranked < *worst) {
            heap.pop();
            heap.push(ranked);
        }
    }
}

impl Extend<Diagnostic> for Collector<'_> {
    fn extend<T: IntoIterator<Item = Diagnostic>>(&mut self, found: T) {
        for diagnostic in found {
            self.push(diagnostic);
        }
    }
}
