//! The base volume shaders: `mib_volume` (distance fog) and `mib_ray_marcher` (sampling a
//! shader along the ray). They run as volume shaders ([`shader::volume`]): the
//! result arrives holding the colour the ray brought back, `state.org`/`dir` are the ray's,
//! `state.point` its end and `state.dist` its length (0: the ray went to infinity).

use glam::Vec3A;

use shader::volume::segment_length;
use shader::{Color, Ctx, NodeId, RayType, ShaderImpl, Tag, Value};

/// `mib_volume (color color, scalar max, boolean lightrays)`: fog fading the ray's colour
/// towards `color` with the distance travelled. The fog's share is
/// f = min(dist / max, 1), and 1 for a ray gone to infinity or where `max` ≤ 0 (a fog of
/// constant opacity); `color` is a premultiplied layer composited over the result:
/// result = result (1 − f·α) + f·color, α the fog's alpha (which thereby limits its
/// opacity). Light rays (only with `lightrays`; else they pass unchanged) lose the same
/// share: rgb × (1 − f·α).
pub static VOLUME: ShaderImpl =
    ShaderImpl { name: "mib_volume", params: &["color", "max", "lightrays"], run: volume, ..ShaderImpl::PLAIN };

/// The fog's share f of `mib_volume` for a segment of length `dist` (0 or infinite: the
/// ray went to infinity) and fading distance `max`.
pub fn fog_share(dist: f32, max: f32) -> f32 {
    if max > 0.0 && dist > 0.0 && dist < max {
        dist / max
    } else {
        1.0
    }
}

fn volume(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    let light = matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow);
    if light && !ctx.bool(n, 2) {
        return true;
    }
    let fog = ctx.color(n, 0);
    let f = fog_share(ctx.state.dist, ctx.scalar(n, 1));
    let c = out.color();
    let keep = 1.0 - f * fog.w;
    *out = Value::Color(if light { Color::new(c.x * keep, c.y * keep, c.z * keep, c.w) } else { c * keep + fog * f });
    true
}

/// `mib_ray_marcher (shader shader, scalar distance, integer num, integer subdiv, color
/// contrast)`: calls `shader` at points along the ray (with `state.point` moved there) and
/// adds the length-weighted mean of what it returns to the result (mira's reading of the
/// manual's "total weighted sum": the trapezoidal mean over the segment, so a shader
/// returning a constant adds that constant; a call that fails adds nothing). Initial
/// samples: `num` (at least 2, both ends included; 4 when `num` and `distance` are 0),
/// more where `distance` > 0 requires no gap wider than it. Each interval whose ends
/// differ by more than `contrast` in some component is halved, recursively, at most
/// `subdiv` times (≤ 16). A ray gone to infinity is marched over `distance` ×
/// (samples − 1) when `distance` > 0, else left unchanged. Light rays pass unchanged.
pub static RAY_MARCHER: ShaderImpl = ShaderImpl {
    name: "mib_ray_marcher",
    params: &["shader", "distance", "num", "subdiv", "contrast"],
    run: ray_marcher,
    ..ShaderImpl::PLAIN
};

/// Most samples one march takes (initial and subdivision ones together).
const MAX_MARCH_SAMPLES: usize = 4096;

fn ray_marcher(ctx: &mut Ctx, n: NodeId, out: &mut Value) -> bool {
    if matches!(ctx.state.ray_type, RayType::Light | RayType::Shadow) {
        return true;
    }
    let Some(Tag::Shader(shader)) = ctx.tag(n, 0) else { return false };
    let distance = ctx.scalar(n, 1).max(0.0);
    let num = ctx.int(n, 2);
    let subdiv = ctx.int(n, 3).clamp(0, 16) as u32;
    let contrast = ctx.color(n, 4);
    let mut initial = if num >= 2 { num as usize } else { 4 };
    let mut length = segment_length(&ctx.state);
    if !length.is_finite() {
        if distance <= 0.0 {
            return true;
        }
        length = distance * (initial - 1) as f32;
    } else if distance > 0.0 {
        initial = initial.max((length / distance).ceil() as usize + 1);
    }
    let initial = initial.clamp(2, MAX_MARCH_SAMPLES / 2);
    let (org, dir) = (ctx.state.org, ctx.state.dir);
    let saved = ctx.state.point;
    let mut march = March { ctx, shader, org, dir, length, contrast, budget: MAX_MARCH_SAMPLES };
    let mut sum = Color::ZERO;
    let mut prev = march.sample(0.0);
    for i in 1..initial {
        let t = i as f32 / (initial - 1) as f32;
        let next = march.sample(t);
        sum += march.interval(((i - 1) as f32 / (initial - 1) as f32, prev), (t, next), subdiv);
        prev = next;
    }
    march.ctx.state.point = saved;
    march.ctx.flush_cache();
    *out = Value::Color(out.color() + sum);
    true
}

/// One ray march of `mib_ray_marcher`: positions are fractions of the segment.
struct March<'c, 'a> {
    ctx: &'c mut Ctx<'a>,
    shader: NodeId,
    org: Vec3A,
    dir: Vec3A,
    length: f32,
    contrast: Color,
    budget: usize,
}

impl March<'_, '_> {
    /// The shader's colour at fraction `t` of the segment (zero if it fails).
    fn sample(&mut self, t: f32) -> Color {
        self.budget = self.budget.saturating_sub(1);
        self.ctx.state.point = self.org + self.dir * (t * self.length);
        self.ctx.flush_cache();
        let mut v = Value::Color(Color::ZERO);
        if self.ctx.run_list(self.shader, &mut v) {
            v.color()
        } else {
            Color::ZERO
        }
    }

    /// The trapezoidal integral (as a fraction of the segment) over the interval between
    /// samples `a` and `b`, halved while they differ by more than the contrast.
    fn interval(&mut self, a: (f32, Color), b: (f32, Color), levels: u32) -> Color {
        let differs = ((a.1 - b.1).abs() - self.contrast).max_element() > 0.0;
        if levels == 0 || !differs || self.budget == 0 {
            return (a.1 + b.1) * (0.5 * (b.0 - a.0));
        }
        let mid = 0.5 * (a.0 + b.0);
        let m = (mid, self.sample(mid));
        self.interval(a, m, levels - 1) + self.interval(m, b, levels - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fog_share_is_the_distance_over_max_and_solid_beyond() {
        assert_eq!(fog_share(2.5, 10.0), 0.25);
        assert_eq!(fog_share(12.0, 10.0), 1.0);
        // 0: the ray went to infinity.
        assert_eq!(fog_share(0.0, 10.0), 1.0);
        assert_eq!(fog_share(f32::INFINITY, 10.0), 1.0);
        // max 0: constant opacity (the fog colour's alpha).
        assert_eq!(fog_share(3.0, 0.0), 1.0);
    }
}
