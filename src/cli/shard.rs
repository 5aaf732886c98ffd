//! `check --shard K/N`: one of N disjoint parts of the files a run would check, so that a CI
//! matrix of N jobs covers every file exactly once.

use std::path::Path;

/// Part `index` (0-based) of `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    index: u64,
    count: u64,
}

impl Shard {
    /// Parses `K/N` (1 ≤ K ≤ N), as clap's value parser.
    pub fn parse(text: &str) -> Result<Shard, String> {
        let wrong = || format!("'{text}': expected K/N with 1 ≤ K ≤ N, e.g. 2/4");
        let (k, n) = text.split_once('/').ok_or_else(wrong)?;
        let (k, n): (u64, u64) = (
            k.trim().parse().map_err(|_| wrong())?,
            n.trim().parse().map_err(|_| wrong())?,
        );
        if k == 0 || k > n {
            return Err(wrong());
        }
        Ok(Shard {
            index: k - 1,
            count: n,
        })
    }

    /// Whether `path` belongs to this part. Decided by the path's own text (as the run names
    /// it), never by its place in a listing: the parts do not depend on the file system's
    /// order, and a file added to a folder moves no other file to another part.
    pub fn contains(self, path: &Path) -> bool {
        stable_hash(path.to_string_lossy().replace('\\', "/").as_bytes()) % self.count == self.index
    }
}

/// FNV-1a (64-bit): the same on every machine and every build, unlike the standard
/// library's hashers, so that the N jobs of a matrix agree.
fn stable_hash(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |hash, &byte| {
        (hash ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_path_is_in_exactly_one_part() {
        let paths: Vec<String> = (0..500).map(|i| format!("assets/model-{i}.glb")).collect();
        for n in [1, 2, 3, 7] {
            let shards: Vec<Shard> = (1..=n)
                .map(|k| Shard::parse(&format!("{k}/{n}")).unwrap())
                .collect();
            for path in &paths {
                let holders = shards
                    .iter()
                    .filter(|s| s.contains(Path::new(path)))
                    .count();
                assert_eq!(holders, 1, "{path} in {holders} of {n} parts");
            }
            // Near even: no part is empty or holds twice its share.
            for shard in &shards {
                let held = paths
                    .iter()
                    .filter(|p| shard.contains(Path::new(p)))
                    .count();
                assert!(
                    held > 0 && held < 2 * paths.len() / n as usize + 10,
                    "{shard:?} holds {held}"
                );
            }
        }
    }

    #[test]
    fn the_hash_is_fixed_across_builds() {
        // FNV-1a's published test vector: a change of hasher would reshuffle every matrix.
        assert_eq!(stable_hash(b"a"), 0xaf63_dc4c_8601_ec8c);
    }

    #[test]
    fn only_k_of_n_with_one_to_n_is_a_shard() {
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", "/2", "-1/2"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(Shard::parse(" 2/ 5").unwrap(), Shard { index: 1, count: 5 });
    }
}
