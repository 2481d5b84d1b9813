//! `--shard I/N`: a job array's share of a batch file's rows, round robin.

use serde::{Deserialize, Serialize};

/// `--shard I/N`: the rows (numbered from 1) r with (r − 1) mod N = I − 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Whether row `row` (from 1) belongs to this shard.
    pub fn holds(&self, row: usize) -> bool {
        (row - 1) % self.count == self.index - 1
    }
}

/// Parses `I/N` with 1 ≤ I ≤ N ≤ 100000.
pub fn parse_shard(text: &str) -> Result<Shard, String> {
    let bad = || format!("'{text}' is not I/N with 1 ≤ I ≤ N (e.g. 2/4)");
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let index: usize = i.trim().parse().map_err(|_| bad())?;
    let count: usize = n.trim().parse().map_err(|_| bad())?;
    if index == 0 || index > count || count > 100_000 {
        return Err(bad());
    }
    Ok(Shard { index, count })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_split_rows_round_robin() {
        let s = parse_shard("2/3").unwrap();
        let rows: Vec<usize> = (1..=8).filter(|&r| s.holds(r)).collect();
        assert_eq!(rows, [2, 5, 8]);
        for bad in ["0/3", "4/3", "3", "a/b", "1/0", ""] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
