//! The own frames of a lobe sum ([`super::LobeSum`]): around a layer's own normal, or
//! turned to an anisotropic lobe's own tangent about the shading normal or a layer's.

use glam::Vec3A;

use crate::Frame;

/// Two directions in a part's own frame, and |cos θi| there over |cos θi| in the shading
/// frame; `None` where the frames disagree on a side (the part scatters nothing there).
#[inline]
pub(super) fn in_own_frame(frame: &Frame, wo: Vec3A, wi: Vec3A) -> Option<(Vec3A, Vec3A, f32)> {
    let (o, i) = (frame.to_local(wo), frame.to_local(wi));
    let agree = (o.z * wo.z > 0.0) && (i.z * wi.z > 0.0) && wi.z.abs() > 1e-6;
    agree.then(|| (o, i, i.z.abs() / wi.z.abs()))
}

/// Which own frames are tangent frames (`tangents`: bit k − 1 for frame k) and which of
/// those turn about the normal of the frame before them (`in_layer`, bit k − 1) rather
/// than the shading normal.
#[derive(Clone, Copy)]
pub(super) struct FrameKinds {
    pub(super) tangents: u8,
    pub(super) in_layer: u8,
}

/// Own frame `k` (≥ 1) of `normals` (local shading frame): x the shading frame's x laid
/// into its tangent plane; or, for a tangent frame, the frame it turns about (the shading
/// frame, or frame k − 1) turned so that x is the tangent `normals[k − 1]` made
/// orthogonal to its normal.
#[inline]
pub(super) fn own_frame(normals: &[[f32; 3]], kinds: FrameKinds, k: u8) -> Frame {
    let j = usize::from(k) - 1;
    let v = Vec3A::from_array(normals[j]);
    if kinds.tangents & (1 << j) != 0 {
        let n = if kinds.in_layer & (1 << j) != 0 { Vec3A::from_array(normals[j - 1]) } else { Vec3A::Z };
        Frame::from_normal_and_tangent(n, v)
    } else {
        Frame::from_normal_and_tangent(v, Vec3A::X)
    }
}

/// Directions in frame `k` of `normals` and the cosine ratio (see [`in_own_frame`]); the
/// shading frame's are the directions themselves.
#[inline]
pub(super) fn directions_in(
    normals: &[[f32; 3]],
    kinds: FrameKinds,
    k: u8,
    wo: Vec3A,
    wi: Vec3A,
) -> Option<(Vec3A, Vec3A, f32)> {
    if k == 0 {
        Some((wo, wi, 1.0))
    } else {
        in_own_frame(&own_frame(normals, kinds, k), wo, wi)
    }
}

/// Brings the own frames' normals from world space into the local shading frame `frame`
/// (world space), each turned to the side of the shading normal; the tangents of tangent
/// frames (`kinds`) are laid into the tangent plane instead (x where one has no direction
/// there) — or, where one turns about a layer's normal, kept whole (unit; made orthogonal
/// to that normal when the frame is built).
pub(super) fn place_normals(normals: &mut [[f32; 3]], kinds: FrameKinds, frame: &Frame) {
    for (k, n) in normals.iter_mut().enumerate() {
        let local = frame.to_local(Vec3A::from_array(*n));
        *n = if kinds.tangents & kinds.in_layer & (1 << k) != 0 {
            local.normalize_or(Vec3A::X).to_array()
        } else if kinds.tangents & (1 << k) != 0 {
            Vec3A::new(local.x, local.y, 0.0).normalize_or(Vec3A::X).to_array()
        } else {
            let local = if local.z < 0.0 { -local } else { local };
            local.normalize_or(Vec3A::Z).to_array()
        };
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;

    use crate::beckmann::Beckmann;
    use crate::lobes::{Lobe, Lobes, Role, WideLobes};
    use crate::{Bsdf, Frame, Rgb};

    /// Two Ward lobes of different tangents (0.2, 1, 0.3) and (1, −0.4, 0) inside one layer
    /// normal n = (0.3, 0.1, 1) (normalised), world = local: the first tangent takes the
    /// slot after n's, the second a copy of n and the slot after it (four frames), an
    /// equal tangent about n is shared; each part equals the lone lobe evaluated in the
    /// frame of normal n and x axis its tangent made orthogonal to n, times |cos θi| about
    /// n over |cos θi| about z, nothing where the two normals disagree on a side (1e-5 of
    /// the larger value, 64 × 64 direction pairs).
    #[test]
    fn tangents_inside_a_layer_normal_turn_about_it() {
        let n = Vec3A::new(0.3, 0.1, 1.0).normalize();
        let tangents = [Vec3A::new(0.2, 1.0, 0.3), Vec3A::new(1.0, -0.4, 0.0)];
        let ward = Lobe::Ward(Beckmann::new(0.15, 0.45));
        let mut sum = WideLobes::default();
        let layer = sum.add_normal(n).expect("a frame");
        let frames: Vec<u8> = tangents.iter().map(|t| sum.add_tangent_in(*t, layer).expect("a frame")).collect();
        assert_eq!((frames[0], frames[1], sum.normal_count), (2, 4, 4));
        assert_eq!(sum.add_tangent_in(tangents[0], layer), Some(2));
        for &f in &frames {
            assert!(sum.push_in_frame(Rgb::ONE, ward, Role::default(), f));
        }
        let mut lone = Lobes::default();
        assert!(lone.push(Rgb::ONE, ward));
        let lone = Bsdf::Lobes(lone);
        sum.place(&Frame::from_normal_and_tangent(Vec3A::Z, Vec3A::X));
        let dirs: Vec<Vec3A> = (1..65)
            .map(|i| {
                let u = crate::testing::r2(i);
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * u.y;
                Vec3A::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        for &wo in &dirs {
            for &wi in &dirs {
                let agree = wo.dot(n) * wo.z > 0.0 && wi.dot(n) * wi.z > 0.0 && wi.z.abs() > 1e-6;
                let mut want = Rgb::ZERO;
                for t in tangents {
                    let frame = Frame::from_normal_and_tangent(n, t);
                    if agree {
                        want += lone.eval(frame.to_local(wo), frame.to_local(wi)) * (wi.dot(n).abs() / wi.z.abs());
                    }
                }
                let got = sum.eval(wo, wi);
                let scale = got.max_element().max(want.max_element()).max(1e-3);
                assert!((got - want).abs().max_element() <= 1e-5 * scale, "{wo} → {wi}: {got} vs {want}");
            }
        }
    }
}
