//! New names beside taken ones: `base`, else the first of `base_2`, `base_3`, … not taken, found in constant time per name however often a base is asked for.

use std::collections::HashMap;

/// Per base name, the suffix to try next: the ones below it were handed out or taken.
#[derive(Default, Debug, Clone)]
pub struct Suffixes(HashMap<String, usize>);

impl Suffixes {
    /// A name no `taken` call accepts: `base` itself when free, else `base_k` for the
    /// smallest `k ≥ 2` not tried for this base before. The caller records it as taken.
    pub fn unique(&mut self, base: &str, taken: impl Fn(&str) -> bool) -> String {
        if !taken(base) {
            return base.to_string();
        }
        let k = self.0.entry(base.to_string()).or_insert(2);
        loop {
            let name = format!("{base}_{k}");
            *k += 1;
            if !taken(&name) {
                return name;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Suffixes;
    use std::collections::BTreeSet;

    #[test]
    fn names_are_new_and_in_order() {
        let mut taken: BTreeSet<String> = ["x", "x_3"].iter().map(|s| s.to_string()).collect();
        let mut suffixes = Suffixes::default();
        let mut got = Vec::new();
        for base in ["x", "x", "y", "x", "y"] {
            let name = suffixes.unique(base, |n| taken.contains(n));
            assert!(taken.insert(name.clone()), "{name} handed out twice");
            got.push(name);
        }
        assert_eq!(got, ["x_2", "x_4", "y", "x_5", "y_2"]);
    }
}
