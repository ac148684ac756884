//! `--shard K/N` and `--jobs N`, as `stljit fuzz` and `stljit run` take them: item `i` of a
//! list belongs to shard `i mod N` (0-based `K`), so N machines each running one shard cover the
//! list exactly once, whatever each one's job count.

/// Parses `K/N` with `0 <= K < N`.
pub(crate) fn parse_shard(s: &str) -> Result<(u64, u64), String> {
    let (k, n) = s
        .split_once('/')
        .ok_or_else(|| format!("`{s}`: expected K/N, e.g. 0/4"))?;
    let k: u64 = k.trim().parse().map_err(|_| format!("`{s}`: bad K"))?;
    let n: u64 = n.trim().parse().map_err(|_| format!("`{s}`: bad N"))?;
    if n == 0 || k >= n {
        return Err(format!("`{s}`: need 0 <= K < N"));
    }
    Ok((k, n))
}

#[cfg(test)]
mod tests {
    use super::parse_shard;

    #[test]
    fn shards_are_k_of_n() {
        assert_eq!(parse_shard("0/4"), Ok((0, 4)));
        assert_eq!(parse_shard(" 3 / 4 "), Ok((3, 4)));
        assert!(parse_shard("4/4").is_err());
        assert!(parse_shard("1/0").is_err());
        assert!(parse_shard("x").is_err());
    }
}
