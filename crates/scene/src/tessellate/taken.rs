//! Trilist arrays moved out of the syntax tree before the scene is built, so that the
//! tessellation can hand them to the mesh instead of copying them: the index list becomes
//! the mesh's triangles and the vertex numbers its positions, in place (for a 4 M-triangle
//! trilist, 72 MB neither allocated again nor copied).
//!
//! The scene builder reads the syntax tree through shared references, so the arrays are
//! moved out first ([`TakenTrilists::take_from`]) and looked up by the trilist's place in
//! the source ([`TakenTrilists::take`]). Each array can be handed out once: an object is
//! tessellated once and shared by its instances, except below a geometry shader
//! (`mib_geo_add_uv_texsurf` tessellates a changed copy of an object beside the object
//! itself), so nothing is moved out of a file with geometry shader instances.

use std::cell::RefCell;
use std::collections::{HashMap, HashSet};

use mi::ast::{Geometry, InstanceTarget, Item, Trilist};
use mi::Span;

/// Where a trilist was written: its file and byte range (spans compare equal whatever
/// they hold, so the key is spelled out).
type Place = (u32, u32, u32);

fn place(span: Span) -> Place {
    (span.file.0, span.lo, span.hi)
}

/// A trilist's vertex numbers and triangle indices, moved out of the syntax tree.
#[derive(Debug, Default)]
pub struct TrilistArrays {
    /// All vertex lines, as [`Trilist::floats`].
    pub floats: Vec<f32>,
    /// The triangles' vertex indices, as the trilist's `triangles.indices`.
    pub indices: Vec<u32>,
}

/// Trilist arrays moved out of a syntax tree, by the trilists' places in the source; each
/// handed out at most once.
#[derive(Debug, Default)]
pub struct TakenTrilists {
    arrays: RefCell<HashMap<Place, TrilistArrays>>,
    handed_out: RefCell<HashSet<Place>>,
}

impl TakenTrilists {
    /// Moves the vertex and index arrays of every trilist of `items` (objects at the top,
    /// in namespaces and behind prefixes) into the store, leaving them empty in the tree —
    /// unless an instance anywhere places a geometry shader, which may tessellate an object
    /// twice: then nothing is moved.
    pub fn take_from(items: &mut [Item]) -> TakenTrilists {
        let store = TakenTrilists::default();
        if !any_geometry_shader(items) {
            store.take_all(items);
        }
        store
    }

    fn take_all(&self, items: &mut [Item]) {
        for item in items {
            match item {
                Item::Object(o) => {
                    for g in &mut o.geometry {
                        if let Geometry::Trilist(list) = g {
                            let arrays = TrilistArrays {
                                floats: std::mem::take(&mut list.floats),
                                indices: std::mem::take(&mut list.triangles.indices),
                            };
                            self.arrays.borrow_mut().insert(place(list.span), arrays);
                        }
                    }
                }
                Item::Namespace(n) => self.take_all(&mut n.items),
                Item::Modified { item, .. } => self.take_all(std::slice::from_mut(&mut **item)),
                _ => {}
            }
        }
    }

    /// The arrays moved out of `list`, if they were and are still here (`None`: the tree
    /// holds them).
    pub fn take(&self, list: &Trilist) -> Option<TrilistArrays> {
        let key = place(list.span);
        let arrays = self.arrays.borrow_mut().remove(&key)?;
        self.handed_out.borrow_mut().insert(key);
        Some(arrays)
    }

    /// Whether the arrays of `list` were handed out already (a second tessellation of
    /// the same trilist, which [`TakenTrilists::take_from`] rules out).
    pub fn was_handed_out(&self, list: &Trilist) -> bool {
        self.handed_out.borrow().contains(&place(list.span))
    }
}

/// Whether an instance of `items` (at any depth) places a geometry shader.
fn any_geometry_shader(items: &[Item]) -> bool {
    items.iter().any(|item| match item {
        Item::Instance(i) => matches!(i.target, InstanceTarget::Geometry(_)),
        Item::Namespace(n) => any_geometry_shader(&n.items),
        Item::Modified { item, .. } => any_geometry_shader(std::slice::from_ref(&**item)),
        _ => false,
    })
}
