//! The firmware's report lines: `key i… x…`, integer indices first, then
//! numbers (`defmt` prints `f32` with `ryu`: always a `.` or an exponent, and
//! the shortest digits that read back to the same bits).

/// One parsed line.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// First word.
    pub key: String,
    /// Leading integer fields.
    pub idx: Vec<usize>,
    /// The numbers after them.
    pub vals: Vec<f64>,
}

impl Entry {
    /// An entry from its parts.
    pub fn new(key: &str, idx: &[usize], vals: &[f64]) -> Self {
        Entry {
            key: key.into(),
            idx: idx.to_vec(),
            vals: vals.to_vec(),
        }
    }

    /// `key i j …`, the identity two entries are matched by.
    pub fn id(&self) -> String {
        let mut s = self.key.clone();
        for i in &self.idx {
            s.push(' ');
            s.push_str(&i.to_string());
        }
        s
    }
}

/// Parses one line; `None` if a field is neither an index nor a number.
pub fn parse(line: &str) -> Option<Entry> {
    let mut words = line.split_whitespace();
    let key = words.next()?.to_string();
    let mut idx = Vec::new();
    let mut vals = Vec::new();
    for w in words {
        let integral = w.bytes().all(|b| b.is_ascii_digit());
        if integral && vals.is_empty() {
            idx.push(w.parse().ok()?);
        } else {
            // Read as f32 first: the firmware's numbers are f32, and this
            // recovers their exact bits.
            vals.push(w.parse::<f32>().ok()? as f64);
        }
    }
    Some(Entry { key, idx, vals })
}
