//! The findings of one report, held compactly: a file with 10^6 findings must cost the
//! report a few tens of bytes per finding, not a [`Diagnostic`] and its pointer's own string
//! each (about 140 bytes).
//!
//! Each finding is a fixed-size entry; its JSON pointer (and its message, when the message
//! was made for it) sits in one shared text, and codes and fixed messages are held once.

use super::{Code, Diagnostic, Location, Severity};
use std::collections::HashMap;
use std::fmt;

/// The findings of one report, in the order they were kept.
#[derive(Clone, Default)]
pub struct Findings {
    entries: Vec<Entry>,
    /// Every finding's pointer, each followed by its message when that message is its own.
    text: String,
    codes: Vec<Code>,
    code_ids: HashMap<Code, u16>,
    fixed_messages: Vec<&'static str>,
    /// Fixed messages by where their text lies: the same literal is one message.
    fixed_ids: HashMap<(usize, usize), u32>,
    /// The findings placed at a byte offset (GLB container findings), by index.
    offsets: Vec<(usize, u64)>,
    /// The few findings that carry a byte offset into the JSON text (syntax errors), by index.
    span_hints: Vec<(usize, usize)>,
}

/// One finding: where its text starts, what it is, and how to read its message.
#[derive(Clone, Copy)]
struct Entry {
    /// Where its pointer (or, placed at an offset, its own message) starts in `text`.
    start: u64,
    pointer_len: u32,
    /// A fixed message's index with `FIXED` set, otherwise the length of its own message,
    /// which follows its pointer.
    message: u32,
    code: u16,
    severity: Severity,
}

/// `Entry::pointer_len` of a finding placed at a byte offset.
const OFFSET: u32 = u32::MAX;
/// The bit of `Entry::message` that marks a fixed message.
const FIXED: u32 = 1 << 31;

/// One finding of [`Findings`], borrowed from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Finding<'f> {
    /// Where it lies among its report's findings.
    pub index: usize,
    /// What was found.
    pub code: Code,
    /// How much it matters, as the report decided it.
    pub severity: Severity,
    /// A sentence for a person.
    pub message: &'f str,
    /// Where it was found.
    pub location: Place<'f>,
    /// A byte offset into the JSON text when the pointer cannot say it (syntax errors).
    pub span_hint: Option<usize>,
}

/// Where a [`Finding`] points: [`Location`], borrowed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Place<'f> {
    /// An RFC 6901 JSON pointer into the glTF JSON (`""` is the root).
    Pointer(&'f str),
    /// A byte offset in the file (GLB container findings).
    Offset(u64),
}

impl<'f> Finding<'f> {
    /// The JSON pointer, when the location is one.
    pub fn pointer(&self) -> Option<&'f str> {
        match self.location {
            Place::Pointer(p) => Some(p),
            Place::Offset(_) => None,
        }
    }
}

impl Findings {
    /// No findings.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many findings there are.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Adds one finding at the end.
    pub fn push(&mut self, diagnostic: Diagnostic) {
        let index = self.entries.len();
        let code = self.code_id(diagnostic.code);
        let start = self.text.len() as u64;
        let pointer_len = match &diagnostic.location {
            Location::Pointer(pointer) => {
                self.text.push_str(pointer);
                length(pointer)
            }
            Location::Offset(offset) => {
                self.offsets.push((index, *offset));
                OFFSET
            }
        };
        let message = match diagnostic.message {
            std::borrow::Cow::Borrowed(fixed) => FIXED | self.fixed_id(fixed),
            std::borrow::Cow::Owned(own) => {
                let own = within(&own, FIXED as usize - 1);
                self.text.push_str(own);
                length(own)
            }
        };
        if let Some(hint) = diagnostic.span_hint {
            self.span_hints.push((index, hint));
        }
        self.entries.push(Entry {
            start,
            pointer_len,
            message,
            code,
            severity: diagnostic.severity,
        });
    }

    /// The finding at `index`.
    pub fn get(&self, index: usize) -> Option<Finding<'_>> {
        let entry = self.entries.get(index)?;
        let text = |from: u64, len: u32| &self.text[from as usize..][..len as usize];
        let (location, pointer_len) = match entry.pointer_len {
            OFFSET => (Place::Offset(side(&self.offsets, index)?), 0),
            len => (Place::Pointer(text(entry.start, len)), len),
        };
        let message = if entry.message & FIXED != 0 {
            self.fixed_messages[(entry.message & !FIXED) as usize]
        } else {
            text(entry.start + u64::from(pointer_len), entry.message)
        };
        Some(Finding {
            index,
            code: self.codes[usize::from(entry.code)],
            severity: entry.severity,
            message,
            location,
            span_hint: side(&self.span_hints, index),
        })
    }

    /// The JSON pointer of the finding at `index`, when it has one (read without the rest
    /// of the finding: reports sort and search findings by it).
    pub fn pointer_at(&self, index: usize) -> Option<&str> {
        let entry = self.entries.get(index)?;
        let start = entry.start as usize;
        (entry.pointer_len != OFFSET).then(|| &self.text[start..start + entry.pointer_len as usize])
    }

    /// The first finding.
    pub fn first(&self) -> Option<Finding<'_>> {
        self.get(0)
    }

    /// Every finding, in order.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = Finding<'_>> + ExactSizeIterator + '_ {
        (0..self.len()).map(|i| self.get(i).expect("within the entries"))
    }

    fn code_id(&mut self, code: Code) -> u16 {
        if let Some(&id) = self.code_ids.get(&code) {
            return id;
        }
        // Codes are constants: a report cannot name more than the registry holds.
        let id = u16::try_from(self.codes.len()).expect("fewer codes than 2^16");
        self.codes.push(code);
        self.code_ids.insert(code, id);
        id
    }

    fn fixed_id(&mut self, message: &'static str) -> u32 {
        let key = (message.as_ptr() as usize, message.len());
        if let Some(&id) = self.fixed_ids.get(&key) {
            return id;
        }
        let id = self.fixed_messages.len() as u32;
        self.fixed_messages.push(message);
        self.fixed_ids.insert(key, id);
        id
    }
}

/// The value kept beside the finding at `index`, in a list kept in index order.
fn side<T: Copy>(list: &[(usize, T)], index: usize) -> Option<T> {
    let at = list.binary_search_by_key(&index, |(i, _)| *i).ok()?;
    Some(list[at].1)
}

/// A text's length as an entry holds it (pointers and messages are far below 4 GiB: the
/// input they were made from is read under a budget).
fn length(text: &str) -> u32 {
    u32::try_from(text.len()).unwrap_or(u32::MAX - 1)
}

/// `text` cut to at most `limit` bytes at a character boundary.
fn within(text: &str, limit: usize) -> &str {
    if text.len() <= limit {
        return text;
    }
    let mut end = limit;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    &text[..end]
}

impl fmt::Debug for Findings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

impl FromIterator<Diagnostic> for Findings {
    fn from_iter<T: IntoIterator<Item = Diagnostic>>(found: T) -> Self {
        let mut findings = Findings::new();
        found.into_iter().for_each(|d| findings.push(d));
        findings
    }
}

impl<'f> IntoIterator for &'f Findings {
    type Item = Finding<'f>;
    type IntoIter = Box<dyn Iterator<Item = Finding<'f>> + 'f>;

    fn into_iter(self) -> Self::IntoIter {
        Box::new(self.iter())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::khronos;

    /// Every kind of finding reads back as it was kept: pointers and offsets, fixed and own
    /// messages, with and without a span hint, in order.
    #[test]
    fn findings_read_back_as_they_were_kept() {
        let own = |text: &str| std::borrow::Cow::Owned(text.to_string());
        let mut hinted = Diagnostic::at(khronos::TYPE_MISMATCH, "", own("made for it"));
        hinted.span_hint = Some(17);
        let kept = vec![
            Diagnostic::at(khronos::TYPE_MISMATCH, "/nodes/0", "fixed"),
            Diagnostic::new(
                khronos::TYPE_MISMATCH,
                Location::Offset(12),
                own("at a byte"),
            ),
            hinted,
            Diagnostic::new(khronos::UNUSED_OBJECT, Location::Offset(40), "fixed"),
            Diagnostic::at(khronos::UNUSED_OBJECT, "/a~1b/0", own("")),
        ];
        let findings: Findings = kept.iter().cloned().collect();
        assert_eq!(findings.len(), kept.len());
        for (i, (finding, diagnostic)) in findings.iter().zip(&kept).enumerate() {
            let place = match &diagnostic.location {
                Location::Pointer(p) => Place::Pointer(p),
                Location::Offset(o) => Place::Offset(*o),
            };
            let expected = Finding {
                index: i,
                code: diagnostic.code,
                severity: diagnostic.severity,
                message: &diagnostic.message,
                location: place,
                span_hint: diagnostic.span_hint,
            };
            assert_eq!(finding, expected);
            assert_eq!(findings.pointer_at(i), diagnostic.pointer());
        }
    }
}
