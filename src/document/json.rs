//! JSON text → the compact [`Tree`](super::tree::Tree), plus source locations found on demand.
//!
//! Values are parsed once with serde_json (fast, depth-limited, never overflows the stack).
//! Spans are *not* stored per node: a pointer is resolved back to a byte range only when a
//! diagnostic is printed, by [`locate_all`] (every diagnostic of a report in one pass), a
//! small scanner over the original text.
//! The same scanner reports duplicate object keys, which serde_json silently collapses.

use std::borrow::Cow;
use std::hash::BuildHasher;

/// A JSON syntax error with its 1-based position.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SyntaxError {
    pub message: String,
    pub offset: usize,
}

/// Parses JSON text into a compact tree. A UTF-8 byte-order mark is an error, as in the
/// glTF spec.
pub(crate) fn parse(bytes: &[u8]) -> Result<super::Tree, SyntaxError> {
    parse_with(bytes, super::Tree::parse)
}

fn parse_with<R>(
    bytes: &[u8],
    parse: fn(&[u8]) -> serde_json::Result<R>,
) -> Result<R, SyntaxError> {
    if bytes.starts_with(&[0xEF, 0xBB, 0xBF]) {
        return Err(SyntaxError {
            message: "BOM found at the beginning of UTF-8 stream".into(),
            offset: 0,
        });
    }
    let parsed = match parse(bytes) {
        // A string escaping half a UTF-16 surrogate pair is valid JSON to the Khronos
        // validator (a string of UTF-16 units); serde_json refuses it. Each such escape is
        // read as U+FFFD, six characters for six, so every offset stays where it was.
        Err(e)
            if ["surrogate", "unicode", "hex escape"]
                .iter()
                .any(|m| e.to_string().contains(m)) =>
        {
            match lone_surrogates_replaced(bytes) {
                Some(patched) => parse(&patched),
                None => Err(e),
            }
        }
        parsed => parsed,
    };
    parsed.map_err(|e| {
        let offset = offset_of(bytes, e.line(), e.column());
        // The place is the offset's, printed once by whoever reports it.
        let message = e.to_string();
        let suffix = format!(" at line {} column {}", e.line(), e.column());
        SyntaxError {
            message: message
                .strip_suffix(&suffix)
                .unwrap_or(&message)
                .to_string(),
            offset,
        }
    })
}

/// `text` with every `\uXXXX` escape of a UTF-16 surrogate that is not half of a pair
/// replaced by `\ufffd`; `None` when there is none.
fn lone_surrogates_replaced(text: &[u8]) -> Option<Vec<u8>> {
    let unit = |at: usize| -> Option<u16> {
        let digits = text.get(at..at + 6).filter(|e| e.starts_with(b"\\u"))?;
        u16::from_str_radix(std::str::from_utf8(&digits[2..]).ok()?, 16).ok()
    };
    let (mut patched, mut changed) = (text.to_vec(), false);
    let (mut at, mut in_string) = (0, false);
    while at < text.len() {
        match text[at] {
            b'"' => in_string = !in_string,
            b'\\' if in_string => {
                let low_follows = unit(at + 6).is_some_and(|u| (0xDC00..=0xDFFF).contains(&u));
                match unit(at) {
                    // A whole pair: both escapes are kept.
                    Some(0xD800..=0xDBFF) if low_follows => {
                        at += 12;
                        continue;
                    }
                    Some(0xD800..=0xDFFF) => {
                        patched[at..at + 6].copy_from_slice(b"\\ufffd");
                        changed = true;
                    }
                    _ => {}
                }
                // The escaped character is skipped with its backslash.
                at += 2;
                continue;
            }
            _ => {}
        }
        at += 1;
    }
    changed.then_some(patched)
}

fn offset_of(bytes: &[u8], line: usize, column: usize) -> usize {
    let mut current = 1;
    let mut start = 0;
    for (i, b) in bytes.iter().enumerate() {
        if current == line {
            break;
        }
        if *b == b'\n' {
            current += 1;
            start = i + 1;
        }
    }
    (start + column.saturating_sub(1)).min(bytes.len())
}

/// Unescapes one token of a JSON pointer (borrowed when it has no escape: a pointer is
/// resolved on every lookup).
pub(crate) fn unescape_token(token: &str) -> Cow<'_, str> {
    if token.contains('~') {
        Cow::Owned(token.replace("~1", "/").replace("~0", "~"))
    } else {
        Cow::Borrowed(token)
    }
}

/// Escapes one token for use in a JSON pointer (borrowed when nothing needs escaping).
pub(crate) fn escape_token(token: &str) -> Cow<'_, str> {
    if token.contains(['~', '/']) {
        Cow::Owned(token.replace('~', "~0").replace('/', "~1"))
    } else {
        Cow::Borrowed(token)
    }
}

/// Byte range of the value each pointer of `sorted` names (sorted and each once), in its
/// order; for an object member the range starts at its key, so a snippet shows the property
/// name (of a repeated key, the last one, whose value parsers keep). A pointer that names
/// nothing has `None`. See [`locate_each`].
pub(crate) fn locate_all(text: &[u8], sorted: &[&str]) -> Vec<Option<std::ops::Range<usize>>> {
    let mut found = vec![None; sorted.len()];
    locate_each(
        text,
        sorted.len(),
        |i| sorted[i],
        |i, range| found[i] = Some(range),
    );
    found
}

/// Calls `found(i, range)` for each of `count` pointers (the `i`th is `pointer(i)`, in sorted
/// order, each once) that names a value of `text`, with the byte range of that value. All
/// are found in one pass over the text, skipping the subtrees no pointer enters, so the cost
/// is one scan however many findings are located, and no memory per pointer.
pub(crate) fn locate_each<'p>(
    text: &[u8],
    count: usize,
    pointer: impl Fn(usize) -> &'p str,
    mut found: impl FnMut(usize, std::ops::Range<usize>),
) {
    let mut scanner = Scanner { text, pos: 0 };
    scanner.skip_ws();
    let start = scanner.pos;
    // Malformed text ends the walk; what was found before stays found.
    let mut path = String::new();
    let wanted = Wanted { pointer: &pointer };
    if (scanner.locate_in(&wanted, 0..count, &mut path, &mut found)).is_some() {
        // The root is named by "" and, as the report prints it, "/".
        for root in ["", "/"] {
            if let Some(at) = wanted.exactly(root, &(0..count)) {
                found(at, start..scanner.pos);
            }
        }
    }
}

/// The pointers being located, in sorted order: those below a path are the ones between the
/// path followed by '/' and the path followed by '0' (the byte after '/').
struct Wanted<'w, 'p> {
    pointer: &'w dyn Fn(usize) -> &'p str,
}

impl Wanted<'_, '_> {
    /// Where in `within` the first pointer not before `path` is.
    fn first_from(&self, path: &str, within: &std::ops::Range<usize>) -> usize {
        let (mut low, mut high) = (within.start, within.end);
        while low < high {
            let middle = low + (high - low) / 2;
            if (self.pointer)(middle) < path {
                low = middle + 1;
            } else {
                high = middle;
            }
        }
        low
    }

    /// The place of `path` itself among the pointers of `within`.
    fn exactly(&self, path: &str, within: &std::ops::Range<usize>) -> Option<usize> {
        let at = self.first_from(path, within);
        (at < within.end && (self.pointer)(at) == path).then_some(at)
    }

    /// The pointers of `within` that lie below `path` (start with it and a '/').
    fn below(&self, path: &mut String, within: &std::ops::Range<usize>) -> std::ops::Range<usize> {
        path.push('/');
        let start = self.first_from(path, within);
        path.pop();
        path.push('0');
        let end = self.first_from(path, &(start..within.end));
        path.pop();
        start..end
    }
}

/// 1-based line and column of byte offsets in one text, from an index built once: the number
/// of line breaks and of characters before every 256-byte boundary. A line or a column then
/// costs at most 256 bytes of counting (in a large single-line file a report may place 10^6
/// findings), and the index is a thirty-second of the text, however many lines it has.
pub(crate) struct LineIndex<'t> {
    text: &'t [u8],
    /// Fit in 32 bits: no text read is longer (`file::MAX_FILE_BYTES`).
    breaks_before_block: Vec<u32>,
    chars_before_block: Vec<u32>,
}

const BLOCK: usize = 1 << 8;

impl<'t> LineIndex<'t> {
    /// Indexes `text`.
    pub(crate) fn new(text: &'t [u8]) -> Self {
        let blocks = text.len() / BLOCK + 2;
        let mut breaks_before_block = Vec::with_capacity(blocks);
        let mut chars_before_block = Vec::with_capacity(blocks);
        let (mut breaks, mut chars) = (0u32, 0u32);
        for block in text.chunks(BLOCK) {
            breaks_before_block.push(breaks);
            chars_before_block.push(chars);
            breaks = breaks.saturating_add(count_breaks(block) as u32);
            chars = chars.saturating_add(count_chars(block) as u32);
        }
        breaks_before_block.push(breaks);
        chars_before_block.push(chars);
        LineIndex {
            text,
            breaks_before_block,
            chars_before_block,
        }
    }

    /// The line and column (in characters) of `offset`.
    pub(crate) fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let block = offset / BLOCK;
        let line = self.breaks_before_block[block] as usize
            + count_breaks(&self.text[block * BLOCK..offset])
            + 1;
        let line_start = self.line_start(line);
        (
            line,
            self.chars_before(offset) - self.chars_before(line_start) + 1,
        )
    }

    /// The byte offset at which line `line` (1-based) starts: just after the text's
    /// (`line` − 1)th line break (the end of the text past the last line).
    pub(crate) fn line_start(&self, line: usize) -> usize {
        let Some(nth) = line.checked_sub(1).filter(|&n| n > 0) else {
            return 0;
        };
        let breaks = self.breaks_before_block.last().copied().unwrap_or(0) as usize;
        if nth > breaks {
            return self.text.len();
        }
        // The last block with fewer breaks before it than `nth` holds the `nth` break.
        let before = self
            .breaks_before_block
            .partition_point(|&b| (b as usize) < nth);
        let Some(block) = before.checked_sub(1) else {
            return 0;
        };
        let wanted = nth - self.breaks_before_block[block] as usize;
        let start = block * BLOCK;
        let end = (start + BLOCK).min(self.text.len());
        (memchr::memchr_iter(b'\n', &self.text[start..end]).nth(wanted - 1))
            .map_or(self.text.len(), |i| start + i + 1)
    }

    /// The bytes of line `line` (1-based), without its line break.
    pub(crate) fn line(&self, line: usize) -> &'t [u8] {
        let start = self.line_start(line);
        let next = self.line_start(line + 1);
        let end = if next > start && self.text.get(next - 1) == Some(&b'\n') {
            next - 1
        } else {
            next
        };
        &self.text[start..end.max(start)]
    }

    fn chars_before(&self, offset: usize) -> usize {
        let block = offset / BLOCK;
        self.chars_before_block[block] as usize + count_chars(&self.text[block * BLOCK..offset])
    }
}

/// Characters in UTF-8 text: every byte that does not continue a character.
fn count_chars(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b & 0xC0 != 0x80).count()
}

fn count_breaks(bytes: &[u8]) -> usize {
    memchr::memchr_iter(b'\n', bytes).count()
}

/// A key that occurs more than once in its object: its pointer, where its first repeat
/// starts in the text, and how many times it occurs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DuplicateKey {
    pub pointer: String,
    pub offset: usize,
    pub occurrences: usize,
}

/// An open container of [`duplicate_keys`]'s walk.
struct Frame<'t> {
    /// The token naming this container inside its parent.
    token: Cow<'t, str>,
    /// Keys seen so far (objects), or `None` for arrays.
    keys: Option<KeysSeen>,
    /// Next element index (arrays).
    next_index: usize,
}

/// The JSON pointer of the innermost open container.
fn pointer_of(stack: &[Frame]) -> String {
    stack
        .iter()
        .skip(1)
        .map(|f| format!("/{}", escape_token(&f.token)))
        .collect()
}

/// The token naming the next value in the innermost open container (the key read before
/// it, or its index), counting it.
fn child_token<'t>(stack: &mut [Frame<'t>], pending: &mut Option<Cow<'t, str>>) -> Cow<'t, str> {
    match stack.last_mut() {
        Some(Frame { keys: Some(_), .. }) => pending.take().unwrap_or_default(),
        Some(frame) => {
            frame.next_index += 1;
            Cow::Owned((frame.next_index - 1).to_string())
        }
        None => Cow::Borrowed(""),
    }
}

/// Object keys that occur more than once in their object, one entry per key and object
/// however often it repeats (an object of 10^6 copies of one key is one finding, not 10^6),
/// in the order of their first repeats.
///
/// Each open container keeps only its own token, so memory stays linear in the nesting depth;
/// a pointer is built only for a duplicate.
pub(crate) fn duplicate_keys(text: &[u8]) -> Vec<DuplicateKey> {
    let mut found = Vec::new();
    let mut stack: Vec<Frame> = Vec::new();
    let mut scanner = Scanner { text, pos: 0 };
    let mut pending_key: Option<Cow<str>> = None;
    while scanner.pos < text.len() {
        scanner.skip_ws();
        let Some(b) = scanner.peek() else { break };
        match b {
            b'{' | b'[' => {
                let token = child_token(&mut stack, &mut pending_key);
                let keys = (b == b'{').then(Default::default);
                stack.push(Frame {
                    token,
                    keys,
                    next_index: 0,
                });
                scanner.pos += 1;
            }
            b'}' | b']' => {
                stack.pop();
                scanner.pos += 1;
            }
            b',' | b':' => scanner.pos += 1,
            b'"' => {
                let start = scanner.pos;
                let Some(s) = scanner.read_string() else {
                    break;
                };
                scanner.skip_ws();
                let in_object = matches!(stack.last(), Some(Frame { keys: Some(_), .. }));
                if scanner.peek() == Some(b':') && in_object && pending_key.is_none() {
                    // A hash table: an object with 10^5 keys costs 10^5 lookups, not 10^10.
                    let next = found.len();
                    let keys = stack.last_mut().and_then(|f| f.keys.as_mut());
                    match keys.map(|keys| keys.insert(text, &s, start, next)) {
                        Some(Seen::FirstRepeat) => found.push(DuplicateKey {
                            pointer: format!("{}/{}", pointer_of(&stack), escape_token(&s)),
                            offset: start,
                            occurrences: 2,
                        }),
                        Some(Seen::RepeatedAgain(at)) => found[at].occurrences += 1,
                        _ => {}
                    }
                    pending_key = Some(s);
                } else {
                    child_token(&mut stack, &mut pending_key);
                }
            }
            _ => {
                child_token(&mut stack, &mut pending_key);
                if scanner.skip_scalar().is_none() {
                    break;
                }
            }
        }
    }
    found
}

/// The keys of one object seen so far, each by where it starts in the text and the index of
/// its finding once it repeats (eight bytes a key: an object of 10^6 members must not cost
/// a string and a hash slot per member).
#[derive(Default)]
struct KeysSeen {
    starts: hashbrown::HashTable<(u32, u32)>,
    hasher: hashbrown::DefaultHashBuilder,
}

/// What [`KeysSeen::insert`] found.
enum Seen {
    New,
    /// The key's second occurrence: its finding is the next one.
    FirstRepeat,
    /// A later occurrence: its finding is at this index.
    RepeatedAgain(usize),
}

/// No finding yet.
const NOT_FOUND: u32 = u32::MAX;

impl KeysSeen {
    /// Notes `key`, which starts at `start` of `text`; on its first repeat its finding is
    /// to be `next`.
    fn insert(&mut self, text: &[u8], key: &str, start: usize, next: usize) -> Seen {
        let key_at = |at: u32| {
            Scanner {
                text,
                pos: at as usize,
            }
            .read_string()
        };
        let hash = self.hasher.hash_one(key);
        if let Some((_, finding)) = self
            .starts
            .find_mut(hash, |(at, _)| key_at(*at).as_deref() == Some(key))
        {
            if *finding == NOT_FOUND {
                *finding = next as u32;
                return Seen::FirstRepeat;
            }
            return Seen::RepeatedAgain(*finding as usize);
        }
        let hasher = &self.hasher;
        let rehash =
            |(at, _): &(u32, u32)| hasher.hash_one(key_at(*at).as_deref().unwrap_or_default());
        // Files are at most u32::MAX bytes (`file::MAX_FILE_BYTES`), and hold fewer keys.
        self.starts
            .insert_unique(hash, (start as u32, NOT_FOUND), rehash);
        Seen::New
    }
}

struct Scanner<'a> {
    text: &'a [u8],
    pos: usize,
}

impl<'a> Scanner<'a> {
    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn skip_ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.pos += 1;
        }
    }

    /// The string at the cursor, decoded: borrowed from the text when it holds no escape (a
    /// key of each of an object's 10^6 members is then no allocation of its own).
    fn read_string(&mut self) -> Option<Cow<'a, str>> {
        let start = self.pos;
        self.skip_string()?;
        let quoted = &self.text[start..self.pos];
        let inner = &quoted[1..quoted.len() - 1];
        if !inner.iter().any(|&b| b == b'\\' || b < 0x20) {
            if let Ok(plain) = std::str::from_utf8(inner) {
                return Some(Cow::Borrowed(plain));
            }
        }
        serde_json::from_slice(quoted).ok().map(Cow::Owned)
    }

    fn skip_string(&mut self) -> Option<()> {
        self.pos += 1;
        loop {
            match self.peek()? {
                b'\\' => self.pos += 2,
                b'"' => {
                    self.pos += 1;
                    return Some(());
                }
                _ => self.pos += 1,
            }
        }
    }

    fn skip_scalar(&mut self) -> Option<()> {
        let start = self.pos;
        while let Some(b) = self.peek() {
            if matches!(b, b',' | b'}' | b']' | b' ' | b'\t' | b'\n' | b'\r' | b':') {
                break;
            }
            self.pos += 1;
        }
        (self.pos > start).then_some(())
    }

    /// Skips one value without recursion: containers are matched by counting brackets.
    fn skip_value(&mut self) -> Option<()> {
        self.skip_ws();
        match self.peek()? {
            b'"' => self.skip_string(),
            b'{' | b'[' => {
                let mut depth = 0usize;
                loop {
                    match self.peek()? {
                        b'"' => {
                            self.skip_string()?;
                            continue;
                        }
                        b'{' | b'[' => depth += 1,
                        b'}' | b']' => {
                            depth -= 1;
                            if depth == 0 {
                                self.pos += 1;
                                return Some(());
                            }
                        }
                        _ => {}
                    }
                    self.pos += 1;
                }
            }
            _ => self.skip_scalar(),
        }
    }

    /// Positioned on a value whose descendants some pointers of `below` name: walks into the
    /// members and elements they go through, skipping the rest. It recurses only along the
    /// pointers' tokens, so its depth is that of the deepest pointer.
    fn locate_in(
        &mut self,
        wanted: &Wanted,
        below: std::ops::Range<usize>,
        path: &mut String,
        found: &mut dyn FnMut(usize, std::ops::Range<usize>),
    ) -> Option<()> {
        self.skip_ws();
        let has_below = !below.is_empty();
        match self.peek()? {
            b'{' if has_below => {
                self.pos += 1;
                loop {
                    self.skip_ws();
                    match self.peek()? {
                        b'}' => break,
                        b',' => self.pos += 1,
                        b'"' => {
                            let key_start = self.pos;
                            let name = self.read_string()?;
                            self.skip_ws();
                            if self.peek()? != b':' {
                                return None;
                            }
                            self.pos += 1;
                            let length = path.len();
                            path.push('/');
                            path.push_str(&escape_token(&name));
                            self.member(wanted, &below, path, key_start, found)?;
                            path.truncate(length);
                        }
                        _ => return None,
                    }
                }
                self.pos += 1;
            }
            b'[' if has_below => {
                self.pos += 1;
                let mut index = 0usize;
                loop {
                    self.skip_ws();
                    if self.peek()? == b']' {
                        break;
                    }
                    let length = path.len();
                    path.push('/');
                    path.push_str(&index.to_string());
                    let at = self.pos;
                    self.member(wanted, &below, path, at, found)?;
                    path.truncate(length);
                    self.skip_ws();
                    match self.peek()? {
                        b',' => {
                            self.pos += 1;
                            index += 1;
                        }
                        b']' => break,
                        _ => return None,
                    }
                }
                self.pos += 1;
            }
            _ => self.skip_value()?,
        }
        Some(())
    }

    /// Walks the member or element at `path` (whose text starts at `start`), one of the
    /// values below its parent's pointers `within`: into it when some pointer enters it,
    /// recording its range when a pointer names it, otherwise skipping it.
    fn member(
        &mut self,
        wanted: &Wanted,
        within: &std::ops::Range<usize>,
        path: &mut String,
        start: usize,
        found: &mut dyn FnMut(usize, std::ops::Range<usize>),
    ) -> Option<()> {
        let named = wanted.exactly(path, within);
        let below = wanted.below(path, within);
        if named.is_none() && below.is_empty() {
            self.skip_ws();
            return self.skip_value();
        }
        self.skip_ws();
        let value_start = self.pos;
        self.locate_in(wanted, below, path, found)?;
        if let Some(at) = named {
            found(at, start.min(value_start)..self.pos);
        }
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &[u8] = br#"{
  "asset": {"version": "2.0"},
  "nodes": [{}, {"name": "a/b", "mesh": 3}]
}"#;

    fn locate(text: &[u8], pointer: &str) -> Option<std::ops::Range<usize>> {
        locate_all(text, &[pointer]).remove(0)
    }

    #[test]
    fn locate_finds_a_member_by_its_key() {
        let range = locate(TEXT, "/nodes/1/mesh").unwrap();
        assert_eq!(&TEXT[range], br#""mesh": 3"#);
        let lines = LineIndex::new(TEXT);
        assert_eq!(
            lines.line_col(locate(TEXT, "/nodes/1").unwrap().start),
            (3, 17)
        );
        assert_eq!(
            lines.line(3),
            br#"  "nodes": [{}, {"name": "a/b", "mesh": 3}]"#
        );
    }

    /// Lines and columns from the blocked index are those of counting from the start, at
    /// every offset of texts with short and long lines, multi-byte characters and breaks on
    /// block boundaries.
    #[test]
    fn lines_and_columns_are_those_counted_from_the_start() {
        let mut random = crate::test_random::Sequence::new(7);
        for _ in 0..40 {
            let length = random.below(1200);
            let text: String = (0..length)
                .map(|_| match random.below(40) {
                    0..=2 => '\n',
                    3 => 'é',
                    4 => '€',
                    _ => 'a',
                })
                .collect();
            let bytes = text.as_bytes();
            let index = LineIndex::new(bytes);
            let lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
            for (n, line) in lines.iter().enumerate() {
                assert_eq!(index.line(n + 1), *line, "line {}", n + 1);
            }
            assert_eq!(index.line(lines.len() + 1), b"");
            for offset in (0..=bytes.len()).filter(|&o| text.is_char_boundary(o)) {
                let before = &text[..offset];
                let line = before.matches('\n').count() + 1;
                let column = before.rsplit('\n').next().unwrap().chars().count() + 1;
                assert_eq!(index.line_col(offset), (line, column), "offset {offset}");
            }
        }
    }

    /// A pointer and its neighbours in sorted order that share its text ("/nodes/1",
    /// "/nodes/1/mesh", "/nodes/10") are each found at their own value.
    #[test]
    fn pointers_sharing_a_prefix_are_each_found_at_their_own_value() {
        let text = format!(
            r#"{{"nodes": [{}]}}"#,
            (0..12)
                .map(|i| format!(r#"{{"mesh": {i}}}"#))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let sorted = [
            "/nodes/1",
            "/nodes/1/mesh",
            "/nodes/10",
            "/nodes/10/mesh",
            "/nodes/2/mesh",
        ];
        let found = locate_all(text.as_bytes(), &sorted);
        let shown: Vec<&str> = (found.iter())
            .map(|range| &text[range.clone().unwrap()])
            .collect();
        assert_eq!(
            shown,
            [
                r#"{"mesh": 1}"#,
                r#""mesh": 1"#,
                r#"{"mesh": 10}"#,
                r#""mesh": 10"#,
                r#""mesh": 2"#
            ]
        );
    }

    #[test]
    fn many_pointers_are_located_in_one_pass_each_as_alone() {
        let pointers = [
            "/nodes/1/mesh",
            "/nodes/1",
            "/nodes/0",
            "/asset/version",
            "/nodes",
            "",
        ];
        let mut sorted = pointers.to_vec();
        sorted.sort_unstable();
        let all = locate_all(TEXT, &sorted);
        for (pointer, together) in sorted.iter().zip(&all) {
            let alone = locate(TEXT, pointer);
            assert_eq!(*together, alone, "{pointer}");
            assert!(alone.is_some(), "{pointer}");
        }
        assert_eq!(
            &TEXT[locate(TEXT, "/asset/version").unwrap()],
            br#""version": "2.0""#
        );
    }

    /// Keys holding '/' and '~' are reached through their escaped tokens (RFC 6901), and a
    /// pointer through a key nothing has is found nowhere, not at a neighbour.
    #[test]
    fn escaped_keys_are_located_and_absent_ones_are_not() {
        let text = br#"{"a/b": {"~x": [7, 8]}, "ab": 1}"#;
        assert_eq!(&text[locate(text, "/a~1b/~0x/1").unwrap()], b"8");
        assert_eq!(
            &text[locate(text, "/a~1b").unwrap()],
            br#""a/b": {"~x": [7, 8]}"#
        );
        for absent in ["/a/b", "/a~1b/~x", "/a~1b/~0x/2", "/ab/0"] {
            assert_eq!(locate(text, absent), None, "{absent}");
        }
        assert_eq!(locate(text, "/").map(|r| r.start), Some(0));
    }

    #[test]
    fn a_repeated_key_is_located_at_its_last_value() {
        let text = br#"{"a": 1, "a": [5]}"#;
        assert_eq!(&text[locate(text, "/a").unwrap()], br#""a": [5]"#);
    }

    #[test]
    fn columns_count_characters_across_index_blocks() {
        let text = format!("{}é\nxy", "a".repeat(2 * BLOCK + 5));
        let lines = LineIndex::new(text.as_bytes());
        let e_acute = 2 * BLOCK + 5;
        assert_eq!(lines.line_col(e_acute), (1, e_acute + 1));
        assert_eq!(
            lines.line_col(e_acute + 2),
            (1, e_acute + 2),
            "é is one character"
        );
        assert_eq!(lines.line_col(text.len() - 1), (2, 2));
    }

    #[test]
    fn locate_of_a_missing_member_is_none() {
        assert_eq!(locate(TEXT, "/nodes/1/skin"), None);
        assert_eq!(locate(TEXT, "/nodes/7"), None);
    }

    #[test]
    fn duplicate_keys_are_reported_with_their_pointer() {
        let text = br#"{"a": 1, "b": {"c": [1, {"d": 0, "d": 1}]}, "a": 2}"#;
        let dups: Vec<String> = duplicate_keys(text)
            .into_iter()
            .map(|d| d.pointer)
            .collect();
        assert_eq!(dups, vec!["/b/c/1/d".to_string(), "/a".to_string()]);
    }

    #[test]
    fn keys_are_compared_as_decoded_and_found_among_many() {
        let escaped = br#"{"a": 1, "\u0061": 2, "b\"": 3, "b\u0022": 4}"#;
        let dups: Vec<String> = duplicate_keys(escaped)
            .into_iter()
            .map(|d| d.pointer)
            .collect();
        assert_eq!(dups, vec!["/a".to_string(), "/b\"".to_string()]);
        let mut many: String = (0..100_000).map(|i| format!("\"k{i}\": 0, ")).collect();
        many = format!("{{{many}\"k7\": 1, \"k99999\": 2}}");
        let found = duplicate_keys(many.as_bytes());
        let pointers: Vec<&str> = found.iter().map(|d| d.pointer.as_str()).collect();
        assert_eq!(pointers, ["/k7", "/k99999"]);
        assert_eq!(
            &many.as_bytes()[found[0].offset..found[0].offset + 4],
            br#""k7""#
        );
    }

    #[test]
    fn a_key_repeated_many_times_is_one_entry_with_its_count() {
        let repeated: String = (0..100_000).map(|_| "\"k\": 0, ").collect();
        let text = format!("{{{repeated}\"j\": 1, \"j\": 2, \"o\": {{\"k\": 1, \"k\": 2}}}}");
        let found = duplicate_keys(text.as_bytes());
        let summary: Vec<(&str, usize)> = (found.iter())
            .map(|d| (d.pointer.as_str(), d.occurrences))
            .collect();
        assert_eq!(summary, [("/k", 100_000), ("/j", 2), ("/o/k", 2)]);
    }

    #[test]
    fn half_a_surrogate_pair_is_read_as_the_replacement_character_and_pairs_stay_whole() {
        let text = br#"{"a": "\ud800", "b": "x\udc00y", "c": "\ud83d\ude00", "d": "\\ud800"}"#;
        let tree = parse(text).unwrap();
        let member = |key: &str| {
            tree.root()
                .get(key)
                .and_then(|v| v.as_str())
                .map(str::to_string)
        };
        assert_eq!(member("a").as_deref(), Some("\u{fffd}"));
        assert_eq!(member("b").as_deref(), Some("x\u{fffd}y"));
        assert_eq!(member("c").as_deref(), Some("\u{1f600}"));
        assert_eq!(
            member("d").as_deref(),
            Some("\\ud800"),
            "an escaped backslash, no escape"
        );
        // Anything else wrong in an escape is still an error.
        assert!(parse(br#"{"a": "\uzzzz"}"#).is_err());
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let text = "[".repeat(100_000) + &"]".repeat(100_000);
        assert!(parse(text.as_bytes()).is_err());
        assert!(duplicate_keys(text.as_bytes()).is_empty());
        assert!(locate(text.as_bytes(), "/0/0/0").is_some());
    }

    #[test]
    fn a_bom_is_rejected() {
        assert!(parse(b"\xEF\xBB\xBF{}").is_err());
    }
}
