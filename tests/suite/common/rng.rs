//! A small deterministic random generator (xorshift64*) for the differential tests, seeded per case.
#![allow(dead_code)]

/// A small deterministic generator (xorshift64*), seeded per case.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        // splitmix64 of the seed, so that neighbouring seeds give unrelated streams.
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        Rng((z ^ (z >> 31)) | 1)
    }
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }
    pub fn chance(&mut self, percent: u64) -> bool {
        self.below(100) < percent
    }
    pub fn pick<'a, T>(&mut self, xs: &'a [T]) -> &'a T {
        &xs[self.below(xs.len() as u64) as usize]
    }
}

/// Inputs that each hold a random value for a random stretch of scans: a new value is
/// drawn (1 with `percent` % chance) when an input's stretch ends, and stretches last 1 to
/// `longest` scans.
pub struct HeldInputs {
    values: std::collections::BTreeMap<String, bool>,
    left: Vec<u64>,
    percent: u64,
    longest: u64,
}

impl HeldInputs {
    pub fn new(names: &[&str], percent: u64, longest: u64) -> HeldInputs {
        let values = names.iter().map(|n| (n.to_string(), false)).collect();
        HeldInputs { values, left: vec![0; names.len()], percent, longest }
    }

    /// The inputs of the next scan.
    pub fn next(&mut self, rng: &mut Rng) -> &std::collections::BTreeMap<String, bool> {
        for (left, value) in self.left.iter_mut().zip(self.values.values_mut()) {
            if *left == 0 {
                *value = rng.chance(self.percent);
                *left = 1 + rng.below(self.longest);
            }
            *left -= 1;
        }
        &self.values
    }
}
