//! JSON text → a compact tree: eight bytes a value, strings stored once.
//!
//! A `serde_json::Value` costs 80 bytes (with `preserve_order`), whatever the text spends
//! on it: a document of 10^7 zeros, two bytes each, would take forty times its size. Here
//! every value is one `Slot` (a tag and a payload in a `u64`):
//! small integers and floats inline, the rare wide number in a side table, a string as the
//! id of its one copy in an arena, an array or object as a range of slots holding its
//! elements (an object's as key, value pairs).
//!
//! The text is read twice with serde_json (the same numbers, the same errors, the same
//! last-wins duplicate keys at the first key's place as `serde_json::Value`): first to count
//! each container's elements, then to fill exactly that many reserved slots. A container's
//! elements are then contiguous without being gathered on a stack first, which would double
//! the memory of the largest one.
//!
//! The number of values is bounded: past [`MAX_VALUES`] parsing stops with an error at that
//! value's place, instead of memory growing with whatever a stranger uploads.

use hashbrown::{DefaultHashBuilder, HashMap, HashTable};
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::ser::{Serialize, SerializeMap, SerializeSeq, Serializer};
use std::cell::{Cell, RefCell};

use std::fmt;
use std::hash::BuildHasher;

/// The most values one document's tree holds (128 MB of slots). Real glTF JSON stays far
/// below: 10^5 nodes with a name, a mesh and a full transform are about 2·10^6 values.
pub(crate) const MAX_VALUES: usize = 1 << 24;

/// A parsed JSON document.
pub(crate) struct Tree {
    slots: Vec<Slot>,
    /// Numbers that do not fit a slot: integers from 2^60 up, negative integers, and floats
    /// whose low four bits are set, as their bits.
    wide: Vec<u64>,
    /// Every distinct string (keys and values) once, one after the other.
    arena: String,
    /// Where each string ends in `arena`; string `i` starts where `i - 1` ends.
    ends: Vec<u32>,
    /// The string values stored past the lookup table, one after the other, each read by
    /// where its `Text` slot says it lies.
    texts: String,
    /// The string ids, by the hash of their text (for lookups by key), each beside that
    /// hash's low half: growing the table then reads no text again (the arena, read in no
    /// order), and a text is compared only when its hash matches.
    strings: HashTable<(u32, u32)>,
    hasher: DefaultHashBuilder,
    /// The members of each object of more than [`SCANNED_MEMBERS`] members whose keys are
    /// not in string-id order, as (key, member) sorted by key, each object's run found by
    /// its first slot in `indexed_objects`: 8 bytes a member, searched by bisection (a hash
    /// entry a member cost 30 bytes and a cache miss each). A larger object not indexed has
    /// its keys in increasing id order (as an object of keys never seen before has) and is
    /// bisected in place: 10^6 members then cost nothing more.
    member_index: Vec<(u32, u32)>,
    indexed_objects: HashMap<usize, std::ops::Range<usize>>,
    /// Whether some object repeats a key.
    repeats_keys: bool,
    root: Slot,
}

/// Members an object lookup compares one by one; larger objects are indexed.
const SCANNED_MEMBERS: usize = 8;

/// One value: a 4-bit tag over a 60-bit payload.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct Slot(u64);

const PAYLOAD_BITS: u32 = 60;
const PAYLOAD: u64 = (1 << PAYLOAD_BITS) - 1;
/// A container's payload: the first slot of its elements above, their count below.
const LEN_BITS: u32 = 28;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Tag {
    Null,
    False,
    True,
    /// An unsigned integer below 2^60.
    Small,
    /// An unsigned integer from 2^60 up (payload: index into `wide`).
    Large,
    /// A negative integer (payload: index into `wide`, the i64's bits).
    Negative,
    /// A float whose low four bits are clear (payload: its bits shifted right by four).
    Float,
    /// Any other float (payload: index into `wide`).
    WideFloat,
    /// Payload: the string's id.
    String,
    /// A string value stored past the lookup table's [`INTERNED_VALUES`], without an id
    /// (payload: where it starts in `texts` above [`LEN_BITS`], its length below), so that
    /// 10^7 distinct strings cost no list of where each ends.
    Text,
    Array,
    Object,
    /// An object member taken out of the tree (in the key's slot; its value stays unread).
    Removed,
}

const TAGS: [Tag; 13] = [
    Tag::Null,
    Tag::False,
    Tag::True,
    Tag::Small,
    Tag::Large,
    Tag::Negative,
    Tag::Float,
    Tag::WideFloat,
    Tag::String,
    Tag::Text,
    Tag::Array,
    Tag::Object,
    Tag::Removed,
];

impl Slot {
    const NULL: Slot = Slot(0);

    fn new(tag: Tag, payload: u64) -> Slot {
        Slot(((tag as u64) << PAYLOAD_BITS) | (payload & PAYLOAD))
    }

    fn container(tag: Tag, start: usize, len: usize) -> Slot {
        Slot::new(tag, ((start as u64) << LEN_BITS) | len as u64)
    }

    fn tag(self) -> Tag {
        // Every slot is made by `new` with a tag of `TAGS`.
        TAGS[(self.0 >> PAYLOAD_BITS) as usize % TAGS.len()]
    }

    fn payload(self) -> u64 {
        self.0 & PAYLOAD
    }

    /// A container's elements (first slot, count), or a `Text`'s place (start, length).
    fn range(self) -> (usize, usize) {
        let payload = self.payload();
        (
            (payload >> LEN_BITS) as usize,
            (payload & ((1 << LEN_BITS) - 1)) as usize,
        )
    }
}

impl Tree {
    /// Parses JSON text into a tree of at most [`MAX_VALUES`] values.
    pub(crate) fn parse(text: &[u8]) -> serde_json::Result<Tree> {
        Self::parse_within(text, MAX_VALUES, None)
    }

    /// A tree of `value` (tests write their JSON with `serde_json::json!`).
    #[cfg(test)]
    pub(crate) fn of(value: &serde_json::Value) -> Tree {
        Tree::parse(value.to_string().as_bytes()).expect("JSON a test wrote")
    }

    /// [`Tree::parse`] keeping only the root object's members named in `keep`: the others
    /// are read past (their syntax still checked) and left out. A proof reads a 1.0 asset's
    /// materials this way, without the 10^5 meshes beside them.
    pub(crate) fn parse_members(text: &[u8], keep: &[&str]) -> serde_json::Result<Tree> {
        Self::parse_within(text, MAX_VALUES, Some(keep))
    }

    fn parse_within(
        text: &[u8],
        max_values: usize,
        keep: Option<&[&str]>,
    ) -> serde_json::Result<Tree> {
        let counts = count(text, max_values, keep)?;
        let slots = counts.slots;
        let state = RefCell::new(Building {
            tree: Tree {
                slots: Vec::with_capacity(slots),
                wide: Vec::new(),
                arena: String::new(),
                ends: Vec::new(),
                texts: String::new(),
                strings: HashTable::new(),
                hasher: DefaultHashBuilder::default(),
                member_index: Vec::new(),
                indexed_objects: HashMap::new(),
                repeats_keys: false,
                root: Slot::NULL,
            },
            counts: counts.elements,
            next_container: 0,
            root_keep: keep,
        });
        let mut deserializer = serde_json::Deserializer::from_slice(text);
        let root = Build { state: &state }.deserialize(&mut deserializer)?;
        deserializer.end()?;
        let mut tree = state.into_inner().tree;
        tree.root = root;
        tree.wide.shrink_to_fit();
        tree.arena.shrink_to_fit();
        tree.ends.shrink_to_fit();
        tree.texts.shrink_to_fit();
        Ok(tree)
    }

    /// The document's root value.
    pub(crate) fn root(&self) -> Node<'_> {
        self.node(self.root)
    }

    fn node(&self, slot: Slot) -> Node<'_> {
        Node { tree: self, slot }
    }

    fn string(&self, id: u32) -> &str {
        arena_string(&self.arena, &self.ends, id)
    }

    /// The string `id` names (ids are of this tree; one taken out with its member stays).
    pub(crate) fn text(&self, id: StringId) -> &str {
        self.string(id.0)
    }

    /// The id of a string the document holds, if any.
    fn find(&self, text: &str) -> Option<u32> {
        self.find_hashed(text, self.string_hash(text))
    }

    fn find_hashed(&self, text: &str, hash: u32) -> Option<u32> {
        let same = |&(id, stored): &(u32, u32)| stored == hash && self.string(id) == text;
        self.strings.find(spread(hash), same).map(|&(id, _)| id)
    }

    /// The stored half of a string's hash.
    fn string_hash(&self, text: &str) -> u32 {
        self.hasher.hash_one(text) as u32
    }

    /// The slot of the live member keyed by string `key` in the object at `range`.
    fn member_slot(&self, (start, len): (usize, usize), key: u32) -> Option<usize> {
        let key_slot = Slot::new(Tag::String, u64::from(key));
        let at = if len <= SCANNED_MEMBERS {
            return (start..start + 2 * len)
                .step_by(2)
                .find(|&at| self.slots[at] == key_slot);
        } else if let Some(run) = self.indexed_objects.get(&start) {
            let index = &self.member_index[run.clone()];
            let &(found, member) = index.get(index.partition_point(|&(k, _)| k < key))?;
            (found == key).then_some(start + 2 * member as usize)?
        } else {
            let member = self.bisect_members(start, len, key);
            (member < len).then_some(start + 2 * member)?
        };
        (self.slots[at] == key_slot).then_some(at)
    }

    /// The first member of the object at `start` (its keys in increasing id order) whose
    /// key id is not below `key`; `len` when there is none. A member taken out keeps its
    /// key's id, so the order holds.
    fn bisect_members(&self, start: usize, len: usize, key: u32) -> usize {
        let key_id = |member: usize| self.slots[start + 2 * member].payload() as u32;
        let (mut low, mut high) = (0, len);
        while low < high {
            let middle = low + (high - low) / 2;
            if key_id(middle) < key {
                low = middle + 1;
            } else {
                high = middle;
            }
        }
        low
    }

    /// Whether some object of the text repeats a key (the last value was kept).
    pub(crate) fn repeats_keys(&self) -> bool {
        self.repeats_keys
    }

    /// Takes the member a pointer names out of its object, as if it had never been there.
    /// Returns whether it was `null`, or `None` when the pointer names no object member.
    pub(crate) fn remove(&mut self, pointer: &str) -> Option<bool> {
        let (parent, token) = pointer.rsplit_once('/')?;
        let key = self.find(&super::json::unescape_token(token))?;
        let object = self.root().pointer(parent)?.object_range()?;
        let at = self.member_slot(object, key)?;
        self.take_member(at, key, |_| true)
    }

    /// Makes the member a pointer names an empty object, whatever it held. Returns whether
    /// there was such a member.
    pub(crate) fn empty(&mut self, pointer: &str) -> bool {
        let Some((parent, token)) = pointer.rsplit_once('/') else {
            return false;
        };
        let key = self.find(&super::json::unescape_token(token));
        let object = self.root().pointer(parent).and_then(Node::object_range);
        let Some(at) = key
            .zip(object)
            .and_then(|(key, object)| self.member_slot(object, key))
        else {
            return false;
        };
        self.slots[at + 1] = Slot::container(Tag::Object, 0, 0);
        true
    }

    /// [`Tree::remove`] for the members named `keys` of the object at `parent` (a pointer),
    /// each when its value is one `taken` accepts: the names are not looked up again, nor
    /// the pointer once for each. Gives how many were taken out.
    pub(crate) fn remove_members(
        &mut self,
        parent: &str,
        keys: impl IntoIterator<Item = StringId>,
        mut taken: impl FnMut(Node) -> bool,
    ) -> usize {
        let Some(object) = self.root().pointer(parent).and_then(Node::object_range) else {
            return 0;
        };
        // Keys asked for in the order they are written are each found next to the last,
        // live or already taken out (a key slot keeps its key's id either way).
        let mut next = object.0;
        let end = object.0 + 2 * object.1;
        let mut removed = 0;
        for StringId(key) in keys {
            let at = if next < end && self.slots[next].payload() == u64::from(key) {
                next
            } else if let Some(at) = self.member_slot(object, key) {
                at
            } else {
                continue;
            };
            next = at + 2;
            removed += usize::from(self.take_member(at, key, &mut taken).is_some());
        }
        removed
    }

    /// Takes out the member at slot `at`, keyed by string `key`, when it is still there and
    /// `taken` accepts it.
    fn take_member(
        &mut self,
        at: usize,
        key: u32,
        taken: impl FnOnce(Node) -> bool,
    ) -> Option<bool> {
        let live = self.slots[at] == Slot::new(Tag::String, u64::from(key));
        if !live || !taken(self.node(self.slots[at + 1])) {
            return None;
        }
        let was_null = self.slots[at + 1] == Slot::NULL;
        self.slots[at] = Slot::new(Tag::Removed, u64::from(key));
        Some(was_null)
    }
}

impl fmt::Debug for Tree {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "Tree {{ slots: {}, strings: {} }}",
            self.slots.len(),
            self.ends.len()
        )
    }
}

/// Distinct strings entered in the lookup table before string values stop being entered:
/// the most a table of 2^20 buckets holds (it fills seven eighths before it doubles).
const INTERNED_VALUES: usize = 7 << 17;

/// A stored half hash spread over 64 bits, as the hash table wants them: its low bits
/// place an entry, its top bits tag it.
fn spread(hash: u32) -> u64 {
    u64::from(hash).wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// String `id` of an arena: it starts where string `id - 1` ends.
fn arena_string<'a>(arena: &'a str, ends: &[u32], id: u32) -> &'a str {
    let id = id as usize;
    let start = id.checked_sub(1).map_or(0, |i| ends[i] as usize);
    &arena[start..ends[id] as usize]
}

/// A value of a [`Tree`]: a handle as cheap to copy as a reference.
#[derive(Clone, Copy)]
pub(crate) struct Node<'t> {
    tree: &'t Tree,
    slot: Slot,
}

/// What [`Node::get`] accepts: a member name or an element index.
pub(crate) trait Index {
    /// The value this index names in `node`.
    fn index_into<'t>(&self, node: Node<'t>) -> Option<Node<'t>>;
}

impl Index for str {
    fn index_into<'t>(&self, node: Node<'t>) -> Option<Node<'t>> {
        node.as_object()?.get(self)
    }
}

impl Index for String {
    fn index_into<'t>(&self, node: Node<'t>) -> Option<Node<'t>> {
        node.as_object()?.get(self)
    }
}

impl Index for usize {
    fn index_into<'t>(&self, node: Node<'t>) -> Option<Node<'t>> {
        node.as_array()?.get(*self)
    }
}

impl<T: Index + ?Sized> Index for &T {
    fn index_into<'t>(&self, node: Node<'t>) -> Option<Node<'t>> {
        (**self).index_into(node)
    }
}

/// A string of a tree, by its place in the tree's store: four bytes, where a copy of a
/// name 10^6 members share would cost a string each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct StringId(u32);

impl<'t> Node<'t> {
    /// The tree this value is in.
    pub(crate) fn tree(self) -> &'t Tree {
        self.tree
    }

    /// A member of an object or an element of an array.
    pub(crate) fn get(self, index: impl Index) -> Option<Node<'t>> {
        index.index_into(self)
    }

    /// A `null` of the same tree (what a missing member reads as).
    pub(crate) fn null(self) -> Node<'t> {
        Node {
            tree: self.tree,
            slot: Slot::NULL,
        }
    }

    /// The value an RFC 6901 pointer names below this one.
    pub(crate) fn pointer(self, pointer: &str) -> Option<Node<'t>> {
        if pointer.is_empty() {
            return Some(self);
        }
        let tokens = pointer.strip_prefix('/')?.split('/');
        tokens
            .map(super::json::unescape_token)
            .try_fold(self, |node, token| match node.slot.tag() {
                Tag::Object => node.get(&*token),
                Tag::Array => node.get(array_index(&token)?),
                _ => None,
            })
    }

    /// The members, when it is an object.
    pub(crate) fn as_object(self) -> Option<Object<'t>> {
        let (start, len) = self.object_range()?;
        Some(Object {
            tree: self.tree,
            start,
            len,
        })
    }

    /// The elements, when it is an array.
    pub(crate) fn as_array(self) -> Option<Array<'t>> {
        (self.slot.tag() == Tag::Array).then(|| {
            let (start, len) = self.slot.range();
            Array {
                tree: self.tree,
                start,
                len,
            }
        })
    }

    /// The text, when it is a string.
    pub(crate) fn as_str(self) -> Option<&'t str> {
        match self.slot.tag() {
            Tag::String => Some(self.tree.string(self.slot.payload() as u32)),
            Tag::Text => {
                let (start, len) = self.slot.range();
                Some(&self.tree.texts[start..start + len])
            }
            _ => None,
        }
    }

    /// The truth value, when it is a boolean.
    pub(crate) fn as_bool(self) -> Option<bool> {
        match self.slot.tag() {
            Tag::True => Some(true),
            Tag::False => Some(false),
            _ => None,
        }
    }

    /// The number, when it is an integer from 0 to `u64::MAX` as written (not `1.0`).
    pub(crate) fn as_u64(self) -> Option<u64> {
        match self.slot.tag() {
            Tag::Small => Some(self.slot.payload()),
            Tag::Large => Some(self.wide()),
            _ => None,
        }
    }

    /// The number, when it is an integer within `i64` as written (not `1.0`).
    pub(crate) fn as_i64(self) -> Option<i64> {
        match self.slot.tag() {
            Tag::Negative => Some(self.wide() as i64),
            _ => self.as_u64().and_then(|v| i64::try_from(v).ok()),
        }
    }

    /// Any number, as the nearest f64.
    pub(crate) fn as_f64(self) -> Option<f64> {
        match self.slot.tag() {
            Tag::Small => Some(self.slot.payload() as f64),
            Tag::Large => Some(self.wide() as f64),
            Tag::Negative => Some(self.wide() as i64 as f64),
            Tag::Float => Some(f64::from_bits(self.slot.payload() << 4)),
            Tag::WideFloat => Some(f64::from_bits(self.wide())),
            _ => None,
        }
    }

    /// Whether it is `null`.
    pub(crate) fn is_null(self) -> bool {
        self.slot.tag() == Tag::Null
    }

    /// Whether it is an object.
    pub(crate) fn is_object(self) -> bool {
        self.slot.tag() == Tag::Object
    }

    /// Whether it is an array.
    pub(crate) fn is_array(self) -> bool {
        self.slot.tag() == Tag::Array
    }

    /// Whether it is a string.
    pub(crate) fn is_string(self) -> bool {
        matches!(self.slot.tag(), Tag::String | Tag::Text)
    }

    /// Whether it is `true` or `false`.
    pub(crate) fn is_boolean(self) -> bool {
        self.as_bool().is_some()
    }

    /// Whether it is a number.
    pub(crate) fn is_number(self) -> bool {
        self.as_f64().is_some()
    }

    /// The value as a `serde_json::Value` (for code that builds on serde's tree).
    pub(crate) fn to_value(self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or_default()
    }

    fn wide(self) -> u64 {
        self.tree.wide[self.slot.payload() as usize]
    }

    fn object_range(self) -> Option<(usize, usize)> {
        (self.slot.tag() == Tag::Object).then(|| self.slot.range())
    }
}

impl<'t> crate::gltf::Json<'t> for Node<'t> {
    fn get(self, key: &str) -> Option<Self> {
        Node::get(self, key)
    }

    fn as_u64(self) -> Option<u64> {
        Node::as_u64(self)
    }

    fn as_f64(self) -> Option<f64> {
        Node::as_f64(self)
    }

    fn as_str(self) -> Option<&'t str> {
        Node::as_str(self)
    }

    fn is_object(self) -> bool {
        Node::is_object(self)
    }

    fn member_values(self) -> Box<dyn Iterator<Item = Self> + 't> {
        Box::new(self.as_object().into_iter().flat_map(Object::values))
    }

    fn item(self, index: usize) -> Option<Self> {
        self.as_array()?.get(index)
    }
}

/// An array's index as a pointer token spells it: no sign, no leading zero.
fn array_index(token: &str) -> Option<usize> {
    let leading_zero = token.len() > 1 && token.starts_with('0');
    (!leading_zero && !token.starts_with('+'))
        .then(|| token.parse().ok())
        .flatten()
}

/// The elements of an array value.
#[derive(Clone, Copy)]
pub(crate) struct Array<'t> {
    tree: &'t Tree,
    start: usize,
    len: usize,
}

impl<'t> Array<'t> {
    /// An array of no elements (what a missing list reads as).
    pub(crate) fn empty(of: Node<'t>) -> Array<'t> {
        Array {
            tree: of.tree,
            start: 0,
            len: 0,
        }
    }

    /// How many elements it has.
    pub(crate) fn len(self) -> usize {
        self.len
    }

    /// Whether it has no element.
    pub(crate) fn is_empty(self) -> bool {
        self.len == 0
    }

    /// The element at `index`.
    pub(crate) fn get(self, index: usize) -> Option<Node<'t>> {
        (index < self.len).then(|| self.tree.node(self.tree.slots[self.start + index]))
    }

    /// The element at an index known to be in range (a null value past the end).
    pub(crate) fn at(self, index: usize) -> Node<'t> {
        self.get(index).unwrap_or(Node {
            tree: self.tree,
            slot: Slot::NULL,
        })
    }

    /// The first element.
    pub(crate) fn first(self) -> Option<Node<'t>> {
        self.get(0)
    }

    /// The elements in order.
    pub(crate) fn iter(self) -> impl DoubleEndedIterator<Item = Node<'t>> + ExactSizeIterator + 't {
        let tree = self.tree;
        tree.slots[self.start..self.start + self.len]
            .iter()
            .map(move |&slot| tree.node(slot))
    }
}

impl<'t> IntoIterator for Array<'t> {
    type Item = Node<'t>;
    type IntoIter = Box<dyn DoubleEndedIterator<Item = Node<'t>> + 't>;

    fn into_iter(self) -> Self::IntoIter {
        Box::new(self.iter())
    }
}

/// The members of an object value, in the order they were written.
#[derive(Clone, Copy)]
pub(crate) struct Object<'t> {
    tree: &'t Tree,
    start: usize,
    /// Members written (some may have been taken out since).
    len: usize,
}

impl<'t> Object<'t> {
    /// The member named `key`.
    pub(crate) fn get(self, key: &str) -> Option<Node<'t>> {
        let id = self.tree.find(key)?;
        let at = self.tree.member_slot((self.start, self.len), id)?;
        Some(self.tree.node(self.tree.slots[at + 1]))
    }

    /// The place of the member named `key` among the members as written (members taken
    /// out since still count): a 1.0 dictionary's ids become 2.0 indices by it.
    pub(crate) fn position(self, key: &str) -> Option<usize> {
        let id = self.tree.find(key)?;
        let at = self.tree.member_slot((self.start, self.len), id)?;
        Some((at - self.start) / 2)
    }

    /// Whether a member is named `key`.
    pub(crate) fn contains_key(self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// The members in the order they were written: (key, value).
    pub(crate) fn iter(self) -> impl Iterator<Item = (&'t str, Node<'t>)> + 't {
        let tree = self.tree;
        tree.slots[self.start..self.start + 2 * self.len]
            .chunks_exact(2)
            .filter(|pair| pair[0].tag() == Tag::String)
            .map(move |pair| {
                let key = tree.string(pair[0].payload() as u32);
                (key, tree.node(pair[1]))
            })
    }

    /// The member names in order, each with its id in the tree (see [`Tree::text`]).
    pub(crate) fn keys_with_ids(self) -> impl Iterator<Item = (StringId, &'t str)> + 't {
        let tree = self.tree;
        tree.slots[self.start..self.start + 2 * self.len]
            .chunks_exact(2)
            .filter(|pair| pair[0].tag() == Tag::String)
            .map(move |pair| {
                let id = pair[0].payload() as u32;
                (StringId(id), tree.string(id))
            })
    }

    /// The member names in order.
    pub(crate) fn keys(self) -> impl Iterator<Item = &'t str> + 't {
        self.iter().map(|(key, _)| key)
    }

    /// The member values in order.
    pub(crate) fn values(self) -> impl Iterator<Item = Node<'t>> + 't {
        self.iter().map(|(_, value)| value)
    }

    /// The members still in the tree.
    pub(crate) fn len(self) -> usize {
        self.iter().count()
    }

    /// Whether no member is left.
    pub(crate) fn is_empty(self) -> bool {
        self.iter().next().is_none()
    }
}

impl<'t> IntoIterator for Object<'t> {
    type Item = (&'t str, Node<'t>);
    type IntoIter = Box<dyn Iterator<Item = (&'t str, Node<'t>)> + 't>;

    fn into_iter(self) -> Self::IntoIter {
        Box::new(self.iter())
    }
}

impl Serialize for Node<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let node = *self;
        match node.slot.tag() {
            Tag::Null | Tag::Removed => serializer.serialize_unit(),
            Tag::False | Tag::True => serializer.serialize_bool(node.slot.tag() == Tag::True),
            Tag::Small | Tag::Large => serializer.serialize_u64(node.as_u64().unwrap_or(0)),
            Tag::Negative => serializer.serialize_i64(node.as_i64().unwrap_or(0)),
            Tag::Float | Tag::WideFloat => serializer.serialize_f64(node.as_f64().unwrap_or(0.0)),
            Tag::String | Tag::Text => serializer.serialize_str(node.as_str().unwrap_or_default()),
            Tag::Array => {
                let elements = node.as_array().into_iter().flat_map(Array::iter);
                let mut seq = serializer.serialize_seq(None)?;
                for element in elements {
                    seq.serialize_element(&element)?;
                }
                seq.end()
            }
            Tag::Object => {
                let members = node.as_object().into_iter().flat_map(Object::iter);
                let mut map = serializer.serialize_map(None)?;
                for (key, value) in members {
                    map.serialize_entry(key, &value)?;
                }
                map.end()
            }
        }
    }
}

/// The value as JSON text, as `serde_json::Value` prints it.
impl fmt::Display for Node<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let text = serde_json::to_string(self).map_err(|_| fmt::Error)?;
        f.write_str(&text)
    }
}

impl fmt::Debug for Node<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

// ---- The first reading: how many elements each container has. ----

struct Counts {
    /// Elements (members) of each array (object), in the order they open.
    elements: Vec<u32>,
    /// Slots the whole tree needs.
    slots: usize,
}

fn count(text: &[u8], max_values: usize, keep: Option<&[&str]>) -> serde_json::Result<Counts> {
    let state = Counting {
        elements: RefCell::new(Vec::new()),
        slots: Cell::new(0),
        left: Cell::new(max_values),
        root_keep: keep,
    };
    let mut deserializer = serde_json::Deserializer::from_slice(text);
    Count(&state).deserialize(&mut deserializer)?;
    deserializer.end()?;
    Ok(Counts {
        elements: state.elements.into_inner(),
        slots: state.slots.get(),
    })
}

struct Counting<'k> {
    elements: RefCell<Vec<u32>>,
    slots: Cell<usize>,
    left: Cell<usize>,
    /// The root object's members to keep (None: all).
    root_keep: Option<&'k [&'k str]>,
}

#[derive(Clone, Copy)]
struct Count<'c>(&'c Counting<'c>);

impl Count<'_> {
    /// Counts one more value, or fails once the budget is spent.
    fn spend<E: de::Error>(self) -> Result<(), E> {
        let left = self.0.left.get().checked_sub(1).ok_or_else(|| {
            E::custom(format_args!(
                "more than {MAX_VALUES} values, the most gltfmat reads in one document"
            ))
        })?;
        self.0.left.set(left);
        Ok(())
    }

    /// Opens a container: its place in the list of counts.
    fn open(self) -> usize {
        let mut elements = self.0.elements.borrow_mut();
        elements.push(0);
        elements.len() - 1
    }

    fn close(self, container: usize, elements: usize, slots_each: usize) {
        self.0.elements.borrow_mut()[container] = elements as u32;
        self.0.slots.set(self.0.slots.get() + elements * slots_each);
    }
}

impl<'de> DeserializeSeed<'de> for Count<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Count<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E: de::Error>(self, _: bool) -> Result<(), E> {
        self.spend()
    }

    fn visit_i64<E: de::Error>(self, _: i64) -> Result<(), E> {
        self.spend()
    }

    fn visit_u64<E: de::Error>(self, _: u64) -> Result<(), E> {
        self.spend()
    }

    fn visit_f64<E: de::Error>(self, _: f64) -> Result<(), E> {
        self.spend()
    }

    fn visit_str<E: de::Error>(self, _: &str) -> Result<(), E> {
        self.spend()
    }

    fn visit_unit<E: de::Error>(self) -> Result<(), E> {
        self.spend()
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut elements: A) -> Result<(), A::Error> {
        self.spend()?;
        let container = self.open();
        let mut n = 0;
        while elements.next_element_seed(self)?.is_some() {
            n += 1;
        }
        self.close(container, n, 1);
        Ok(())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut members: A) -> Result<(), A::Error> {
        self.spend()?;
        let container = self.open();
        // The root is the first container opened.
        let keep = self.0.root_keep.filter(|_| container == 0);
        let mut n = 0;
        match keep {
            None => {
                while members.next_key::<de::IgnoredAny>()?.is_some() {
                    members.next_value_seed(self)?;
                    n += 1;
                }
            }
            Some(keep) => {
                while let Some(name) = members.next_key::<String>()? {
                    if keep.contains(&name.as_str()) {
                        members.next_value_seed(self)?;
                        n += 1;
                    } else {
                        members.next_value::<de::IgnoredAny>()?;
                    }
                }
            }
        }
        self.close(container, n, 2);
        Ok(())
    }
}

// ---- The second reading: the values into their reserved slots. ----

struct Building<'k> {
    tree: Tree,
    counts: Vec<u32>,
    next_container: usize,
    /// The root object's members to keep (None: all).
    root_keep: Option<&'k [&'k str]>,
}

impl Building<'_> {
    /// Reserves the slots of the next container to open: `slots_each` per element.
    fn reserve(&mut self, slots_each: usize) -> (usize, usize) {
        let elements = self.counts.get(self.next_container).copied().unwrap_or(0) as usize;
        self.next_container += 1;
        let start = self.tree.slots.len();
        let end = start + elements * slots_each;
        self.tree.slots.resize(end, Slot::NULL);
        (start, elements)
    }

    fn wide(&mut self, tag: Tag, bits: u64) -> Slot {
        self.tree.wide.push(bits);
        Slot::new(tag, self.tree.wide.len() as u64 - 1)
    }

    /// The id of a key: every key is in the lookup table, since members are found by key.
    fn intern<E: de::Error>(&mut self, text: &str) -> Result<u32, E> {
        self.store(text, true)
    }

    /// A string value's slot: stored once while the lookup table is small; past
    /// [`INTERNED_VALUES`] distinct strings a new value is stored without entering the table
    /// (nothing looks a value up by its text, and 10^7 distinct strings in one array made the
    /// table the tree's largest part and its slowest), and without an id: its slot says where
    /// it lies in `texts`.
    fn value<E: de::Error>(&mut self, text: &str) -> Result<Slot, E> {
        let enter = self.tree.strings.len() < INTERNED_VALUES;
        let tree = &mut self.tree;
        let start = tree.texts.len();
        let placed = start < 1 << (PAYLOAD_BITS - LEN_BITS) && text.len() < 1 << LEN_BITS;
        if enter || !placed || tree.find_hashed(text, tree.string_hash(text)).is_some() {
            return Ok(Slot::new(Tag::String, u64::from(self.store(text, enter)?)));
        }
        tree.texts.push_str(text);
        Ok(Slot::container(Tag::Text, start, text.len()))
    }

    fn store<E: de::Error>(&mut self, text: &str, enter: bool) -> Result<u32, E> {
        let tree = &mut self.tree;
        let hash = tree.string_hash(text);
        if let Some(id) = tree.find_hashed(text, hash) {
            return Ok(id);
        }
        let end = u32::try_from(tree.arena.len() + text.len())
            .map_err(|_| E::custom("more than 4 GiB of strings"))?;
        tree.arena.push_str(text);
        tree.ends.push(end);
        let id = tree.ends.len() as u32 - 1;
        if enter {
            let rehash = |&(_, stored): &(u32, u32)| spread(stored);
            tree.strings.insert_unique(spread(hash), (id, hash), rehash);
        }
        Ok(id)
    }
}

#[derive(Clone, Copy)]
struct Build<'b, 'k> {
    state: &'b RefCell<Building<'k>>,
}

impl<'de> DeserializeSeed<'de> for Build<'_, '_> {
    type Value = Slot;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Slot, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Build<'_, '_> {
    type Value = Slot;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E: de::Error>(self, value: bool) -> Result<Slot, E> {
        Ok(Slot::new(if value { Tag::True } else { Tag::False }, 0))
    }

    fn visit_i64<E: de::Error>(self, value: i64) -> Result<Slot, E> {
        match u64::try_from(value) {
            Ok(value) => self.visit_u64(value),
            Err(_) => Ok(self.state.borrow_mut().wide(Tag::Negative, value as u64)),
        }
    }

    fn visit_u64<E: de::Error>(self, value: u64) -> Result<Slot, E> {
        if value <= PAYLOAD {
            return Ok(Slot::new(Tag::Small, value));
        }
        Ok(self.state.borrow_mut().wide(Tag::Large, value))
    }

    fn visit_f64<E: de::Error>(self, value: f64) -> Result<Slot, E> {
        // As serde_json's own visitor: a number with no finite f64 is null.
        if !value.is_finite() {
            return Ok(Slot::NULL);
        }
        let bits = value.to_bits();
        if bits & 0xF == 0 {
            return Ok(Slot::new(Tag::Float, bits >> 4));
        }
        Ok(self.state.borrow_mut().wide(Tag::WideFloat, bits))
    }

    fn visit_str<E: de::Error>(self, value: &str) -> Result<Slot, E> {
        self.state.borrow_mut().value(value)
    }

    fn visit_unit<E: de::Error>(self) -> Result<Slot, E> {
        Ok(Slot::NULL)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut elements: A) -> Result<Slot, A::Error> {
        let (start, reserved) = self.state.borrow_mut().reserve(1);
        let mut n = 0;
        while let Some(element) = elements.next_element_seed(self)? {
            if n < reserved {
                self.state.borrow_mut().tree.slots[start + n] = element;
                n += 1;
            }
        }
        Ok(Slot::container(Tag::Array, start, n))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut members: A) -> Result<Slot, A::Error> {
        let keep = {
            let state = self.state.borrow();
            state.root_keep.filter(|_| state.next_container == 0)
        };
        let (start, reserved) = self.state.borrow_mut().reserve(2);
        let mut n = 0;
        // Whether the keys so far are in increasing string-id order.
        let mut sorted = true;
        while let Some(key) = members.next_key_seed(Key(self))? {
            let left_out = keep.is_some_and(|keep| {
                let state = self.state.borrow();
                !keep.contains(&state.tree.string(key))
            });
            if left_out {
                members.next_value::<de::IgnoredAny>()?;
                continue;
            }
            let value = members.next_value_seed(self)?;
            let tree = &mut self.state.borrow_mut().tree;
            // Keys in increasing id order, and this one above them all, is the common case
            // of a large object (its keys never seen before): nothing to look up. A large
            // object in no order takes every key, and settles its repeats when it closes.
            let after_last = n == 0 || key > tree.slots[start + 2 * n - 2].payload() as u32;
            let repeated = if (sorted && after_last) || (!sorted && n > SCANNED_MEMBERS) {
                None
            } else {
                tree.member_slot((start, n), key)
            };
            // A repeated key keeps its first place and takes the last value.
            match repeated {
                Some(at) => {
                    tree.slots[at + 1] = value;
                    tree.repeats_keys = true;
                }
                None if n < reserved => {
                    sorted &= after_last;
                    tree.slots[start + 2 * n] = Slot::new(Tag::String, u64::from(key));
                    tree.slots[start + 2 * n + 1] = value;
                    n += 1;
                }
                None => {}
            }
        }
        if !sorted && n > SCANNED_MEMBERS {
            n = self.state.borrow_mut().tree.settle_members(start, n);
        }
        Ok(Slot::container(Tag::Object, start, n))
    }
}

impl Tree {
    /// Settles the object at `start`, its `len` members as written, keys in no id order: a
    /// repeated key keeps its first place and takes its last value, and the members are
    /// indexed by key. Gives the number of members left.
    fn settle_members(&mut self, start: usize, len: usize) -> usize {
        let mut index: Vec<(u32, u32)> = (0..len)
            .map(|member| {
                (
                    self.slots[start + 2 * member].payload() as u32,
                    member as u32,
                )
            })
            .collect();
        // By key, then by place: each key's run starts at its first place.
        index.sort_unstable();
        let mut left = len;
        if index.windows(2).any(|pair| pair[0].0 == pair[1].0) {
            self.repeats_keys = true;
            left = self.drop_repeats(start, len, &mut index);
        }
        let run = self.member_index.len()..self.member_index.len() + index.len();
        self.member_index.extend(index);
        self.indexed_objects.insert(start, run);
        left
    }

    /// Moves each repeated key's last value to its first place, closes the gaps the later
    /// ones leave, and renumbers `index` (sorted by key, then place) to match, one entry a
    /// key. Gives the number of members left.
    fn drop_repeats(&mut self, start: usize, len: usize, index: &mut Vec<(u32, u32)>) -> usize {
        let mut dropped = vec![false; len];
        for run in index
            .chunk_by(|a, b| a.0 == b.0)
            .filter(|run| run.len() > 1)
        {
            let (first, last) = (run[0].1 as usize, run[run.len() - 1].1 as usize);
            self.slots[start + 2 * first + 1] = self.slots[start + 2 * last + 1];
            for &(_, later) in &run[1..] {
                dropped[later as usize] = true;
            }
        }
        let mut place = vec![0u32; len];
        let mut kept = 0;
        for member in (0..len).filter(|&member| !dropped[member]) {
            self.slots
                .copy_within(start + 2 * member..start + 2 * member + 2, start + 2 * kept);
            place[member] = kept as u32;
            kept += 1;
        }
        self.slots[start + 2 * kept..start + 2 * len].fill(Slot::NULL);
        index.dedup_by_key(|entry| entry.0);
        for entry in index.iter_mut() {
            entry.1 = place[entry.1 as usize];
        }
        kept
    }
}

/// An object's key, read into the string arena: its id.
struct Key<'b, 'k>(Build<'b, 'k>);

impl<'de> DeserializeSeed<'de> for Key<'_, '_> {
    type Value = u32;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<u32, D::Error> {
        deserializer.deserialize_str(self)
    }
}

impl<'de> Visitor<'de> for Key<'_, '_> {
    type Value = u32;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an object key")
    }

    fn visit_str<E: de::Error>(self, value: &str) -> Result<u32, E> {
        self.0.state.borrow_mut().intern(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::Value;

    fn parsed(text: &str) -> Tree {
        Tree::parse(text.as_bytes()).unwrap()
    }

    #[test]
    fn values_past_the_table_are_stored_apart_and_keys_are_still_found() {
        // More distinct string values than the table takes (an empty one and one with an
        // escape among those past it), then keys with the same texts.
        let n = INTERNED_VALUES + 10;
        let mut values: Vec<String> = (0..n).map(|i| format!("\"s{i}\"")).collect();
        values.extend([r#""""#, r#""a\"b""#, r#""s5""#].map(String::from));
        let last = format!("s{}", n - 1);
        let text = format!(r#"{{"v": [{}], "{last}": 7, "s0": 8}}"#, values.join(","));
        let tree = parsed(&text);
        let root = tree.root();
        assert!(
            tree.strings.len() <= INTERNED_VALUES + 4,
            "{}",
            tree.strings.len()
        );
        // Values past the table have no id, so no list of where each ends.
        assert!(
            tree.ends.len() <= INTERNED_VALUES + 4,
            "{}",
            tree.ends.len()
        );
        let read: Vec<&str> = (root.get("v").unwrap().as_array().unwrap().iter())
            .map(|v| v.as_str().unwrap())
            .collect();
        let expected: Vec<String> = (0..n)
            .map(|i| format!("s{i}"))
            .chain(["", "a\"b", "s5"].map(String::from))
            .collect();
        assert_eq!(read, expected);
        let written = serde_json::to_value(root).unwrap();
        let expected_value = serde_json::from_str::<Value>(&text).unwrap();
        // Keys stored after those values read as written (not shown whole: 10^6 values).
        let keys = |v: &Value| v.as_object().unwrap().keys().cloned().collect::<Vec<_>>();
        assert_eq!(keys(&written), keys(&expected_value));
        assert!(
            written == expected_value,
            "the tree writes the text's values"
        );
        assert_eq!(root.get(last.as_str()).and_then(|v| v.as_u64()), Some(7));
        assert_eq!(root.get("s0").and_then(|v| v.as_u64()), Some(8));
        assert_eq!(
            root.pointer(&format!("/{last}")).and_then(|v| v.as_u64()),
            Some(7)
        );
    }

    #[test]
    fn a_members_position_is_its_place_as_written_in_small_and_indexed_objects() {
        let small = parsed(r#"{"a": 1, "b": 2, "a": 3, "c": 4}"#);
        let small = small.root().as_object().unwrap();
        // A repeated key keeps its first place.
        let places: Vec<_> = ["a", "b", "c", "d"].map(|k| small.position(k)).into();
        assert_eq!(places, [Some(0), Some(1), Some(2), None]);
        let keys: Vec<String> = (0..1000).map(|i| format!("\"k{i}\": {i}")).collect();
        let large = parsed(&format!("{{{}}}", keys.join(", ")));
        let large = large.root().as_object().unwrap();
        assert_eq!(large.position("k0"), Some(0));
        assert_eq!(large.position("k999"), Some(999));
        assert_eq!(large.position("k1000"), None);
    }

    #[test]
    fn only_the_root_members_asked_for_are_kept_and_the_rest_is_still_read_as_json() {
        let text = r#"{"meshes": {"m": [1, {"materials": 2}]}, "materials": {"a": {"materials": 3}},
                       "asset": {"version": "1.0"}, "materials": {"b": [4]}}"#;
        let tree = Tree::parse_members(text.as_bytes(), &["materials", "asset"]).unwrap();
        let expected = serde_json::json!({"materials": {"b": [4]}, "asset": {"version": "1.0"}});
        assert_eq!(tree.root().to_value(), expected);
        let broken = r#"{"meshes": [1, 2,], "materials": {}}"#;
        assert!(Tree::parse_members(broken.as_bytes(), &["materials"]).is_err());
        // Not an object at the root: nothing to leave out.
        assert_eq!(
            Tree::parse_members(b"[1]", &["x"])
                .unwrap()
                .root()
                .to_value(),
            serde_json::json!([1])
        );
    }

    #[test]
    fn reads_every_value_as_serde_json_reads_it() {
        let text = r#"{"b":[1,-2,3.5,0.1,1e300,-0.0,"s\u00e9",true,false,null,{},[]],"a":{"k":1,"k":2,"j":[]},"c":18446744073709551615,"d":1152921504606846976,"e":-9223372036854775808,"f":1.0}"#;
        let reference: Value = serde_json::from_str(text).unwrap();
        let tree = parsed(text);
        assert_eq!(tree.root().to_value(), reference);
        assert_eq!(tree.root().to_string(), reference.to_string());
        // A repeated key keeps its first place and takes the last value.
        let a = tree.root().get("a").unwrap().as_object().unwrap();
        assert_eq!(a.keys().collect::<Vec<_>>(), ["k", "j"]);
        assert_eq!(a.get("k").unwrap().as_u64(), Some(2));
    }

    /// Every JSON file of the fixtures (and of the conformance corpus and the real exporters'
    /// files, when `../shared` is beside the checkout) reads as serde_json reads it.
    #[test]
    fn every_json_file_at_hand_reads_as_serde_json_reads_it() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let mut folders = vec![root.join("fixtures")];
        folders.extend(["conformance", "real-world"].map(|f| root.join("../shared").join(f)));
        let mut stack: Vec<_> = folders.into_iter().filter(|f| f.is_dir()).collect();
        let mut read = 0;
        while let Some(folder) = stack.pop() {
            for entry in std::fs::read_dir(&folder).unwrap().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    stack.push(path);
                    continue;
                }
                let json = path.extension().is_some_and(|e| e == "gltf" || e == "json");
                let Some(text) = json.then(|| std::fs::read(&path).ok()).flatten() else {
                    continue;
                };
                let Ok(reference) = serde_json::from_slice::<serde_json::Value>(&text) else {
                    assert!(
                        Tree::parse(&text).is_err(),
                        "{path:?} is no JSON to serde_json"
                    );
                    continue;
                };
                let tree = Tree::parse(&text).unwrap();
                assert!(tree.root().to_value() == reference, "{path:?}");
                read += 1;
            }
        }
        assert!(read >= 16, "only {read} files read");
    }

    #[test]
    fn numbers_read_as_serde_json_numbers_do() {
        let text = "[0, 7, 1.0, -3, 0.1, 1152921504606846976, 18446744073709551615]";
        let reference: Value = serde_json::from_str(text).unwrap();
        let tree = parsed(text);
        let ours = tree.root().as_array().unwrap();
        for (i, expected) in reference.as_array().unwrap().iter().enumerate() {
            let node = ours.get(i).unwrap();
            assert_eq!(node.as_u64(), expected.as_u64(), "as_u64 of {expected}");
            assert_eq!(node.as_i64(), expected.as_i64(), "as_i64 of {expected}");
            assert_eq!(node.as_f64(), expected.as_f64(), "as_f64 of {expected}");
        }
    }

    #[test]
    fn pointers_resolve_as_serde_json_resolves_them() {
        let text = r#"{"a/b":{"m~n":[10,20]},"x":[{"y":true}]}"#;
        let reference: Value = serde_json::from_str(text).unwrap();
        let tree = parsed(text);
        for pointer in [
            "",
            "/a~1b",
            "/a~1b/m~0n/1",
            "/x/0/y",
            "/x/01",
            "/x/+0",
            "/x/1",
            "/q",
            "x",
        ] {
            assert_eq!(
                tree.root().pointer(pointer).map(Node::to_value).as_ref(),
                reference.pointer(pointer),
                "{pointer}"
            );
        }
    }

    #[test]
    fn a_removed_member_is_gone_and_says_whether_it_was_null() {
        let mut tree = parsed(r#"{"a":{"x":null,"y":1,"z":2}}"#);
        assert_eq!(tree.remove("/a/x"), Some(true));
        assert_eq!(tree.remove("/a/y"), Some(false));
        assert_eq!(tree.remove("/a/y"), None);
        assert_eq!(tree.remove("/a/w"), None);
        assert_eq!(tree.root().to_string(), r#"{"a":{"z":2}}"#);
        let a = tree.root().get("a").unwrap().as_object().unwrap();
        assert_eq!(a.len(), 1);
    }

    #[test]
    fn many_repeated_keys_keep_one_member() {
        let members: Vec<String> = (0..100).map(|i| format!("\"k{}\":{i}", i % 10)).collect();
        let tree = parsed(&format!("{{{}}}", members.join(",")));
        let object = tree.root().as_object().unwrap();
        assert_eq!(object.len(), 10);
        assert_eq!(object.get("k3").unwrap().as_u64(), Some(93));
        assert_eq!(object.keys().next(), Some("k0"));
    }

    #[test]
    fn a_large_object_finds_and_removes_members_by_their_index() {
        let mut members: Vec<String> = (0..100).map(|i| format!("\"k{i}\":{i}")).collect();
        members.push("\"k50\":\"last\"".into());
        let mut tree = parsed(&format!("{{\"o\":{{{}}}}}", members.join(",")));
        let object = tree.root().get("o").unwrap().as_object().unwrap();
        assert_eq!(object.len(), 100);
        assert_eq!(object.get("k50").unwrap().as_str(), Some("last"));
        assert_eq!(object.get("k99").unwrap().as_u64(), Some(99));
        assert_eq!(tree.remove("/o/k99"), Some(false));
        assert!(tree.root().pointer("/o/k99").is_none());
        assert_eq!(tree.root().pointer("/o/k98").unwrap().as_u64(), Some(98));
    }

    /// An object's keys seen before it (as values, say) are in no id order: its members are
    /// then found through the index, whether the order breaks at once or after hundreds.
    #[test]
    fn a_large_object_finds_its_members_whatever_order_its_keys_were_first_seen_in() {
        let seen: Vec<String> = (0..300).map(|i| format!("\"k{i}\"")).collect();
        let shuffled = (0..300).map(|i| (i * 101) % 300);
        let late = (0..200).chain([250, 10, 199, 7]);
        // Out of order at once, repeats scattered: settled when the object closes.
        let repeats = shuffled.clone().chain([7, 299, 7, 0, 5]);
        for written in [
            shuffled.collect::<Vec<_>>(),
            late.collect(),
            repeats.collect(),
        ] {
            // Each value is its place as written: the last of a repeated key's must win.
            let members: Vec<String> = (written.iter().enumerate())
                .map(|(place, i)| format!("\"k{i}\":{place}"))
                .collect();
            let text = format!("[[{}],{{{},\"k7\":-7}}]", seen.join(","), members.join(","));
            let tree = parsed(&text);
            let reference: Value = serde_json::from_str(&text).unwrap();
            assert_eq!(tree.root().to_value(), reference);
            assert!(tree.repeats_keys());
            let object = tree.root().get(1).unwrap().as_object().unwrap();
            // A repeated key keeps its first place.
            for i in &written {
                let first = written.iter().position(|w| w == i);
                assert_eq!(object.position(&format!("k{i}")), first, "k{i}");
                let last = written.iter().rposition(|w| w == i).unwrap() as u64;
                let value = object.get(&format!("k{i}")).unwrap();
                assert!(value.as_u64() == Some(last) || *i == 7, "k{i}");
            }
            assert_eq!(object.get("k7").unwrap().as_i64(), Some(-7));
            assert!(object.get("k300").is_none());
            let distinct: std::collections::HashSet<_> = written.iter().collect();
            assert_eq!(object.len(), distinct.len());
        }
    }

    #[test]
    fn members_are_removed_in_any_order_and_only_when_taken() {
        let members: Vec<String> = (0..50).map(|i| format!("\"k{i}\":{i}")).collect();
        let mut tree = parsed(&format!("{{\"o\":{{{}}}}}", members.join(",")));
        assert!(!tree.repeats_keys());
        let ids: Vec<StringId> = tree
            .root()
            .get("o")
            .unwrap()
            .as_object()
            .unwrap()
            .keys_with_ids()
            .map(|(id, _)| id)
            .collect();
        // Every third, backwards, then all in order: the even ones go.
        let even = |value: Node| value.as_u64().is_some_and(|v| v % 2 == 0);
        let backwards = ids.iter().rev().step_by(3).copied();
        assert_eq!(tree.remove_members("/o", backwards, even), 8);
        assert_eq!(tree.remove_members("/o", ids.iter().copied(), even), 17);
        let odd: Vec<String> = (1..50)
            .step_by(2)
            .map(|i| format!("\"k{i}\":{i}"))
            .collect();
        assert_eq!(
            tree.root().to_string(),
            format!("{{\"o\":{{{}}}}}", odd.join(","))
        );
        assert_eq!(tree.remove_members("/x", ids.iter().copied(), |_| true), 0);
    }

    #[test]
    fn a_value_costs_one_slot() {
        let zeros = format!("[{}]", vec!["0"; 1000].join(","));
        let tree = parsed(&zeros);
        assert_eq!(tree.slots.len(), 1000);
        assert!(tree.wide.is_empty());
        // Strings are stored once however often they are written.
        let names = format!("[{}]", vec!["\"node\""; 1000].join(","));
        assert_eq!(parsed(&names).arena, "node");
    }

    #[test]
    fn the_number_of_values_is_bounded() {
        assert!(Tree::parse_within(b"[1,2,3]", 4, None).is_ok());
        let error = Tree::parse_within(b"[1,2,3,4]", 4, None).err().unwrap();
        assert!(error.to_string().contains("more than"), "{error}");
        assert_eq!(error.column(), 8, "at the fourth element");
    }

    #[test]
    fn invalid_json_fails_as_serde_json_fails() {
        for text in ["[1,", "{\"a\" 1}", "[1] x", "\"\\q\""] {
            let ours = Tree::parse(text.as_bytes()).err().unwrap();
            let theirs = serde_json::from_str::<Value>(text).err().unwrap();
            assert_eq!(ours.to_string(), theirs.to_string(), "{text}");
        }
    }
}
