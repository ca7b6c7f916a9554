//! IEC 61131-3 literals shared by the front ends: durations (`T#5s`, `TIME#1h2m`, 1.0's `00:00:00.100`) in microseconds (a part finer than 1 µs is dropped).

/// An IEC duration literal (`T#5s`, `TIME#1h2m`, `t#1.5s`, `T#-0s`) or a 1.0 interval
/// (`00:00:00.100000`), in microseconds.
pub fn parse_duration(text: &str) -> Option<u64> {
    let t = text.trim();
    if let Some((h, rest)) = t.split_once(':') {
        let (m, s) = rest.split_once(':')?;
        let (h, m): (u64, u64) = (h.parse().ok()?, m.parse().ok()?);
        let secs = parse_decimal(s, 1_000_000)?;
        return (h * 3600 + m * 60).checked_mul(1_000_000)?.checked_add(secs);
    }
    let upper = t.to_ascii_uppercase();
    let body = upper
        .strip_prefix("TIME#")
        .or_else(|| upper.strip_prefix("T#"))
        .or_else(|| upper.strip_prefix("LTIME#"))
        .or_else(|| upper.strip_prefix("LT#"))?;
    let body: String = body.chars().filter(|c| *c != '_').collect();
    if body.is_empty() || body.starts_with('-') {
        return None;
    }
    let units: [(&str, u64); 7] = [
        ("MS", 1_000),
        ("US", 1),
        ("NS", 0),
        ("D", 86_400_000_000),
        ("H", 3_600_000_000),
        ("M", 60_000_000),
        ("S", 1_000_000),
    ];
    let mut rest = body.as_str();
    let mut total: u64 = 0;
    while !rest.is_empty() {
        let n = rest.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(rest.len());
        let (num, after) = rest.split_at(n);
        if num.is_empty() {
            return None;
        }
        let (unit, scale) = units.iter().find(|(u, _)| after.starts_with(u))?;
        let v = if *scale == 0 { Some(0) } else { parse_decimal(num, *scale) }?;
        total = total.checked_add(v)?;
        rest = &after[unit.len()..];
    }
    Some(total)
}

/// `12.5` × `scale`, truncated.
fn parse_decimal(s: &str, scale: u64) -> Option<u64> {
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    let int: u64 = if int.is_empty() { 0 } else { int.parse().ok()? };
    let mut v = int.checked_mul(scale)?;
    let mut unit = scale;
    for c in frac.chars() {
        unit /= 10;
        v = v.checked_add(u64::from(c.to_digit(10)?) * unit)?;
    }
    Some(v)
}

/// An IEC integer literal as PLCopen and ST write it (`5`, `-5`, `16#FF`, `2#1010_0101`,
/// `INT#-3`, `DINT#16#FF`): its value and the type name its prefix gives (upper case),
/// if any. `None` for anything else (reals, booleans, durations).
pub fn int_literal(text: &str) -> Option<(i128, Option<String>)> {
    let t = text.trim();
    let (ty, value) = match t.split_once('#') {
        Some((ty, v)) if ty.chars().all(|c| c.is_ascii_alphabetic()) && !ty.is_empty() => {
            (Some(ty.to_ascii_uppercase()), v)
        }
        _ => (None, t),
    };
    let digits: String = value.chars().filter(|c| *c != '_').collect();
    let (negative, digits) = match digits.strip_prefix('-') {
        Some(d) => (true, d.to_string()),
        None => (false, digits.strip_prefix('+').unwrap_or(&digits).to_string()),
    };
    let v = match digits.split_once('#') {
        Some((base, d)) => {
            let b: u32 = base.parse().ok().filter(|b| [2, 8, 16].contains(b))?;
            if d.is_empty() || d.starts_with(['-', '+']) {
                return None;
            }
            i128::from_str_radix(d, b).ok()?
        }
        None if !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit()) => {
            digits.parse::<i128>().ok()?
        }
        None => return None,
    };
    Some((if negative { -v } else { v }, ty))
}
