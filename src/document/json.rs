//! JSON text → `serde_json::Value`, plus source locations found on demand.
//!
//! Values are parsed once with serde_json (fast, depth-limited, never overflows the stack).
//! Spans are *not* stored per node: a pointer is resolved back to a byte range only when a
//! diagnostic is printed, by [`locate`], a small iterative scanner over the original text.
//! The same scanner reports duplicate object keys, which serde_json silently collapses.

use serde_json::Value;

/// A JSON syntax error with its 1-based position.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntaxError {
    pub message: String,
    pub offset: usize,
}

/// Parses JSON text. A UTF-8 byte-order mark is an error, as in the glTF spec.
pub fn parse(bytes: &[u8]) -> Result<Value, SyntaxError> {
    if bytes.starts_with(&[0xEF, 0xBB, 0xBF]) {
        return Err(SyntaxError {
            message: "BOM found at the beginning of UTF-8 stream".into(),
            offset: 0,
        });
    }
    serde_json::from_slice(bytes).map_err(|e| {
        let offset = offset_of(bytes, e.line(), e.column());
        SyntaxError {
            message: e.to_string(),
            offset,
        }
    })
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

/// 1-based line and column (in characters) of a byte offset.
pub fn line_col(text: &[u8], offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.iter().filter(|b| **b == b'\n').count() + 1;
    let line_start = before
        .iter()
        .rposition(|b| *b == b'\n')
        .map_or(0, |p| p + 1);
    let column = String::from_utf8_lossy(&text[line_start..offset])
        .chars()
        .count()
        + 1;
    (line, column)
}

/// Splits an RFC 6901 pointer into unescaped tokens.
pub fn pointer_tokens(pointer: &str) -> Vec<String> {
    if pointer.is_empty() || pointer == "/" {
        return Vec::new();
    }
    pointer
        .trim_start_matches('/')
        .split('/')
        .map(|t| t.replace("~1", "/").replace("~0", "~"))
        .collect()
}

/// Escapes one token for use in a JSON pointer.
pub fn escape_token(token: &str) -> String {
    token.replace('~', "~0").replace('/', "~1")
}

/// Byte range of the value a pointer names; for an object member the range starts at its key,
/// so a snippet shows the property name. Falls back to the deepest existing ancestor.
pub fn locate(text: &[u8], pointer: &str) -> Option<std::ops::Range<usize>> {
    let mut scanner = Scanner { text, pos: 0 };
    scanner.skip_ws();
    let mut found_start = scanner.pos;
    for token in pointer_tokens(pointer) {
        scanner.skip_ws();
        match scanner.peek()? {
            b'{' => {
                let key_start = scanner.find_member(&token)?;
                found_start = key_start;
            }
            b'[' => {
                let index: usize = token.parse().ok()?;
                scanner.find_element(index)?;
                found_start = scanner.pos;
            }
            _ => return None,
        }
    }
    scanner.skip_ws();
    let value_start = scanner.pos;
    scanner.skip_value()?;
    Some(found_start.min(value_start)..scanner.pos)
}

/// Pointers (and key offsets) of object keys that occur more than once in their object.
///
/// Each open container keeps only its own token, so memory stays linear in the nesting depth;
/// a pointer is built only for a duplicate.
pub fn duplicate_keys(text: &[u8]) -> Vec<(String, usize)> {
    struct Frame {
        /// The token naming this container inside its parent.
        token: String,
        /// Keys seen so far (objects), or `None` for arrays.
        keys: Option<Vec<String>>,
        /// Next element index (arrays).
        next_index: usize,
    }
    fn pointer(stack: &[Frame]) -> String {
        stack
            .iter()
            .skip(1)
            .map(|f| format!("/{}", escape_token(&f.token)))
            .collect()
    }
    fn child_token(stack: &mut [Frame], pending: &mut Option<String>) -> String {
        match stack.last_mut() {
            Some(Frame { keys: Some(_), .. }) => pending.take().unwrap_or_default(),
            Some(frame) => {
                frame.next_index += 1;
                (frame.next_index - 1).to_string()
            }
            None => String::new(),
        }
    }
    let mut found = Vec::new();
    let mut stack: Vec<Frame> = Vec::new();
    let mut scanner = Scanner { text, pos: 0 };
    let mut pending_key: Option<String> = None;
    while scanner.pos < text.len() {
        scanner.skip_ws();
        let Some(b) = scanner.peek() else { break };
        match b {
            b'{' | b'[' => {
                let token = child_token(&mut stack, &mut pending_key);
                let keys = (b == b'{').then(Vec::new);
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
                    let duplicate = stack
                        .last()
                        .and_then(|f| f.keys.as_ref())
                        .is_some_and(|k| k.contains(&s));
                    if duplicate {
                        found.push((format!("{}/{}", pointer(&stack), escape_token(&s)), start));
                    } else if let Some(keys) = stack.last_mut().and_then(|f| f.keys.as_mut()) {
                        keys.push(s.clone());
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

struct Scanner<'a> {
    text: &'a [u8],
    pos: usize,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.text.get(self.pos).copied()
    }

    fn skip_ws(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.pos += 1;
        }
    }

    fn read_string(&mut self) -> Option<String> {
        let start = self.pos;
        self.skip_string()?;
        serde_json::from_slice(&self.text[start..self.pos]).ok()
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

    /// Positioned on `{`: moves to the value of `key` (last occurrence wins, as in parsing)
    /// and returns the offset of that key.
    fn find_member(&mut self, key: &str) -> Option<usize> {
        self.pos += 1;
        let mut hit: Option<(usize, usize)> = None;
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
                    self.skip_ws();
                    if name == key {
                        hit = Some((key_start, self.pos));
                    }
                    self.skip_value()?;
                }
                _ => return None,
            }
        }
        let (key_start, value_start) = hit?;
        self.pos = value_start;
        Some(key_start)
    }

    /// Positioned on `[`: moves to element `index`.
    fn find_element(&mut self, index: usize) -> Option<()> {
        self.pos += 1;
        for _ in 0..index {
            self.skip_value()?;
            self.skip_ws();
            if self.peek()? != b',' {
                return None;
            }
            self.pos += 1;
        }
        self.skip_ws();
        (self.peek()? != b']').then_some(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &[u8] = br#"{
  "asset": {"version": "2.0"},
  "nodes": [{}, {"name": "a/b", "mesh": 3}]
}"#;

    #[test]
    fn locate_finds_a_member_by_its_key() {
        let range = locate(TEXT, "/nodes/1/mesh").unwrap();
        assert_eq!(&TEXT[range], br#""mesh": 3"#);
        assert_eq!(
            line_col(TEXT, locate(TEXT, "/nodes/1").unwrap().start),
            (3, 17)
        );
    }

    #[test]
    fn locate_of_a_missing_member_is_none() {
        assert_eq!(locate(TEXT, "/nodes/1/skin"), None);
        assert_eq!(locate(TEXT, "/nodes/7"), None);
    }

    #[test]
    fn duplicate_keys_are_reported_with_their_pointer() {
        let text = br#"{"a": 1, "b": {"c": [1, {"d": 0, "d": 1}]}, "a": 2}"#;
        let dups: Vec<String> = duplicate_keys(text).into_iter().map(|d| d.0).collect();
        assert_eq!(dups, vec!["/b/c/1/d".to_string(), "/a".to_string()]);
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
