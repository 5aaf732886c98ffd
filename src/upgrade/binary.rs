//! The upgraded binary buffer as runs of bytes: data that 2.0 can take unchanged stays in
//! the input buffer and is only referenced; everything the converter
//! produces is owned. Writing the output then copies each input byte once, file to file,
//! and a 100 MB asset never needs a 100 MB buffer in memory.

use crate::document::Bytes;
use std::ops::Range;
use std::sync::Arc;

/// The output buffer: repacked data and runs borrowed from the input, laid out in order.
#[derive(Debug, Clone, Default)]
pub struct Binary {
    runs: Vec<Run>,
    /// The runs' total length, kept as they are added: an asset of 10^5 accessors adds 10^5
    /// runs, and aligning each one must not add them all up again.
    runs_len: usize,
    /// The owned bytes after the last run, still growing.
    tail: Vec<u8>,
}

#[derive(Debug, Clone)]
enum Run {
    Shared(Arc<Bytes>, Range<usize>),
    Owned(Vec<u8>),
}

impl Run {
    fn bytes(&self) -> &[u8] {
        match self {
            Run::Shared(bytes, range) => &bytes[range.clone()],
            Run::Owned(bytes) => bytes,
        }
    }
}

impl Binary {
    /// Its length in bytes.
    pub fn len(&self) -> usize {
        self.runs_len + self.tail.len()
    }

    /// Whether it holds nothing.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The bytes, run by run, in order.
    pub fn runs(&self) -> impl Iterator<Item = &[u8]> {
        let tail = Some(self.tail.as_slice()).filter(|t| !t.is_empty());
        self.runs.iter().map(Run::bytes).chain(tail)
    }

    /// The whole buffer in one piece (a copy).
    pub fn to_vec(&self) -> Vec<u8> {
        self.runs().collect::<Vec<_>>().concat()
    }

    /// Pads to a multiple of 4 bytes; returns the length.
    pub fn align(&mut self) -> usize {
        let length = self.len();
        let padding = length.next_multiple_of(4) - length;
        self.tail.resize(self.tail.len() + padding, 0);
        length + padding
    }

    /// Appends a range of an input buffer by reference.
    pub fn share(&mut self, buffer: &Arc<Bytes>, range: Range<usize>) {
        if !self.tail.is_empty() {
            self.runs_len += self.tail.len();
            self.runs.push(Run::Owned(std::mem::take(&mut self.tail)));
        }
        self.runs_len += range.len();
        self.runs.push(Run::Shared(Arc::clone(buffer), range));
    }

    /// The owned bytes at the end, for appending produced data.
    pub fn owned(&mut self) -> &mut Vec<u8> {
        &mut self.tail
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_concatenate_in_order_and_align_with_zeros() {
        let input = Arc::new(Bytes::from(vec![10, 11, 12, 13, 14]));
        let mut binary = Binary::default();
        binary.owned().push(1);
        assert_eq!(binary.align(), 4);
        binary.share(&input, 1..4);
        assert_eq!(binary.align(), 8);
        binary.owned().push(2);
        assert_eq!(binary.to_vec(), vec![1, 0, 0, 0, 11, 12, 13, 0, 2]);
        assert_eq!(binary.len(), 9);
        assert_eq!(binary.len(), binary.runs().map(<[u8]>::len).sum::<usize>());
    }
}
