//! Which triangles touch each vertex of a mesh: a counting sort of the triangles' corners
//! by vertex, built on all the pool's threads, each list in increasing triangle order.
//!
//! The vertices are cut into as many runs as the pool has threads (at most [`MAX_PARTS`]);
//! each thread reads every triangle and counts, then lists, the corners at its own run of
//! vertices, whose lists are one contiguous stretch of the table. So no thread writes
//! where another does, no array is kept per thread, and the table is the same at any
//! thread count.

use rayon::prelude::*;

/// The most runs of vertices the table is built in (each reads every triangle twice).
const MAX_PARTS: usize = 16;

/// Which triangles touch each vertex (compressed rows: `start[v]..start[v + 1]` of the
/// list, each row's triangle indices increasing; a triangle with a vertex twice is in its
/// row twice).
pub struct Incidence {
    /// Where each vertex's row begins in `list`, then the list's length (vertex count + 1
    /// entries).
    start: Vec<u32>,
    /// The rows one after another, three entries a triangle, held as triangles so that
    /// the allocation can be handed on as one ([`Incidence::into_storage`]).
    list: Vec<[u32; 3]>,
}

impl Incidence {
    /// The table of `triangles` (vertex indices, each below `vertex_count`; fewer than
    /// `u32::MAX / 3` triangles), built on the current rayon pool.
    pub fn new(triangles: &[[u32; 3]], vertex_count: usize) -> Incidence {
        Incidence::with_parts(triangles, vertex_count, rayon::current_num_threads().clamp(1, MAX_PARTS))
    }

    /// [`Incidence::new`] with the vertices cut into `parts` runs (the same table for any
    /// `parts` ≥ 1).
    pub fn with_parts(triangles: &[[u32; 3]], vertex_count: usize, parts: usize) -> Incidence {
        let span = vertex_count.div_ceil(parts.max(1)).max(1);
        // Allocated zeroed (fresh pages), first touched by the threads that fill them.
        let mut start = vec![0u32; vertex_count + 1];
        let mut list = vec![[0u32; 3]; triangles.len()];
        let rows = &mut start[..vertex_count];
        // The corners at each vertex, each run counting its own.
        rows.par_chunks_mut(span).enumerate().for_each(|(p, counts)| {
            let first = p * span;
            for tri in triangles {
                for &i in tri {
                    if let Some(c) = counts.get_mut((i as usize).wrapping_sub(first)) {
                        *c += 1;
                    }
                }
            }
        });
        // Each row's end: the running sum, each run's from the corners of the runs before.
        let totals: Vec<u32> = rows.par_chunks(span).map(|c| c.iter().sum()).collect();
        let offsets: Vec<u32> = totals
            .iter()
            .scan(0u32, |sum, &n| {
                let before = *sum;
                *sum += n;
                Some(before)
            })
            .collect();
        rows.par_chunks_mut(span).zip(&offsets).for_each(|(ends, &before)| {
            let mut sum = before;
            for e in ends {
                sum += *e;
                *e = sum;
            }
        });
        // Each run's rows: one stretch of the list, filled from the last triangle to the
        // first, each corner put just below its row's end, which then moves down to it:
        // once filled, each row is in increasing order and its end has reached its start.
        let mut stretches = Vec::with_capacity(totals.len());
        let mut rest = list.as_flattened_mut();
        for &n in &totals {
            let (stretch, after) = rest.split_at_mut(n as usize);
            stretches.push(stretch);
            rest = after;
        }
        rows.par_chunks_mut(span).zip(stretches).zip(&offsets).enumerate().for_each(
            |(p, ((ends, stretch), &before))| {
                let first = p * span;
                for (t, tri) in triangles.iter().enumerate().rev() {
                    for &i in tri {
                        if let Some(e) = ends.get_mut((i as usize).wrapping_sub(first)) {
                            *e -= 1;
                            stretch[(*e - before) as usize] = t as u32;
                        }
                    }
                }
            },
        );
        start[vertex_count] = 3 * triangles.len() as u32;
        Incidence { start, list }
    }

    /// The triangles touching `vertex`, in increasing order.
    #[inline]
    pub fn of(&self, vertex: u32) -> &[u32] {
        let v = vertex as usize;
        &self.list.as_flattened()[self.start[v] as usize..self.start[v + 1] as usize]
    }

    /// The list's allocation, handed on for another array of as many triangles (its
    /// contents are the table's rows).
    pub fn into_storage(self) -> Vec<[u32; 3]> {
        self.list
    }
}

#[cfg(test)]
#[path = "incidence_tests.rs"]
mod tests;
