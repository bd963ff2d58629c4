//! Photon maps (mental ray's caustics and photon global illumination): photons stored on
//! diffuse surfaces in world space, held in a kd-tree, and the irradiance estimates
//! `compute_irradiance` adds from them.
//!
//! A photon carries flux (watts when the light's `energy` is in watts) arriving at a point
//! from a direction. The irradiance estimate at a point with normal n is the flux of the
//! photons found around it that arrived on n's side, over the area of the disc they were
//! gathered from: E = Σ w_p Φ_p / (c π r²), r the distance of the farthest photon used
//! (the `accuracy` count nearest within the `accuracy` radius; the radius itself when fewer
//! were found), w_p and c the filter's weights and normalisation (box: 1, 1; cone with
//! constant k: 1 − d_p / (k r), 1 − 2 / (3k); Gaussian: Jensen's). As the rest of
//! `compute_irradiance`, the estimate is not divided by π: shaders multiply it by their
//! diffuse colour, as they do the direct light.
//!
//! Two maps: the caustic map holds photons that reached a diffuse surface through specular
//! or glossy events only (at least one); the global map holds photons that reached a diffuse
//! surface after at least one diffuse bounce. Photons arriving straight from the light are
//! in neither: the light loop renders direct light.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::Vec3A;

/// A stored photon, world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Where it landed.
    pub position: Vec3A,
    /// Its flux, RGB.
    pub power: Vec3A,
    /// The direction it travelled (unit, towards the surface).
    pub dir: Vec3A,
    /// The surface's shading normal there, facing the side the photon came from.
    pub normal: Vec3A,
}

/// The lookup filter of a photon map (the options' `caustic filter`; the global map uses
/// the box).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Filter {
    /// Every photon counts fully.
    Box,
    /// Weight 1 − d / (k r).
    Cone(f32),
    /// Jensen's Gaussian weight.
    Gauss,
}

impl Filter {
    /// The weight of a photon at distance² `d2` within radius² `r2`.
    fn weight(self, d2: f32, r2: f32) -> f32 {
        match self {
            Filter::Box => 1.0,
            Filter::Cone(k) => (1.0 - (d2 / r2).sqrt() / k).max(0.0),
            Filter::Gauss => {
                const ALPHA: f32 = 0.918;
                const BETA: f32 = 1.953;
                ALPHA * (1.0 - (1.0 - (-BETA * d2 / (2.0 * r2)).exp()) / (1.0 - (-BETA).exp()))
            }
        }
    }

    /// The normalisation making the weights integrate to the disc's area.
    fn norm(self) -> f32 {
        match self {
            Filter::Box => 1.0,
            Filter::Cone(k) => 1.0 - 2.0 / (3.0 * k),
            Filter::Gauss => {
                // The weight's mean over the disc: α ((1 − a) + a (2/β)(1 − e^(−β/2))),
                // a = 1 / (1 − e^(−β)).
                const ALPHA: f32 = 0.918;
                const BETA: f32 = 1.953;
                let a = 1.0 / (1.0 - (-BETA).exp());
                ALPHA * ((1.0 - a) + a * (2.0 / BETA) * (1.0 - (-BETA / 2.0).exp()))
            }
        }
    }
}

/// How a map is looked up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lookup {
    /// Photons per estimate (`accuracy` n).
    pub count: u32,
    /// Largest lookup radius, world units.
    pub radius: f32,
    /// The filter.
    pub filter: Filter,
    /// `caustic scale` / `globillum scale`.
    pub scale: Vec3A,
}

/// Photons in a kd-tree: the median photon of each range splits it along the range's
/// widest axis, so the tree is implicit in the photons' order.
#[derive(Clone, Debug, Default)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// Split axis of the node at each position (the middle of its range).
    axes: Vec<u8>,
}

/// A candidate of a k-nearest search, ordered by distance².
#[derive(Clone, Copy, PartialEq)]
struct Near(f32, u32);

impl Eq for Near {}

impl PartialOrd for Near {
    fn partial_cmp(&self, o: &Near) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Near {
    fn cmp(&self, o: &Near) -> Ordering {
        self.0.total_cmp(&o.0).then(self.1.cmp(&o.1))
    }
}

impl PhotonMap {
    /// Builds the tree over `photons`.
    pub fn new(mut photons: Vec<Photon>) -> PhotonMap {
        let mut axes = vec![0u8; photons.len()];
        build(&mut photons, &mut axes);
        PhotonMap { photons, axes }
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The photons, in tree order.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// The split axis (0 = x, 1 = y, 2 = z) of the node at each position of
    /// [`PhotonMap::photons`].
    pub fn axes(&self) -> &[u8] {
        &self.axes
    }

    /// A map from photons already in tree order and their split axes, as
    /// [`PhotonMap::photons`] and [`PhotonMap::axes`] gave them (a map saved to a file and
    /// read back): the same map, searched in the same order. `None` when the lengths differ
    /// or an axis is not 0, 1 or 2.
    pub fn from_tree(photons: Vec<Photon>, axes: Vec<u8>) -> Option<PhotonMap> {
        (photons.len() == axes.len() && axes.iter().all(|&a| a <= 2)).then_some(PhotonMap { photons, axes })
    }

    /// Bytes the map holds.
    pub fn memory(&self) -> usize {
        self.photons.len() * (std::mem::size_of::<Photon>() + 1)
    }

    /// The (at most) `k` photons nearest to `p` within distance `radius`: (distance²,
    /// index) pairs, in no particular order.
    pub fn nearest(&self, p: Vec3A, k: usize, radius: f32) -> Vec<(f32, u32)> {
        let mut heap = BinaryHeap::with_capacity(k + 1);
        if k > 0 && !self.photons.is_empty() {
            let mut r2 = radius * radius;
            self.search(0, self.photons.len(), p, k, &mut r2, &mut heap);
        }
        heap.into_iter().map(|Near(d, i)| (d, i)).collect()
    }

    fn search(&self, lo: usize, hi: usize, p: Vec3A, k: usize, r2: &mut f32, heap: &mut BinaryHeap<Near>) {
        if lo >= hi {
            return;
        }
        let mid = lo + (hi - lo) / 2;
        let photon = &self.photons[mid];
        let axis = self.axes[mid] as usize;
        let delta = p[axis] - photon.position[axis];
        let (near, far) = if delta < 0.0 { ((lo, mid), (mid + 1, hi)) } else { ((mid + 1, hi), (lo, mid)) };
        self.search(near.0, near.1, p, k, r2, heap);
        let d2 = photon.position.distance_squared(p);
        if d2 <= *r2 {
            heap.push(Near(d2, mid as u32));
            if heap.len() > k {
                heap.pop();
            }
            if heap.len() == k {
                *r2 = heap.peek().map_or(*r2, |n| n.0);
            }
        }
        if delta * delta <= *r2 {
            self.search(far.0, far.1, p, k, r2, heap);
        }
    }

    /// The irradiance estimate at `p` with unit normal `n` (see the module documentation),
    /// before the lookup's scale.
    pub fn irradiance(&self, p: Vec3A, n: Vec3A, lookup: &Lookup) -> Vec3A {
        let found = self.nearest(p, lookup.count.max(1) as usize, lookup.radius);
        if found.is_empty() {
            return Vec3A::ZERO;
        }
        let r2 = if found.len() >= lookup.count as usize {
            found.iter().fold(0.0f32, |m, (d, _)| m.max(*d))
        } else {
            lookup.radius * lookup.radius
        };
        if r2 <= 0.0 {
            return Vec3A::ZERO;
        }
        // Only photons on this side, and near the tangent plane (a disc, not a sphere,
        // so that a nearby perpendicular surface does not bleed in).
        let thickness = 0.25 * r2.sqrt();
        let mut sum = Vec3A::ZERO;
        for (d2, i) in found {
            let ph = &self.photons[i as usize];
            if ph.dir.dot(n) >= 0.0 || ph.normal.dot(n) <= 0.0 || (ph.position - p).dot(n).abs() > thickness {
                continue;
            }
            sum += ph.power * lookup.filter.weight(d2, r2);
        }
        sum / (lookup.filter.norm() * std::f32::consts::PI * r2)
    }
}

/// Orders `photons` into an implicit kd-tree; `axes[i]` is the split axis of the node at
/// `i` (relative to the slice).
fn build(photons: &mut [Photon], axes: &mut [u8]) {
    if photons.len() <= 1 {
        return;
    }
    let (lo, hi) =
        photons.iter().fold((Vec3A::splat(f32::INFINITY), Vec3A::splat(f32::NEG_INFINITY)), |(lo, hi), p| {
            (lo.min(p.position), hi.max(p.position))
        });
    let e = hi - lo;
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = photons.len() / 2;
    photons.select_nth_unstable_by(mid, |a, b| a.position[axis].total_cmp(&b.position[axis]));
    axes[mid] = axis as u8;
    let (left, right) = photons.split_at_mut(mid);
    let (left_axes, right_axes) = axes.split_at_mut(mid);
    build(left, left_axes);
    build(&mut right[1..], &mut right_axes[1..]);
}

/// A light's photon emission (`energy`, `caustic photons`, `globillum photons`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightPhotons {
    /// `energy`, RGB flux.
    pub energy: Vec3A,
    /// `caustic photons store [emit]`.
    pub caustic: Option<(u32, Option<u32>)>,
    /// `globillum photons store [emit]`.
    pub globillum: Option<(u32, Option<u32>)>,
}

/// The photon maps of a render, with their lookup settings.
#[derive(Clone, Debug, Default)]
pub struct PhotonMaps {
    /// Caustic photons, with `caustic accuracy`.
    pub caustic: Option<(PhotonMap, Lookup)>,
    /// Global illumination photons, with `globillum accuracy`.
    pub global: Option<(PhotonMap, Lookup)>,
    /// The global map's irradiance estimate precomputed at (some of) its photons
    /// (Christensen's "faster photon map global illumination", mental ray's fast lookup):
    /// each entry's `power` is the irradiance there (scaled), `normal` the surface normal.
    /// A lookup takes the nearest entry on a surface facing the same way instead of
    /// gathering `accuracy` photons.
    pub global_fast: Option<PhotonMap>,
}

/// Least cosine between a lookup's normal and a precomputed irradiance point's.
const FAST_COS: f32 = 0.8;

/// Precomputed irradiance points a fast lookup considers.
const FAST_CANDIDATES: usize = 8;

impl PhotonMaps {
    /// The caustic map's irradiance estimate at `p`, normal `n` (scaled); zero without one.
    pub fn caustic_irradiance(&self, p: Vec3A, n: Vec3A) -> Vec3A {
        self.caustic.as_ref().map_or(Vec3A::ZERO, |(m, l)| m.irradiance(p, n, l) * l.scale)
    }

    /// The global map's irradiance estimate at `p`, normal `n` (scaled); `None` without one.
    /// From the precomputed points where one near enough faces the same way, else gathered.
    pub fn global_irradiance(&self, p: Vec3A, n: Vec3A) -> Option<Vec3A> {
        let (map, lookup) = self.global.as_ref()?;
        if let Some(fast) = &self.global_fast {
            let near = fast.nearest(p, FAST_CANDIDATES, lookup.radius);
            let best = near
                .iter()
                .filter(|(_, i)| fast.photons[*i as usize].normal.dot(n) >= FAST_COS)
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((_, i)) = best {
                return Some(fast.photons[*i as usize].power);
            }
        }
        Some(map.irradiance(p, n, lookup) * lookup.scale)
    }

    /// Precomputes the global map's irradiance at every `stride`-th photon (see
    /// [`PhotonMaps::global_fast`]) among the photons of index `range` (so that the caller
    /// can split the work).
    pub fn irradiance_points(&self, stride: usize, range: std::ops::Range<usize>) -> Vec<Photon> {
        let Some((map, lookup)) = &self.global else { return Vec::new() };
        range
            .filter(|i| i % stride.max(1) == 0)
            .filter_map(|i| map.photons.get(i))
            .map(|ph| Photon {
                position: ph.position,
                power: map.irradiance(ph.position, ph.normal, lookup) * lookup.scale,
                dir: -ph.normal,
                normal: ph.normal,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize, power: f32) -> Vec<Photon> {
        let mut v = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let x = (i as f32 + 0.5) / n as f32 * 2.0 - 1.0;
                let y = (j as f32 + 0.5) / n as f32 * 2.0 - 1.0;
                v.push(Photon {
                    position: Vec3A::new(x, y, 0.0),
                    power: Vec3A::splat(power),
                    dir: -Vec3A::Z,
                    normal: Vec3A::Z,
                });
            }
        }
        v
    }

    #[test]
    fn nearest_matches_a_linear_scan() {
        let mut photons = grid(40, 1.0);
        // Some off the plane too.
        for (k, p) in photons.iter_mut().enumerate() {
            p.position.z = ((k * 7919) % 101) as f32 / 101.0 - 0.5;
        }
        let map = PhotonMap::new(photons.clone());
        for q in [Vec3A::new(0.1, -0.3, 0.0), Vec3A::new(0.9, 0.9, 0.4), Vec3A::new(-2.0, 0.0, 0.0)] {
            let found = map.nearest(q, 25, 0.7);
            let mut d: Vec<f32> = found.iter().map(|x| x.0).collect();
            d.sort_by(f32::total_cmp);
            let mut all: Vec<f32> =
                photons.iter().map(|p| p.position.distance_squared(q)).filter(|d| *d <= 0.49).collect();
            all.sort_by(f32::total_cmp);
            all.truncate(25);
            assert_eq!(d, all, "query {q}");
        }
    }

    #[test]
    fn a_map_rebuilt_from_its_tree_searches_the_same() {
        let mut photons = grid(30, 1.0);
        for (k, p) in photons.iter_mut().enumerate() {
            p.position.z = ((k * 7919) % 101) as f32 / 101.0 - 0.5;
        }
        let map = PhotonMap::new(photons);
        let copy = PhotonMap::from_tree(map.photons().to_vec(), map.axes().to_vec()).unwrap();
        let l = Lookup { count: 50, radius: 0.4, filter: Filter::Cone(1.1), scale: Vec3A::ONE };
        for q in [Vec3A::new(0.1, -0.3, 0.0), Vec3A::new(0.7, 0.2, 0.3)] {
            assert_eq!(map.nearest(q, 50, 0.4), copy.nearest(q, 50, 0.4));
            assert_eq!(map.irradiance(q, Vec3A::Z, &l).to_array(), copy.irradiance(q, Vec3A::Z, &l).to_array());
        }
        assert!(PhotonMap::from_tree(map.photons().to_vec(), vec![0; 3]).is_none(), "lengths differ");
        let mut bad = map.axes().to_vec();
        bad[0] = 3;
        assert!(PhotonMap::from_tree(map.photons().to_vec(), bad).is_none(), "axis 3");
    }

    #[test]
    fn uniform_photons_give_their_flux_density() {
        // 200 × 200 photons of flux 1e-4 on a 2 × 2 square: irradiance 4 / 4 = 1 W/m².
        let map = PhotonMap::new(grid(200, 1e-4));
        for filter in [Filter::Box, Filter::Cone(1.1), Filter::Gauss] {
            let l = Lookup { count: 400, radius: 0.5, filter, scale: Vec3A::ONE };
            let e = map.irradiance(Vec3A::ZERO, Vec3A::Z, &l);
            assert!((e.x - 1.0).abs() < 0.05, "{filter:?}: {e}");
            // The back side sees nothing.
            assert_eq!(map.irradiance(Vec3A::ZERO, -Vec3A::Z, &l), Vec3A::ZERO);
        }
        // Fewer photons than asked for within the radius: the radius is the disc.
        let l = Lookup { count: 1_000_000, radius: 0.2, filter: Filter::Box, scale: Vec3A::ONE };
        let e = map.irradiance(Vec3A::ZERO, Vec3A::Z, &l);
        assert!((e.x - 1.0).abs() < 0.05, "{e}");
    }
}
