//! The lights a shader loops over ([`crate::Ctx::light_list`]): indices into
//! `Shading::lights`, held inline up to [`INLINE`] of them, so that the usual light list
//! (a scene's few lights, asked for at every shaded point) costs no allocation.

use std::ops::Deref;

/// How many light indices a [`LightList`] holds without allocating.
pub const INLINE: usize = 8;

/// A list of light indices (into `Shading::lights`), in order; a slice through `Deref`.
#[derive(Clone, Debug)]
pub enum LightList {
    /// Up to [`INLINE`] indices: the first `len` of the array.
    Inline {
        /// How many of `lights` are in the list.
        len: u8,
        /// The indices (the rest zero).
        lights: [u32; INLINE],
    },
    /// More than [`INLINE`] indices.
    Heap(Vec<u32>),
}

impl LightList {
    /// The empty list.
    pub const fn new() -> LightList {
        LightList::Inline { len: 0, lights: [0; INLINE] }
    }

    /// Appends light `light`.
    pub fn push(&mut self, light: u32) {
        match self {
            LightList::Inline { len, lights } if (*len as usize) < INLINE => {
                lights[*len as usize] = light;
                *len += 1;
            }
            LightList::Inline { lights, .. } => {
                let mut heap = Vec::with_capacity(2 * INLINE);
                heap.extend_from_slice(lights);
                heap.push(light);
                *self = LightList::Heap(heap);
            }
            LightList::Heap(heap) => heap.push(light),
        }
    }

    /// Removes consecutive repeated indices (as `Vec::dedup`).
    pub fn dedup(&mut self) {
        match self {
            LightList::Inline { len, lights } => {
                let mut kept = 0;
                for i in 0..*len as usize {
                    if kept == 0 || lights[kept - 1] != lights[i] {
                        lights[kept] = lights[i];
                        kept += 1;
                    }
                }
                *len = kept as u8;
            }
            LightList::Heap(heap) => heap.dedup(),
        }
    }
}

impl Default for LightList {
    fn default() -> LightList {
        LightList::new()
    }
}

impl Deref for LightList {
    type Target = [u32];

    fn deref(&self) -> &[u32] {
        match self {
            LightList::Inline { len, lights } => &lights[..*len as usize],
            LightList::Heap(heap) => heap,
        }
    }
}

impl FromIterator<u32> for LightList {
    fn from_iter<I: IntoIterator<Item = u32>>(iter: I) -> LightList {
        let mut list = LightList::new();
        for light in iter {
            list.push(light);
        }
        list
    }
}

/// The indices of a [`LightList`], by value.
#[derive(Clone, Debug)]
pub struct IntoIter {
    list: LightList,
    next: usize,
}

impl Iterator for IntoIter {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        let light = self.list.get(self.next).copied()?;
        self.next += 1;
        Some(light)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.list.len() - self.next;
        (left, Some(left))
    }
}

impl ExactSizeIterator for IntoIter {}

impl IntoIterator for LightList {
    type Item = u32;
    type IntoIter = IntoIter;

    fn into_iter(self) -> IntoIter {
        IntoIter { list: self, next: 0 }
    }
}

impl<'l> IntoIterator for &'l LightList {
    type Item = &'l u32;
    type IntoIter = std::slice::Iter<'l, u32>;

    fn into_iter(self) -> std::slice::Iter<'l, u32> {
        self.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pushing, dedup and iteration agree with a `Vec` on both sides of the inline size.
    #[test]
    fn agrees_with_vec() {
        for n in [0usize, 1, 3, INLINE, INLINE + 1, 3 * INLINE] {
            let items: Vec<u32> = (0..n as u32).flat_map(|i| [i / 2, i / 2]).collect();
            let list: LightList = items.iter().copied().collect();
            assert_eq!(&*list, &items[..], "n = {n}");
            assert_eq!(list.clone().into_iter().collect::<Vec<_>>(), items, "n = {n}");
            let (mut list, mut items) = (list, items);
            list.dedup();
            items.dedup();
            assert_eq!(&*list, &items[..], "dedup, n = {n}");
            assert_eq!(list.into_iter().len(), items.len());
        }
    }
}
