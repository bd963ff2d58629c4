//! Which engine renders: the kinds the stages and the part split choose between.

/// Which engine makes the samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineKind {
    /// Iray-style progressive path tracing of physical materials.
    Path,
    /// mental ray's shader-driven ray tracing: material shaders decide.
    Classic,
}
