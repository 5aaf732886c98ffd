//! Bytes in memory: a file's, read whole, and shared pieces of them laid end to end (an
//! upgrade's output, checked without being joined first).

use std::borrow::Cow;
use std::ops::{Deref, Range};
use std::sync::Arc;

/// A file's bytes in memory, read whole. Files are never mapped: a mapped file another
/// process truncates ends the reader with SIGBUS, and one it rewrites changes bytes already
/// checked.
#[derive(Default)]
pub struct Bytes(Vec<u8>);

impl From<Vec<u8>> for Bytes {
    fn from(bytes: Vec<u8>) -> Self {
        Bytes(bytes)
    }
}

impl From<String> for Bytes {
    fn from(text: String) -> Self {
        Bytes(text.into_bytes())
    }
}

impl From<&str> for Bytes {
    fn from(text: &str) -> Self {
        Bytes(text.as_bytes().to_vec())
    }
}

impl From<&[u8]> for Bytes {
    fn from(bytes: &[u8]) -> Self {
        Bytes(bytes.to_vec())
    }
}

impl Deref for Bytes {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        &self.0
    }
}

impl AsRef<[u8]> for Bytes {
    fn as_ref(&self) -> &[u8] {
        self
    }
}

impl std::fmt::Debug for Bytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Bytes({})", self.len())
    }
}

/// A range of shared bytes.
#[derive(Debug, Clone)]
pub struct Piece {
    bytes: Arc<Bytes>,
    range: Range<usize>,
}

impl Piece {
    /// `range` of `bytes` (clamped to them).
    pub fn new(bytes: Arc<Bytes>, range: Range<usize>) -> Self {
        let end = range.end.min(bytes.len());
        let range = range.start.min(end)..end;
        Piece { bytes, range }
    }

    /// All of `bytes`.
    pub fn whole(bytes: impl Into<Bytes>) -> Self {
        let bytes = bytes.into();
        let range = 0..bytes.len();
        Piece {
            bytes: Arc::new(bytes),
            range,
        }
    }

    /// The bytes.
    pub fn as_slice(&self) -> &[u8] {
        &self.bytes[self.range.clone()]
    }
}

/// Bytes as pieces laid end to end.
#[derive(Debug, Clone, Default)]
pub struct Pieces {
    pieces: Vec<Piece>,
    /// Where each piece starts.
    starts: Vec<usize>,
    len: usize,
}

impl Pieces {
    /// The pieces, in order.
    pub fn new(pieces: impl IntoIterator<Item = Piece>) -> Self {
        let mut all = Pieces::default();
        for piece in pieces {
            all.starts.push(all.len);
            all.len += piece.range.len();
            all.pieces.push(piece);
        }
        all
    }

    /// How many bytes there are.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is no byte.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The pieces' bytes, in order.
    pub fn slices(&self) -> impl Iterator<Item = &[u8]> {
        self.pieces.iter().map(Piece::as_slice)
    }

    /// The bytes at `range`: borrowed when one piece holds them, joined otherwise.
    pub fn get(&self, range: Range<usize>) -> Option<Cow<'_, [u8]>> {
        if range.start > range.end || range.end > self.len {
            return None;
        }
        let first = self
            .starts
            .partition_point(|&start| start <= range.start)
            .max(1)
            - 1;
        let Some(piece) = self.pieces.get(first) else {
            return Some(Cow::Borrowed(&[]));
        };
        let within = range.start - self.starts[first]..range.end - self.starts[first];
        if let Some(bytes) = piece.as_slice().get(within) {
            return Some(Cow::Borrowed(bytes));
        }
        let mut joined = Vec::with_capacity(range.len());
        for (piece, &start) in self.pieces[first..].iter().zip(&self.starts[first..]) {
            let bytes = piece.as_slice();
            let from = range.start.saturating_sub(start);
            let to = (range.end - start).min(bytes.len());
            joined.extend_from_slice(&bytes[from..to]);
            if start + bytes.len() >= range.end {
                break;
            }
        }
        Some(Cow::Owned(joined))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_read_as_the_bytes_they_join() {
        let shared = Arc::new(Bytes::from(vec![10, 11, 12, 13, 14]));
        let pieces = Pieces::new([
            Piece::whole(vec![1, 2]),
            Piece::new(Arc::clone(&shared), 1..4),
            Piece::whole(Vec::new()),
            Piece::whole(vec![3]),
        ]);
        let joined = [1, 2, 11, 12, 13, 3];
        assert_eq!(pieces.len(), joined.len());
        for start in 0..=joined.len() {
            for end in start..=joined.len() {
                let got = pieces.get(start..end).expect("inside");
                assert_eq!(&got[..], &joined[start..end], "{start}..{end}");
            }
        }
        assert!(
            matches!(pieces.get(2..5), Some(Cow::Borrowed(_))),
            "one piece is borrowed"
        );
        assert!(pieces.get(5..7).is_none());
        assert_eq!(pieces.slices().collect::<Vec<_>>().concat(), joined);
    }
}
