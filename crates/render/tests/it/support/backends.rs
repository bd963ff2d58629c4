//! Two acceleration structures' closest hits and occlusion compared ray by ray.

use render::accel::Accel;
use render::ray::Ray;

/// How two structures' hits compared ([`assert_agree`]).
pub struct Agreement {
    /// Rays whose hits name different triangles (a ray grazing an edge two triangles share
    /// may find either).
    pub different: usize,
    /// Rays whose hit in `want` is on instance `instance`.
    pub on_instance: usize,
}

/// Asserts that `got` finds what `want` finds for every ray: both hit or both miss, at the
/// same distance within 1e-4 relative, the same triangle with barycentrics within 1e-3
/// (or another triangle, counted in [`Agreement::different`]), and the same occlusion.
pub fn assert_agree(want: &dyn Accel, got: &dyn Accel, rays: &[Ray], instance: u32) -> Agreement {
    let mut agreement = Agreement { different: 0, on_instance: 0 };
    for ray in rays {
        let (a, b) = (want.intersect(ray), got.intersect(ray));
        match (a, b) {
            (Some(a), Some(b)) => {
                agreement.on_instance += usize::from(a.instance == instance);
                assert!((a.t - b.t).abs() <= 1e-4 * a.t.max(1.0), "{a:?} vs {b:?}");
                if (a.instance, a.prim) != (b.instance, b.prim) {
                    agreement.different += 1;
                    continue;
                }
                assert!((a.u - b.u).abs() < 1e-3 && (a.v - b.v).abs() < 1e-3, "{a:?} vs {b:?}");
            }
            (None, None) => {}
            _ => panic!("one backend hit and the other missed: {a:?} {b:?} for {ray:?}"),
        }
        assert_eq!(want.occluded(ray), got.occluded(ray), "{ray:?}");
    }
    agreement
}
