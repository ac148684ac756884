//! Durations as the CLI, the Python package and the FMU export take them: `10ms`, `1.5s`, `2m`, `24h`, `250` (ms). Virtual time is kept in
//! whole milliseconds.

/// Parses a duration into milliseconds.
pub fn parse_duration(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale = match unit.trim() {
        "" | "ms" => 1.0,
        "s" => 1_000.0,
        "m" | "min" => 60_000.0,
        "h" => 3_600_000.0,
        "d" => 86_400_000.0,
        other => {
            return Err(format!(
                "`{text}`: unknown unit `{other}` (use ms, s, m, h or d, e.g. 10ms, 1.5s, 24h)"
            ));
        }
    };
    let value: f64 = number
        .parse()
        .map_err(|_| format!("`{text}` is not a duration (e.g. 10ms, 1.5s, 2m, 24h)"))?;
    let ms = value * scale;
    if !(ms.is_finite() && (0.0..=1e15).contains(&ms)) {
        return Err(format!("`{text}` is out of range"));
    }
    if ms.fract() != 0.0 {
        return Err(format!("`{text}` is not a whole number of milliseconds"));
    }
    Ok(ms as u64)
}

/// Formats milliseconds the way a person reads them: `950 ms`, `12.5 s`, `2 h 00 min 01.250 s`.
pub fn format_ms(ms: u64) -> String {
    if ms < 1_000 {
        return format!("{ms} ms");
    }
    if ms < 60_000 {
        return format!("{}.{:03} s", ms / 1000, ms % 1000);
    }
    let (h, rest) = (ms / 3_600_000, ms % 3_600_000);
    let (m, rest) = (rest / 60_000, rest % 60_000);
    let s = format!("{:02}.{:03} s", rest / 1000, rest % 1000);
    if h == 0 {
        format!("{m} min {s}")
    } else {
        format!("{h} h {m:02} min {s}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_documented_forms() {
        assert_eq!(parse_duration("10ms"), Ok(10));
        assert_eq!(parse_duration("1.5s"), Ok(1500));
        assert_eq!(parse_duration("2m"), Ok(120_000));
        assert_eq!(parse_duration("24h"), Ok(86_400_000));
        assert_eq!(parse_duration("250"), Ok(250));
        assert!(parse_duration("1.5ms").is_err());
        assert!(parse_duration("3 parsecs").is_err());
        assert!(parse_duration("").is_err());
        assert!(parse_duration("-1s").is_err());
    }

    #[test]
    fn formats_for_people() {
        assert_eq!(format_ms(950), "950 ms");
        assert_eq!(format_ms(12_500), "12.500 s");
        assert_eq!(format_ms(120_000), "2 min 00.000 s");
        assert_eq!(format_ms(86_400_000), "24 h 00 min 00.000 s");
    }
}
