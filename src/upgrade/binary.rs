//! The upgraded binary buffer as pieces: data that 2.0 can take unchanged stays in the
//! input buffer and is only referenced; everything the converter produces is owned.
//! Writing and checking the output then read each input byte where it lies, and a 100 MB
//! asset never needs a 100 MB buffer of its own.

use crate::document::{Bytes, Piece};
use std::ops::Range;
use std::sync::Arc;

/// Produced data from this size up is a piece of its own (see [`Binary::append_made`]).
const OWN_PIECE_FROM: usize = 1 << 20;

/// The output buffer: repacked data and ranges of the input, laid out in order.
#[derive(Debug, Clone, Default)]
pub struct Binary {
    runs: Vec<Piece>,
    /// The runs' total length, kept as they are added: an asset of 10^5 accessors adds 10^5
    /// runs, and aligning each one must not add them all up again.
    runs_len: usize,
    /// The owned bytes after the last run, still growing.
    tail: Vec<u8>,
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
        self.runs.iter().map(Piece::as_slice).chain(tail)
    }

    /// The bytes as shared pieces, in order (the owned tail is copied unless [`Binary::seal`]
    /// made it a piece already).
    pub fn pieces(&self) -> Vec<Piece> {
        let tail = Some(&self.tail).filter(|t| !t.is_empty());
        let tail = tail.map(|tail| Piece::whole(tail.clone()));
        self.runs.iter().cloned().chain(tail).collect()
    }

    /// Makes the owned tail a piece of its own: nothing more is appended.
    pub fn seal(&mut self) {
        self.close_tail();
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
        self.close_tail();
        self.runs_len += range.len();
        self.runs.push(Piece::new(Arc::clone(buffer), range));
    }

    /// Appends `length` bytes that `make` writes (they start as zeros), returning what it
    /// returns. Large data gets a piece of its own, made fresh: appended to the owned tail
    /// it would first be zeroed on one core, and the tail's growth would copy what came
    /// before; fresh zeros cost nothing until `make` writes them, on as many cores as it
    /// runs on.
    pub fn append_made<R>(&mut self, length: usize, make: impl FnOnce(&mut [u8]) -> R) -> R {
        if length < OWN_PIECE_FROM {
            let start = self.tail.len();
            self.tail.resize(start + length, 0);
            return make(&mut self.tail[start..]);
        }
        self.close_tail();
        let mut bytes = vec![0; length];
        let made = make(&mut bytes);
        self.runs_len += length;
        self.runs.push(Piece::whole(bytes));
        made
    }

    /// The owned bytes at the end, for appending produced data.
    pub fn owned(&mut self) -> &mut Vec<u8> {
        &mut self.tail
    }

    fn close_tail(&mut self) {
        if !self.tail.is_empty() {
            self.runs_len += self.tail.len();
            self.runs.push(Piece::whole(std::mem::take(&mut self.tail)));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_concatenate_in_order_and_align_with_zeros() {
        let input = Arc::new(vec![10, 11, 12, 13, 14].into());
        let mut binary = Binary::default();
        binary.owned().push(1);
        assert_eq!(binary.align(), 4);
        binary.share(&input, 1..4);
        assert_eq!(binary.align(), 8);
        binary.owned().push(2);
        assert_eq!(binary.to_vec(), vec![1, 0, 0, 0, 11, 12, 13, 0, 2]);
        assert_eq!(binary.len(), 9);
        assert_eq!(binary.len(), binary.runs().map(<[u8]>::len).sum::<usize>());
        let pieces = |b: &Binary| {
            b.pieces()
                .iter()
                .map(|p| p.as_slice().to_vec())
                .collect::<Vec<_>>()
                .concat()
        };
        assert_eq!(pieces(&binary), binary.to_vec());
        binary.seal();
        assert_eq!(pieces(&binary), binary.to_vec(), "sealing keeps the bytes");
        assert_eq!(binary.len(), 9);
    }

    #[test]
    fn made_data_follows_in_order_whether_small_or_large() {
        let mut binary = Binary::default();
        binary.owned().push(1);
        let small = binary.append_made(3, |b| {
            b.copy_from_slice(&[2, 3, 4]);
            b.len()
        });
        let large = binary.append_made(OWN_PIECE_FROM, |b| {
            assert!(b.iter().all(|&x| x == 0), "made data starts as zeros");
            b[0] = 5;
            b.len()
        });
        binary.owned().push(6);
        assert_eq!((small, large), (3, OWN_PIECE_FROM));
        let mut expected = vec![1, 2, 3, 4, 5];
        expected.resize(4 + OWN_PIECE_FROM, 0);
        expected.push(6);
        assert_eq!(binary.to_vec(), expected);
        assert_eq!(binary.len(), expected.len());
        assert_eq!(
            binary.runs().count(),
            3,
            "the large data is a run of its own"
        );
    }
}
