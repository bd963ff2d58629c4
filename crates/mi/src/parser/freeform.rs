//! Free-form geometry inside a group: curves, space curves, surfaces with their knot
//! vectors, trimming and special points, and `connect` statements.

use super::{PResult, Parser};
use crate::ast::*;
use crate::lexer::Tok;

impl Parser {
    /// Knot values: float tokens only (an integer starts the vertex references).
    fn knots(&mut self) -> PResult<Vec<f64>> {
        let mut v = Vec::new();
        while let Tok::Float(x) = self.peek()?.tok {
            self.bump()?;
            v.push(x);
        }
        Ok(v)
    }

    /// Control-point references: `i`, `i weight`, `i w weight`.
    fn vertex_refs(&mut self) -> PResult<Vec<VertexRef>> {
        let mut refs = Vec::new();
        while matches!(self.peek()?.tok, Tok::Int(_)) {
            let index = self.uint("a vertex index")?;
            let weight = if self.at("w")? {
                self.bump()?;
                Some((true, self.float()?))
            } else if let Tok::Float(w) = self.peek()?.tok {
                self.bump()?;
                Some((false, w))
            } else {
                None
            };
            refs.push(VertexRef { index, weight });
        }
        Ok(refs)
    }

    /// `special` point list.
    fn special_points(&mut self) -> PResult<Vec<SpecialPoint>> {
        let mut points = Vec::new();
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::Int(_) => {
                    let i = self.uint("a vertex index")?;
                    if self.eat("mapsto")? {
                        points.push(SpecialPoint::MapsTo(i, self.uint("a vertex index")?));
                    } else {
                        points.push(SpecialPoint::Vertex(i));
                    }
                }
                Tok::Str { .. } => points.push(SpecialPoint::Curve(self.curve_segment()?)),
                _ => return Ok(points),
            }
        }
    }

    /// `"curve" t0 t1`
    fn curve_segment(&mut self) -> PResult<CurveSegment> {
        let curve = self.name()?;
        let t0 = self.float()?;
        let t1 = self.float()?;
        Ok(CurveSegment { curve, t0, t1 })
    }

    /// Curve segments while they come.
    fn curve_segments(&mut self) -> PResult<Vec<CurveSegment>> {
        let mut v = vec![self.curve_segment()?];
        while self.at_str()? {
            v.push(self.curve_segment()?);
        }
        Ok(v)
    }

    /// `curve "name" [rational] "basis" knots… refs… [special …]`
    pub(super) fn curve(&mut self) -> PResult<Curve> {
        let start = self.expect("curve")?;
        let name = self.name()?;
        let rational = self.eat("rational")?;
        let basis = self.name()?;
        let params = self.knots()?;
        let refs = self.vertex_refs()?;
        let special = if self.eat("special")? { Some(self.special_points()?) } else { None };
        let end = self.peek()?.span;
        Ok(Curve { name, rational, basis, params, refs, special, span: start.to(end.start()) })
    }

    /// `space curve "name" "curve" t0 t1 …`
    pub(super) fn space_curve(&mut self) -> PResult<SpaceCurve> {
        let start = self.expect("space")?;
        self.expect("curve")?;
        let name = self.name()?;
        let segments = self.curve_segments()?;
        let end = self.peek()?.span;
        Ok(SpaceCurve { name, segments, span: start.to(end.start()) })
    }

    /// `[rational] "basis" [min max] knots…`
    fn surface_dir(&mut self, ranged: bool) -> PResult<SurfaceDir> {
        let rational = self.eat("rational")?;
        let basis = self.name()?;
        let range = if ranged { Some((self.float()?, self.float()?)) } else { None };
        let params = self.knots()?;
        Ok(SurfaceDir { rational, basis, range, params })
    }

    /// `surface "name" mtl|label u v refs… extras…`
    pub(super) fn surface(&mut self, tagged: bool) -> PResult<Surface> {
        let start = self.expect("surface")?;
        let name = self.name()?;
        let material = if matches!(self.peek()?.tok, Tok::Int(_)) {
            FaceMaterial::Label(self.uint("a label")?)
        } else {
            let _ = tagged;
            FaceMaterial::Named(self.name()?)
        };
        let u = self.surface_dir(true)?;
        let v = self.surface_dir(true)?;
        let refs = self.vertex_refs()?;
        let mut extras = Vec::new();
        loop {
            let t = self.peek()?;
            if self.is(&t, "volume") || self.is(&t, "vector") || self.is(&t, "texture") {
                let volume = self.eat("volume")?;
                let vector = self.eat("vector")?;
                self.expect("texture")?;
                let u = self.surface_dir(false)?;
                let v = self.surface_dir(false)?;
                let refs = self.vertex_refs()?;
                extras.push(SurfaceExtra::Texture { volume, vector, u, v, refs });
            } else if self.eat("derivative")? {
                let mut n = Vec::new();
                while n.len() < 2 && matches!(self.peek()?.tok, Tok::Int(_)) {
                    n.push(self.int()?);
                }
                extras.push(SurfaceExtra::Derivative(n));
            } else if self.eat("trim")? {
                extras.push(SurfaceExtra::Trim(self.curve_segments()?));
            } else if self.eat("hole")? {
                extras.push(SurfaceExtra::Hole(self.curve_segments()?));
            } else if self.eat("special")? {
                extras.push(SurfaceExtra::Special(self.special_points()?));
            } else {
                break;
            }
        }
        let end = self.peek()?.span;
        Ok(Surface { name, material, u, v, refs, extras, span: start.to(end.start()) })
    }

    /// `connect "s1" "c1" t0 t1 "s2" "c2" t0 t1`
    pub(super) fn connect(&mut self) -> PResult<Connect> {
        let start = self.expect("connect")?;
        let s1 = self.name()?;
        let c1 = self.curve_segment()?;
        let s2 = self.name()?;
        let c2 = self.curve_segment()?;
        let end = self.peek()?.span;
        Ok(Connect { first: (s1, c1), second: (s2, c2), span: start.to(end.start()) })
    }
}
