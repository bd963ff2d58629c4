//! The media a classic-engine ray is inside (mental ray's refraction chain): the materials
//! whose surfaces it entered through refraction or transparency rays and has not left,
//! innermost last, at any depth.
//!
//! Most rays are inside no medium or a few, so the first [`INLINE_MEDIA`] entries live in
//! the state itself (a [`crate::State`] is no larger than with the fixed array of eight
//! that it replaces); a deeper chain, or one holding a medium evaluated where the ray
//! entered it (a volume that varies over its object's surface), moves to a shared heap
//! copy, cloned only when a ray changes it. Nothing is forgotten.

use std::sync::Arc;

/// How many media a chain keeps inline before it moves to the heap.
pub const INLINE_MEDIA: usize = 8;

/// A medium a ray is inside: the material it entered through and that material's
/// index of refraction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Medium {
    /// The material (scene index).
    pub material: u32,
    /// Its index of refraction.
    pub ior: f32,
}

/// The media a ray is inside, outermost first (see the module documentation).
#[derive(Clone, Debug)]
pub struct MediaChain(Entries);

/// A [`MediaChain`]'s entries, inline or spilled.
#[derive(Clone, Debug)]
enum Entries {
    /// Up to [`INLINE_MEDIA`] media without an evaluated medium, the first `len` in use.
    Inline { media: [Medium; INLINE_MEDIA], len: u8 },
    /// A deeper chain, or one holding a medium evaluated at its entry point.
    Spilled(Arc<Vec<Entered>>),
}

/// A medium entered: the chain's entry and, where the material's participating medium
/// varies over its surface, that medium evaluated where the ray entered.
#[derive(Clone, Copy, Debug)]
struct Entered {
    medium: Medium,
    own: Option<bsdf::Medium>,
}

impl Default for MediaChain {
    /// Inside no medium.
    fn default() -> MediaChain {
        MediaChain(Entries::Inline { media: [Medium::default(); INLINE_MEDIA], len: 0 })
    }
}

impl PartialEq for MediaChain {
    /// The same entries in the same order (evaluated media not compared).
    fn eq(&self, other: &MediaChain) -> bool {
        self.iter().eq(other.iter())
    }
}

impl MediaChain {
    /// The entries, outermost first.
    pub fn iter(&self) -> impl DoubleEndedIterator<Item = Medium> + '_ {
        let (inline, spilled): (&[Medium], &[Entered]) = match &self.0 {
            Entries::Inline { media, len } => (&media[..usize::from(*len)], &[]),
            Entries::Spilled(v) => (&[], v),
        };
        inline.iter().copied().chain(spilled.iter().map(|e| e.medium))
    }

    /// How many media the ray is inside.
    pub fn len(&self) -> usize {
        match &self.0 {
            Entries::Inline { len, .. } => usize::from(*len),
            Entries::Spilled(v) => v.len(),
        }
    }

    /// Whether the ray is inside no medium.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The innermost entry.
    pub fn innermost(&self) -> Option<Medium> {
        match &self.0 {
            Entries::Inline { media, len } => media[..usize::from(*len)].last().copied(),
            Entries::Spilled(v) => v.last().map(|e| e.medium),
        }
    }

    /// The participating medium evaluated where the ray entered its innermost entry, if
    /// that was evaluated there (`None`: the material's own constant medium applies).
    pub fn innermost_evaluated(&self) -> Option<&bsdf::Medium> {
        match &self.0 {
            Entries::Inline { .. } => None,
            Entries::Spilled(v) => v.last()?.own.as_ref(),
        }
    }

    /// Records entering `medium` (innermost now); `own` is its participating medium
    /// evaluated at the entry point when that varies over the surface.
    pub fn enter(&mut self, medium: Medium, own: Option<bsdf::Medium>) {
        match &mut self.0 {
            Entries::Inline { media, len } if usize::from(*len) < INLINE_MEDIA && own.is_none() => {
                media[usize::from(*len)] = medium;
                *len += 1;
            }
            Entries::Inline { media, len } => {
                let mut v = Vec::with_capacity(2 * INLINE_MEDIA);
                v.extend(media[..usize::from(*len)].iter().map(|&medium| Entered { medium, own: None }));
                v.push(Entered { medium, own });
                self.0 = Entries::Spilled(Arc::new(v));
            }
            Entries::Spilled(v) => Arc::make_mut(v).push(Entered { medium, own }),
        }
    }

    /// Records leaving material `material`: its innermost entry is removed (nothing when
    /// the ray is not inside it).
    pub fn leave(&mut self, material: u32) {
        match &mut self.0 {
            Entries::Inline { media, len } => {
                let n = usize::from(*len);
                let Some(i) = media[..n].iter().rposition(|m| m.material == material) else { return };
                media.copy_within(i + 1..n, i);
                *len -= 1;
            }
            Entries::Spilled(v) => {
                if let Some(i) = v.iter().rposition(|e| e.medium.material == material) {
                    Arc::make_mut(v).remove(i);
                }
            }
        }
    }

    /// The entries with their evaluated media, outermost first (for a walk that enters
    /// and leaves media itself, as shadow rays do).
    pub fn evaluated(&self) -> impl Iterator<Item = (Medium, Option<bsdf::Medium>)> + '_ {
        let (inline, spilled): (&[Medium], &[Entered]) = match &self.0 {
            Entries::Inline { media, len } => (&media[..usize::from(*len)], &[]),
            Entries::Spilled(v) => (&[], v),
        };
        inline.iter().map(|&m| (m, None)).chain(spilled.iter().map(|e| (e.medium, e.own)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(material: u32) -> Medium {
        Medium { material, ior: 1.0 + material as f32 / 100.0 }
    }

    /// The chain takes no more room than the fixed array of eight media and its count
    /// that it replaced (so a `State` is no larger for scenes without media).
    #[test]
    fn is_as_small_as_the_fixed_array_it_replaced() {
        let old = size_of::<[Medium; INLINE_MEDIA]>() + size_of::<usize>();
        assert!(size_of::<MediaChain>() <= old, "{} > {old}", size_of::<MediaChain>());
        eprintln!("MediaChain {} bytes, State {} bytes", size_of::<MediaChain>(), size_of::<crate::State>());
    }

    /// Twenty nested media are all remembered, outermost first, and leaving them from the
    /// inside out (or one in the middle) gives back each enclosing medium in turn.
    #[test]
    fn remembers_any_depth() {
        let mut c = MediaChain::default();
        for m in 0..20 {
            c.enter(at(m), None);
        }
        assert_eq!(c.len(), 20);
        assert!(c.iter().map(|m| m.material).eq(0..20));
        c.leave(10);
        assert!(c.iter().map(|m| m.material).eq((0..10).chain(11..20)));
        for m in (11..20).rev() {
            assert_eq!(c.innermost(), Some(at(m)));
            c.leave(m);
        }
        for m in (0..10).rev() {
            assert_eq!(c.innermost(), Some(at(m)));
            c.leave(m);
        }
        assert!(c.is_empty() && c.innermost().is_none());
    }

    /// An evaluated medium is kept with its entry (and only its own), survives clones
    /// that diverge, and is dropped when its entry is left.
    #[test]
    fn keeps_the_medium_evaluated_at_the_entry() {
        let own = bsdf::Medium::new(bsdf::Rgb::splat(0.5), bsdf::Rgb::ZERO, 0.0);
        let mut c = MediaChain::default();
        c.enter(at(1), None);
        assert!(c.innermost_evaluated().is_none());
        c.enter(at(2), Some(own));
        assert_eq!(c.innermost_evaluated().map(|m| m.sigma_a), Some(own.sigma_a));
        let mut d = c.clone();
        d.enter(at(3), None);
        assert!(d.innermost_evaluated().is_none());
        assert_eq!(c.innermost_evaluated().map(|m| m.sigma_a), Some(own.sigma_a), "a clone's change is its own");
        d.leave(3);
        assert_eq!(d, c);
        c.leave(2);
        assert!(c.innermost_evaluated().is_none());
        assert_eq!(c.innermost(), Some(at(1)));
    }
}
