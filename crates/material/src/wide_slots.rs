//! Per-thread storage for the wide lobe sums of materials that vary per hit, so that
//! lowering one at a hit allocates nothing once a thread has warmed up.
//!
//! A [`bsdf::WideLobes`] sum is too large to copy into each hit's BSDF; the BSDF shares it
//! ([`bsdf::SharedLobes`], an `Arc`). A material whose sum is the same at every hit builds
//! it once ([`crate::SurfaceModel::MdlWide`]); one whose sum varies over the surface
//! lowers a new sum at each hit. Each thread keeps a ring of [`SLOTS`] shared sums: a hit's
//! sum is written into the next slot — in place when no BSDF still holds that slot's sum,
//! else into a new allocation that replaces the slot's — and the hit's material names the
//! slot ([`WideSlot`], plain data: the path tracer's hit materials keep no reference count
//! and no drop glue). Its BSDF takes a share of the slot's sum when it is built
//! ([`WideSlot::lobes`]). A slot is reused only after [`SLOTS`] more sums were lowered on
//! the same thread; both engines build a hit's BSDF before they lower another material
//! (see `render::integrator`, `render::tracer`), and each slot carries a generation that
//! the BSDF checks, so a material kept past its slot's reuse is detected, not misread.

use std::cell::RefCell;

use bsdf::{SharedLobes, WideLobes};

/// Wide sums a thread keeps for its hits.
pub const SLOTS: usize = 16;

/// A hit's wide lobe sum: a slot of the thread's ring and the generation it was written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WideSlot {
    index: u32,
    generation: u32,
    /// Whether light enters the surface ([`bsdf::lobes::LobeSum::has_inside`] of the sum),
    /// kept with the slot so that the engines ask it without the thread's ring.
    inside: bool,
}

/// The ring of one thread.
struct Ring {
    slots: Vec<(SharedLobes, u32)>,
    next: usize,
}

thread_local! {
    static RING: RefCell<Ring> = const { RefCell::new(Ring { slots: Vec::new(), next: 0 }) };
}

impl WideSlot {
    /// Keeps `sum` in the calling thread's ring: in place of the next slot's sum when
    /// nothing shares that one, else in a new allocation.
    pub fn store(sum: &WideLobes) -> WideSlot {
        RING.with_borrow_mut(|ring| {
            let index = ring.next;
            ring.next = (index + 1) % SLOTS;
            if index == ring.slots.len() {
                ring.slots.push((SharedLobes::new(*sum), 0));
            } else {
                let (shared, generation) = &mut ring.slots[index];
                match shared.get_mut() {
                    Some(in_place) => *in_place = *sum,
                    None => *shared = SharedLobes::new(*sum),
                }
                *generation = generation.wrapping_add(1);
            }
            WideSlot { index: index as u32, generation: ring.slots[index].1, inside: sum.has_inside() }
        })
    }

    /// Whether light can enter the surface (a solid glass lobe in the sum), as for a
    /// constant sum ([`crate::SurfaceModel::has_inside`]): media inside are tracked.
    pub fn has_inside(self) -> bool {
        self.inside
    }

    /// A share of the sum (for a BSDF), if the slot still holds it: `None` on another
    /// thread or after [`SLOTS`] more sums were stored.
    pub fn lobes(self) -> Option<SharedLobes> {
        RING.with_borrow(|ring| {
            let (shared, generation) = ring.slots.get(self.index as usize)?;
            (*generation == self.generation).then(|| shared.clone())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bsdf::lobes::Lobe;
    use bsdf::Rgb;

    fn sum(w: f32) -> WideLobes {
        let mut s = WideLobes::default();
        assert!(s.push(Rgb::splat(w), Lobe::Translucent));
        s
    }

    /// A sum stored after the previous one's shares are gone reuses the slot's memory;
    /// one stored while a BSDF still holds the slot's sum leaves that sum as it was.
    #[test]
    fn slots_are_reused_in_place_unless_shared() {
        let first = WideSlot::store(&sum(0.1));
        let held = first.lobes().unwrap();
        let at = |s: &SharedLobes| std::ptr::from_ref::<WideLobes>(&**s) as usize;
        let address = at(&held);
        drop(held);
        // Around the ring: the same slot, written in place.
        let mut last = first;
        for k in 0..SLOTS {
            last = WideSlot::store(&sum(0.2 + k as f32 * 0.01));
        }
        assert_eq!(last.index, first.index);
        assert_eq!(first.lobes(), None, "the first sum's generation is gone");
        let again = last.lobes().unwrap();
        assert_eq!(at(&again), address, "written in place");
        assert_eq!(again.parts().next().unwrap().0, Rgb::splat(0.2 + (SLOTS - 1) as f32 * 0.01));
        // Held while its slot comes round again: the slot takes a new allocation and the
        // holder keeps its sum.
        let stored: Vec<WideSlot> = (0..SLOTS).map(|_| WideSlot::store(&sum(0.9))).collect();
        let newer = stored.iter().find(|s| s.index == last.index).unwrap().lobes().unwrap();
        assert_ne!(at(&again), at(&newer));
        assert_eq!(newer.parts().next().unwrap().0, Rgb::splat(0.9));
        assert_eq!(again.parts().next().unwrap().0, Rgb::splat(0.2 + (SLOTS - 1) as f32 * 0.01));
    }
}
