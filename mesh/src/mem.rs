//! Fallible allocation. Buffers whose size depends on the input (vertices,
//! faces, corners, patches) are reserved through `try_reserve`, so that an
//! allocation the system refuses becomes an [`OutOfMemory`] error that the
//! caller can report, instead of an abort of the whole process.
//!
//! The helpers reserve the full size up front; pushes that stay within the
//! reservation do not allocate again.
//!
//! The analysis (topology, whole-mesh steps, the adaptive refinement with
//! its levels, points and patches, the plan) and the tessellations (the
//! streaming weld, [`crate::tessellate::StreamTessellator`], and
//! [`crate::tessellate::try_tessellate`]), the closedness check
//! ([`crate::tessellate::try_closed_and_oriented`]) and the OBJ text
//! ([`crate::tessellate::try_write_obj`]) reserve this way; what they
//! allocate as it is has the size of one vertex's neighbourhood (a fan, a
//! stencil row being built, a cap's c-net) or of one patch's layout.
//! `tests/out_of_memory.rs` refuses each of their allocations of 4 KB or
//! more in turn.

use alloc::vec::Vec;
use core::fmt;
use core::hash::{BuildHasher, Hash};

/// An allocation of `bytes` bytes could not be made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct OutOfMemory {
    /// The size asked for (`usize::MAX` when the size itself overflowed).
    pub bytes: usize,
}

impl OutOfMemory {
    /// The error for `n` items of `T`.
    pub fn of<T>(n: usize) -> Self {
        OutOfMemory {
            bytes: bytes_of::<T>(n),
        }
    }

    /// The message without a leading subject: `out of memory (could not
    /// allocate N bytes)`.
    pub fn message(&self) -> alloc::string::String {
        if self.bytes == usize::MAX {
            alloc::string::String::from(
                "out of memory (the size asked for exceeds the address space)",
            )
        } else {
            alloc::format!("out of memory (could not allocate {} bytes)", self.bytes)
        }
    }
}

impl fmt::Display for OutOfMemory {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message())
    }
}

impl core::error::Error for OutOfMemory {}

/// Bytes taken by `n` items of `T` (saturating).
pub fn bytes_of<T>(n: usize) -> usize {
    n.saturating_mul(core::mem::size_of::<T>())
}

/// Room for `additional` more items in `v`, or the error naming the bytes
/// that the new buffer would take.
#[inline]
pub fn reserve<T>(v: &mut Vec<T>, additional: usize) -> Result<(), OutOfMemory> {
    v.try_reserve(additional)
        .map_err(|_| OutOfMemory::of::<T>(v.len().saturating_add(additional)))
}

/// Room for `additional` more bytes in `s` (growing as `push_str` does).
#[inline]
pub fn reserve_str(s: &mut alloc::string::String, additional: usize) -> Result<(), OutOfMemory> {
    if s.capacity() - s.len() >= additional {
        return Ok(());
    }
    s.try_reserve(additional)
        .map_err(|_| OutOfMemory::of::<u8>(s.len().saturating_add(additional)))
}

/// Room for exactly `additional` more items in `v` (no growth margin).
pub fn reserve_exact<T>(v: &mut Vec<T>, additional: usize) -> Result<(), OutOfMemory> {
    v.try_reserve_exact(additional)
        .map_err(|_| OutOfMemory::of::<T>(v.len().saturating_add(additional)))
}

/// An empty vector with room for `capacity` items.
pub fn with_capacity<T>(capacity: usize) -> Result<Vec<T>, OutOfMemory> {
    let mut v = Vec::new();
    reserve_exact(&mut v, capacity)?;
    Ok(v)
}

/// `len` copies of `value` (the fallible `vec![value; len]`).
pub fn filled<T: Clone>(len: usize, value: T) -> Result<Vec<T>, OutOfMemory> {
    let mut v = with_capacity(len)?;
    v.resize(len, value);
    Ok(v)
}

/// Appends `x`, growing the buffer (doubling, as `push` does) fallibly.
#[inline]
pub fn push<T>(v: &mut Vec<T>, x: T) -> Result<(), OutOfMemory> {
    if v.len() == v.capacity() {
        reserve(v, 1)?;
    }
    v.push(x);
    Ok(())
}

/// The items of `iter` in a vector, reserved for the iterator's lower size
/// bound up front and grown fallibly past it. An iterator that knows its
/// length exactly is copied in one `extend` (no check per item).
pub fn collect<T>(iter: impl IntoIterator<Item = T>) -> Result<Vec<T>, OutOfMemory> {
    let iter = iter.into_iter();
    let (lower, upper) = iter.size_hint();
    let mut v = with_capacity(lower)?;
    if upper == Some(lower) {
        v.extend(iter);
        return Ok(v);
    }
    for x in iter {
        push(&mut v, x)?;
    }
    Ok(v)
}

/// A copy of `items`.
pub fn to_vec<T: Clone>(items: &[T]) -> Result<Vec<T>, OutOfMemory> {
    let mut v = with_capacity(items.len())?;
    v.extend_from_slice(items);
    Ok(v)
}

/// The value, or the abort a `Vec`'s growth makes when the system refuses
/// an allocation: for callers whose signature has no error to return.
pub fn or_abort<T>(r: Result<T, OutOfMemory>) -> T {
    match r {
        Ok(t) => t,
        Err(e) => {
            let layout = core::alloc::Layout::from_size_align(e.bytes, 1)
                .unwrap_or(core::alloc::Layout::new::<u8>());
            alloc::alloc::handle_alloc_error(layout)
        }
    }
}

/// Room for `additional` more entries in a hash map.
#[inline]
pub fn reserve_map<K, V, S>(
    m: &mut hashbrown::HashMap<K, V, S>,
    additional: usize,
) -> Result<(), OutOfMemory>
where
    K: Eq + Hash,
    S: BuildHasher,
{
    m.try_reserve(additional)
        .map_err(|_| OutOfMemory::of::<(K, V)>(m.len().saturating_add(additional)))
}

/// Room for `additional` more entries in a hash set.
#[inline]
pub fn reserve_set<K, S>(
    m: &mut hashbrown::HashSet<K, S>,
    additional: usize,
) -> Result<(), OutOfMemory>
where
    K: Eq + Hash,
    S: BuildHasher,
{
    m.try_reserve(additional)
        .map_err(|_| OutOfMemory::of::<K>(m.len().saturating_add(additional)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use alloc::string::ToString;

    #[test]
    fn absurd_sizes_are_errors() {
        // More bytes than the address space: refused before asking the
        // allocator.
        let e = with_capacity::<[f64; 3]>(usize::MAX / 8).unwrap_err();
        assert_eq!(e.bytes, usize::MAX);
        assert!(e.message().starts_with("out of memory"));
        // Representable, but no machine has it (2^50 bytes): the allocator
        // refuses.
        let e = filled::<u64>(1 << 47, 0).unwrap_err();
        assert_eq!(e.bytes, 1 << 50);
        assert_eq!(
            e.to_string(),
            "out of memory (could not allocate 1125899906842624 bytes)"
        );
        let mut m: hashbrown::HashMap<u64, u64> = hashbrown::HashMap::new();
        assert!(reserve_map(&mut m, usize::MAX / 4).is_err());
        let mut s: hashbrown::HashSet<u64> = hashbrown::HashSet::new();
        assert!(reserve_set(&mut s, usize::MAX / 4).is_err());
    }

    #[test]
    fn helpers_fill_as_the_infallible_forms() {
        assert_eq!(filled(3, 7u8).unwrap(), alloc::vec![7u8; 3]);
        assert_eq!(collect(0..5).unwrap(), (0..5).collect::<Vec<_>>());
        assert_eq!(
            collect((0..9).filter(|x| x % 2 == 0)).unwrap(),
            [0, 2, 4, 6, 8]
        );
        assert_eq!(to_vec(&[1, 2]).unwrap(), [1, 2]);
        let mut v = with_capacity::<u32>(2).unwrap();
        assert!(v.capacity() >= 2 && v.is_empty());
        for i in 0..100 {
            push(&mut v, i).unwrap();
        }
        assert_eq!(v.len(), 100);
    }
}
