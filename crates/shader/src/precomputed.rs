//! Data a shader node computes once per render, on first use, and reads for the rest of it
//! (a pre-blurred environment map, a table): mental ray shaders kept such data in their
//! init functions' user pointers.
//!
//! The store lives in the [`super::Shading`] of one render, so a new render (a new
//! `Shading`) starts empty. Rendering threads share it: the first thread to ask for a
//! node's data computes it while the others asking for the same node wait; different nodes
//! do not wait for each other. A node whose computation asks for its own data again (an
//! environment that ends up looking itself up) gets `None` instead of deadlocking.

use std::any::Any;
use std::cell::RefCell;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use super::graph::NodeId;

type Cell = Arc<OnceLock<Arc<dyn Any + Send + Sync>>>;

/// Per-node data computed once per render.
#[derive(Default)]
pub struct Precomputed {
    cells: Mutex<HashMap<NodeId, Cell>>,
}

impl std::fmt::Debug for Precomputed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.cells.lock().map_or(0, |c| c.len());
        f.debug_struct("Precomputed").field("nodes", &n).finish()
    }
}

thread_local! {
    /// (store address, node) pairs whose data this thread is computing.
    static BUSY: RefCell<Vec<(usize, NodeId)>> = const { RefCell::new(Vec::new()) };
}

impl Precomputed {
    /// The data of `node`, computed by `init` the first time any thread asks. `None` when
    /// this thread is already computing it (a self-referencing computation) or when the data
    /// stored for `node` is of another type.
    pub fn get_or_init<T: Any + Send + Sync>(&self, node: NodeId, init: impl FnOnce() -> T) -> Option<Arc<T>> {
        let key = (self as *const Precomputed as usize, node);
        if BUSY.with(|b| b.borrow().contains(&key)) {
            return None;
        }
        let cell = {
            let mut cells = self.cells.lock().unwrap_or_else(|e| e.into_inner());
            cells.entry(node).or_default().clone()
        };
        let value = cell.get_or_init(|| {
            BUSY.with(|b| b.borrow_mut().push(key));
            let v: Arc<dyn Any + Send + Sync> = Arc::new(init());
            BUSY.with(|b| b.borrow_mut().retain(|k| *k != key));
            v
        });
        value.clone().downcast::<T>().ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_is_computed_once_per_node_and_self_reference_gives_none() {
        let store = Precomputed::default();
        let calls = std::sync::atomic::AtomicU32::new(0);
        let make = || {
            calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            vec![1.0f32, 2.0]
        };
        let a = store.get_or_init(3, make).expect("data");
        let b = store.get_or_init(3, || vec![9.0f32]).expect("data");
        assert_eq!((a[1], b[1]), (2.0, 2.0));
        assert_eq!(calls.load(std::sync::atomic::Ordering::Relaxed), 1);
        // Another type for the same node: none.
        assert!(store.get_or_init(3, || 1u8).is_none());
        // Node 4 asking for itself while being computed.
        let inner = store.get_or_init(4, || store.get_or_init(4, || 5u32).is_none());
        assert_eq!(inner.as_deref(), Some(&true));
        // Threads share the data.
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| assert_eq!(store.get_or_init(3, Vec::<f32>::new).expect("data").len(), 2));
            }
        });
    }
}
