//! The grammar of keyword statements, as tables.
//!
//! Most of the `.mi` language inside an element block is a list of statements that start
//! with one or more keywords and take a fixed shape of arguments (`trace depth 2 2 4`,
//! `shadowmap resolution 512`, `rectangle 1 0 0 0 1 0 4 4`). Each table below lists, for
//! one context, every such statement mental ray 3.x accepts (from the mental ray 3.x scene
//! grammar and manual); the parser matches the longest keyword sequence and reads the
//! arguments by the pattern. A keyword that is not in the table is an error naming it.

/// The shape of one argument (or group of arguments) of a keyword statement.
#[derive(Clone, Copy, Debug)]
pub enum P {
    /// `on`, `off`, `true`, `false`.
    Bool,
    /// An integer.
    Int,
    /// A number, stored as a float.
    Float,
    /// A number, kept as written (integer or float): where mental ray tells them apart.
    Num,
    /// A string (quoted, or an unquoted name where the argument is required).
    Name,
    /// A string not followed by `(` (so not the start of a shader call).
    NameNotCall,
    /// 3 or 4 numbers.
    Color,
    /// 3 numbers or a 12-byte binary vector.
    Vec3,
    /// 16 numbers, row-major.
    Matrix,
    /// Between `min` and `max` integers.
    Ints(u8, u8),
    /// Between `min` and `max` numbers.
    Floats(u8, u8),
    /// One of these words.
    Words(&'static [&'static str]),
    /// A shader list (`"decl" (…)`, `= "name"`, several in a row).
    Shaders,
    /// `[ shader, shader ]`: shaders in brackets, separated by commas (`state`).
    ShaderArray,
    /// `[ "a", "b" ]`: names in brackets, commas optional.
    Names,
    /// `a, b, c`: names separated by commas, no brackets (`apply material, shadow`).
    CommaNames,
    /// A bracketed token tree kept as written (`( … )`, `[ … ]` or `{ … }`).
    Tree,
    /// An approximation technique and what it applies to (`approximate …`).
    Approx,
    /// A literal `,`.
    Comma,
    /// One or more hexadecimal byte strings.
    Bytes,
    /// All of these, present when the next token can start the first of them.
    Opt(&'static [P]),
    /// The first alternative whose first pattern fits the next token.
    Alt(&'static [&'static [P]]),
}

use P::*;

/// One keyword statement: its keywords (space separated) and its argument patterns.
#[derive(Clone, Copy, Debug)]
pub struct Rule {
    /// The keywords, e.g. `"finalgather trace depth"`.
    pub key: &'static str,
    /// The arguments.
    pub args: &'static [P],
}

const fn r(key: &'static str, args: &'static [P]) -> Rule {
    Rule { key, args }
}

const ON_OFF_INT: P = Alt(&[&[Bool], &[Int]]);
const DATA: P = Alt(&[&[Words(&["null"])], &[Name]]);
const FILTERS: &[&str] = &["box", "triangle", "gauss", "mitchell", "lanczos", "cone"];
const SAMPLES: P = Ints(0, 5);
const FG_MODES: &[&str] = &["strict", "compatible", "automatic", "multiframe", "force"];

/// Statements of `options … end options` (besides string options and attributes).
pub static OPTIONS: &[Rule] = &[
    r("samples", &[Ints(1, 4)]),
    r("samples collect", &[Int]),
    r("samples motion", &[Int]),
    r("contrast", &[Color]),
    r("time contrast", &[Color]),
    r("filter", &[Opt(&[Words(&["clip"])]), Words(FILTERS), Floats(0, 2)]),
    r("jitter", &[Float]),
    r("samplelock", &[Bool]),
    r("task size", &[Int]),
    r("shading samples", &[Float]),
    r("shutter", &[Floats(1, 2)]),
    r("motion", &[Bool]),
    r("motion steps", &[Int]),
    r("trace", &[Bool]),
    r("trace depth", &[Ints(1, 3)]),
    r("shadow", &[Alt(&[&[Bool], &[Words(&["sort", "segments"])]])]),
    r("shadowmap", &[Opt(&[Alt(&[&[Bool], &[Words(&["opengl", "only", "detail"])]])])]),
    r("shadowmap trace", &[Opt(&[Bool])]),
    r("shadowmap window", &[Opt(&[Bool])]),
    r("shadowmap motion", &[Bool]),
    r("shadowmap rebuild", &[Alt(&[&[Bool], &[Words(&["merge"])]])]),
    r("shadowmap bias", &[Float]),
    r("scanline", &[Alt(&[&[Bool], &[Words(&["opengl", "rapid", "rast"])]])]),
    r("hardware", &[Alt(&[&[Bool], &[Words(&["all", "force", "cg", "native", "fast"])]])]),
    r("hardware samples", &[Ints(1, 2)]),
    r("lens", &[Bool]),
    r("volume", &[Bool]),
    r("geometry", &[Bool]),
    r("displace", &[Bool]),
    r("displace presample", &[Bool]),
    r("output", &[Bool]),
    r("merge", &[Bool]),
    r("hair", &[Bool]),
    r("pass", &[Bool]),
    r("autovolume", &[Bool]),
    r("photon autovolume", &[Bool]),
    r("face", &[Words(&["front", "back", "both"])]),
    r("field", &[Words(&["off", "even", "odd"])]),
    r("acceleration", &[Opt(&[Words(&["large"])]), Words(&["bsp", "bsp2", "grid", "raycl"])]),
    r("bsp size", &[Int]),
    r("bsp depth", &[Int]),
    r("bsp memory", &[Int]),
    r("bsp shadow", &[Bool]),
    r("grid size", &[Num]),
    r("grid resolution", &[Ints(1, 3)]),
    r("grid depth", &[Int]),
    r("caustic", &[ON_OFF_INT]),
    r("caustic accuracy", &[Int, Opt(&[Float])]),
    r("caustic filter", &[Words(FILTERS), Opt(&[Float])]),
    r("caustic scale", &[Color]),
    r("caustic importance", &[Floats(1, 2)]),
    r("globillum", &[ON_OFF_INT]),
    r("globillum accuracy", &[Int, Opt(&[Float])]),
    r("globillum scale", &[Color]),
    r("globillum importance", &[Floats(1, 2)]),
    r("photon trace depth", &[Ints(1, 3)]),
    r("photonvol accuracy", &[Int, Opt(&[Float])]),
    r("photonvol scale", &[Color]),
    r("photonmap file", &[Opt(&[Alt(&[&[Words(&["off"])], &[Name]])])]),
    r("photonmap only", &[Opt(&[Bool])]),
    r("photonmap rebuild", &[Bool]),
    r("finalgather", &[Alt(&[&[Bool], &[Words(&["fastlookup", "only"])]])]),
    r("finalgather accuracy", &[Opt(&[Words(&["view"])]), Int, Floats(0, 2)]),
    r("finalgather trace depth", &[Ints(1, 4)]),
    r("finalgather file", &[Opt(&[Alt(&[&[Words(&["off"])], &[Names], &[Name]])])]),
    r("finalgather filter", &[Int]),
    r("finalgather rebuild", &[Alt(&[&[Bool], &[Words(&["freeze"])]])]),
    r("finalgather falloff", &[Floats(1, 2)]),
    r("finalgather scale", &[Color]),
    r("finalgather secondary scale", &[Color]),
    r("finalgather presample density", &[Float]),
    r("finalgather points", &[Int]),
    r("finalgather mode", &[Alt(&[&[Words(FG_MODES), Opt(&[Float])], &[Name]])]),
    r("finalgather importance", &[Floats(1, 2)]),
    r("trace importance", &[Floats(1, 2)]),
    r("lightmap", &[Alt(&[&[Bool], &[Words(&["only"])]])]),
    r("diagnostic samples", &[Bool]),
    r("diagnostic photon", &[Alt(&[&[Words(&["off"])], &[Words(&["density", "irradiance"]), Float]])]),
    r("diagnostic grid", &[Alt(&[&[Words(&["off"])], &[Words(&["object", "world", "camera"]), Float]])]),
    r("diagnostic bsp", &[Words(&["off", "depth", "size"])]),
    r("diagnostic finalgather", &[Bool]),
    r("diagnostic hardware", &[Alt(&[&[Bool], &[Words(&["grid", "window", "light"])]])]),
    r("desaturate", &[Bool]),
    r("dither", &[Bool]),
    r("premultiply", &[Bool]),
    r("colorclip", &[Words(&["rgb", "alpha", "raw"])]),
    r("gamma", &[Float]),
    r("object space", &[]),
    r("camera space", &[]),
    r("mixed space", &[]),
    r("world space", &[]),
    r("inheritance", &[Name]),
    r("traversal", &[Name]),
    r("contour store", &[Shaders]),
    r("contour contrast", &[Shaders]),
    r("state", &[Alt(&[&[ShaderArray], &[Shaders]])]),
    r("frame buffer", &[Int, Opt(&[Name])]),
    r("approximate", &[Approx]),
    r("luminance weight", &[Alt(&[&[Words(&["ntsc"])], &[Color]])]),
    r("max displace", &[Float]),
    r("colorprofile", &[Name]),
    r("data", &[DATA]),
    r("irradiance particles", &[Bool]),
    r("ambient occlusion", &[Bool]),
    r("ibl", &[Bool]),
    r("ibl jitter", &[Bool]),
    r("ibl falloff", &[Floats(1, 2)]),
    r("ibl accuracy", &[Num, Opt(&[Num])]),
    r("trace falloff", &[Floats(1, 2)]),
    r("globillum falloff", &[Floats(1, 2)]),
    r("caustic falloff", &[Floats(1, 2)]),
    r("raycl subdivision", &[Ints(1, 2)]),
    r("raycl memory", &[Int]),
];

/// Statements of `camera … end camera` (besides `output`, `framebuffer` and attributes).
pub static CAMERA: &[Rule] = &[
    r("focal", &[Alt(&[&[Words(&["infinity"])], &[Float]])]),
    r("aperture", &[Float]),
    r("aspect", &[Float]),
    r("resolution", &[Int, Int]),
    r("offset", &[Float, Float]),
    r("window", &[Ints(4, 4)]),
    r("clip", &[Float, Float]),
    r("dof", &[Float, Float]),
    r("frame", &[Int, Opt(&[Float])]),
    r("field", &[Int]),
    r("lens", &[Opt(&[Shaders])]),
    r("volume", &[Opt(&[Shaders])]),
    r("environment", &[Opt(&[Shaders])]),
    r("data", &[DATA]),
    r(
        "pass",
        &[Alt(&[&[Words(&["null"])], &[Opt(&[Words(&["samples"]), Int]), Opt(&[Name]), Words(&["write"]), Name]])],
    ),
    r(
        "pass prep",
        &[
            Opt(&[Words(&["samples"]), Int]),
            Opt(&[Name]),
            Words(&["read"]),
            Name,
            Words(&["write"]),
            Name,
            Opt(&[Shaders]),
        ],
    ),
    r(
        "pass merge",
        &[
            Opt(&[Words(&["samples"]), Int]),
            Opt(&[Name]),
            Words(&["read"]),
            Names,
            Opt(&[Words(&["write"]), Name]),
            Opt(&[Shaders]),
        ],
    ),
    r("pass delete", &[Name]),
    r("pass mask", &[Bool]),
];

/// Options of a file `output`, between the format and the file name (only one is allowed).
pub static OUTPUT_PARAMS: &[Rule] =
    &[r("quality", &[Int]), r("even", &[]), r("odd", &[]), r("dod", &[]), r("dpi", &[Float]), r("compress", &[Name])];

/// Fields of a camera `framebuffer "name"` statement (it has no `end`).
pub static FRAMEBUFFER: &[Rule] = &[
    r("datatype", &[Name]),
    r("filtering", &[Bool]),
    r("filename", &[Name]),
    r("filetype", &[Name]),
    r("colorprofile", &[Name]),
    r("compression", &[Name]),
    r("field", &[Name]),
    r("quality", &[Int]),
    r("dod", &[Bool]),
    r("dpi", &[Num]),
    r("primary", &[Bool]),
    r("useopacity", &[Bool]),
    r("useprimary", &[Bool]),
    r("premultiplied", &[Bool]),
    r("tiled", &[Bool]),
    r("user", &[Bool]),
];

/// Statements of `light … end light` (besides its shader list and attributes).
pub static LIGHT: &[Rule] = &[
    r("emitter", &[Shaders]),
    r("hardware", &[Shaders]),
    r("origin", &[Vec3]),
    r("direction", &[Vec3]),
    r("spread", &[Float]),
    r("rectangle", &[Opt(&[Vec3, Vec3, SAMPLES])]),
    r("disc", &[Opt(&[Vec3, Float, SAMPLES])]),
    r("sphere", &[Opt(&[Float, SAMPLES])]),
    r("cylinder", &[Opt(&[Vec3, Float, SAMPLES])]),
    r("object", &[Name, SAMPLES]),
    r("user", &[SAMPLES]),
    r("visible", &[Opt(&[Bool])]),
    r("tag", &[Int]),
    r("data", &[DATA]),
    r("energy", &[Alt(&[&[Words(&["spectrum"]), Name], &[Opt(&[Words(&["colorprofile"]), Name]), Color]])]),
    r("exponent", &[Float]),
    r("caustic photons", &[Int, Opt(&[Int])]),
    r("globillum photons", &[Int, Opt(&[Int])]),
    r("photons only", &[Bool]),
    r("shadow", &[Bool]),
    r("shadowmap", &[Opt(&[Bool])]),
    r("shadowmap detail", &[Opt(&[Bool])]),
    r("shadowmap detail samples", &[Int]),
    r("shadowmap merge", &[Opt(&[Bool])]),
    r("shadowmap trace", &[Opt(&[Bool])]),
    r("shadowmap window", &[Floats(4, 4)]),
    r("shadowmap camera", &[Name]),
    r("shadowmap bias", &[Float]),
    r("shadowmap resolution", &[Int]),
    r("shadowmap softness", &[Float]),
    r("shadowmap samples", &[Int]),
    r("shadowmap filter", &[Opt(&[Words(&["clip"])]), Words(FILTERS), Floats(0, 2)]),
    r("shadowmap accuracy", &[Float]),
    r("shadowmap alpha", &[]),
    r("shadowmap color", &[]),
    r("shadowmap file", &[Name]),
    r("lightprofile", &[Name]),
];

/// Statements of `instance … end instance` (besides attributes and the parameter list).
pub static INSTANCE: &[Rule] = &[
    r("visible", &[Opt(&[Bool])]),
    r("shadow", &[Opt(&[ON_OFF_INT])]),
    r("shadowmap", &[Opt(&[Bool])]),
    r("trace", &[Opt(&[Bool])]),
    r("reflection", &[Int]),
    r("refraction", &[Int]),
    r("transparency", &[Int]),
    r("face", &[Words(&["front", "back", "both"])]),
    r("select", &[Opt(&[Bool])]),
    r("caustic", &[Opt(&[ON_OFF_INT])]),
    r("globillum", &[Opt(&[ON_OFF_INT])]),
    r("finalgather", &[Opt(&[ON_OFF_INT])]),
    r("finalgather force", &[Bool]),
    r("shading samples", &[Float]),
    r("hardware", &[Opt(&[Bool])]),
    r("hide", &[Opt(&[Bool])]),
    r("transform", &[Opt(&[Alt(&[&[Matrix], &[Shaders]])])]),
    r("motion", &[Bool]),
    r("motion transform", &[Opt(&[Alt(&[&[Matrix], &[Shaders]])])]),
    r("light", &[Opt(&[Name]), Names]),
    r("light shadow", &[Opt(&[Name]), Names]),
    r("material", &[Opt(&[Alt(&[&[Names], &[Name]])])]),
    r("override", &[]),
    r("approximate", &[Opt(&[Tree])]),
    r("tag", &[Int]),
    r("data", &[DATA]),
];

/// Statements of `instgroup … end instgroup` before its members.
pub static INSTGROUP: &[Rule] = &[r("merge", &[Float]), r("tag", &[Int]), r("data", &[DATA])];

/// Flags of `object … end object` before (or between) its geometry.
pub static OBJECT: &[Rule] = &[
    r("visible", &[Opt(&[Bool])]),
    r("shadow", &[Opt(&[ON_OFF_INT])]),
    r("shadowmap", &[Opt(&[Bool])]),
    r("trace", &[Opt(&[Bool])]),
    r("reflection", &[Int]),
    r("refraction", &[Int]),
    r("transparency", &[Int]),
    r("face", &[Words(&["front", "back", "both"])]),
    r("select", &[Opt(&[Bool])]),
    r("tagged", &[Opt(&[Bool])]),
    r("caustic", &[Opt(&[ON_OFF_INT])]),
    r("globillum", &[Opt(&[ON_OFF_INT])]),
    r("finalgather", &[Opt(&[ON_OFF_INT])]),
    r("finalgather file", &[Alt(&[&[Names], &[Name]])]),
    r("photonmap file", &[Opt(&[Alt(&[&[Words(&["off"])], &[Name]])])]),
    r("shading samples", &[Float]),
    r("hardware", &[Opt(&[Bool])]),
    r("tag", &[Int]),
    r("data", &[DATA]),
    r("transform", &[Matrix]),
    r("max displace", &[Float]),
    r("ray offset", &[Float]),
    r("box", &[Opt(&[Vec3, Vec3])]),
    r("motion box", &[Opt(&[Vec3, Vec3])]),
    r("samples", &[Int, Opt(&[Int])]),
    r("volume group", &[Int]),
    r("file", &[Name]),
    r("intersection", &[Shaders]),
    r("approximate", &[Approx]),
];

/// Statements of `material … end material` (besides the material shader list).
pub static MATERIAL: &[Rule] = &[
    r("opaque", &[]),
    r("nocontour", &[]),
    r("displace", &[Opt(&[Shaders])]),
    r("shadow", &[Opt(&[Shaders])]),
    r("volume", &[Opt(&[Shaders])]),
    r("environment", &[Opt(&[Shaders])]),
    r("contour", &[Opt(&[Shaders])]),
    r("photon", &[Opt(&[Shaders])]),
    r("photonvol", &[Opt(&[Shaders])]),
    r("lightmap", &[Opt(&[Shaders])]),
    r("hardware", &[Opt(&[Shaders])]),
    r("bsdf", &[Opt(&[Shaders])]),
];

/// Flags written before `color|scalar|vector texture`.
pub static TEXTURE_FLAGS: &[Rule] = &[r("local", &[]), r("filter", &[Opt(&[Float])]), r("writable", &[])];

/// What may follow the parameter list of a `declare shader|phenomenon|data`.
pub static DECLARATION: &[Rule] = &[
    r("version", &[Int]),
    r("apply", &[CommaNames]),
    r("scanline", &[Bool]),
    r("trace", &[Bool]),
    r("shadow", &[Alt(&[&[Bool], &[Words(&["sort", "segments"])]])]),
    r("face", &[Words(&["front", "back", "both"])]),
    r("texture", &[Int]),
    r("bump", &[Int]),
    r("derivative", &[Ints(0, 2)]),
    r("object space", &[]),
    r("camera space", &[]),
    r("mixed space", &[]),
    r("world space", &[]),
    r("parallel", &[]),
    r("volume level", &[Int]),
    r("hardware", &[Opt(&[Tree])]),
];

/// What may additionally appear in the body of a `declare phenomenon`.
pub static PHENOMENON: &[Rule] = &[
    r("root", &[Shaders]),
    r("root material", &[Name]),
    r("root light", &[Name]),
    r("output", &[Opt(&[NameNotCall]), Shaders]),
    r("lens", &[Shaders]),
    r("volume", &[Shaders]),
    r("environment", &[Shaders]),
    r("geometry", &[Shaders]),
    r("contour store", &[Shaders]),
    r("contour contrast", &[Shaders]),
    r("output priority", &[Int]),
    r("lens priority", &[Int]),
    r("volume priority", &[Int]),
];

/// Top-level commands.
pub static COMMANDS: &[Rule] = &[
    r("link", &[Name]),
    r("code", &[Alt(&[&[Bytes], &[Name]])]),
    r("system", &[Name]),
    r("verbose", &[Alt(&[&[Bool], &[Int]])]),
    r("echo", &[Name]),
    r("memory", &[Int]),
    r("version", &[Name]),
    r("min version", &[Name]),
    r("max version", &[Name]),
    r("debug", &[Name, Opt(&[Name])]),
    r("set", &[Name, Opt(&[Name])]), // read by the parser itself (see `Parser::item`)
    r("touch", &[Name]),
    r("call", &[Shaders, Opt(&[Comma, Name, Name])]),
    r("root", &[Name]),
];

/// Statements of `lightprofile … end lightprofile`.
pub static LIGHTPROFILE: &[Rule] = &[
    r("format", &[Words(&["ies", "eulumdat"])]),
    r("file", &[Name]),
    r("flags", &[Int]),
    r("hermite", &[Int]),
    r("resolution", &[Int, Int]),
];

/// Statements of `assembly … end assembly`.
pub static ASSEMBLY: &[Rule] = &[
    r("box", &[Opt(&[Vec3, Vec3])]),
    r("motion box", &[Opt(&[Vec3, Vec3])]),
    r("file", &[Name]),
    r("tag", &[Int]),
    r("data", &[DATA]),
];

/// Statements of `colorprofile … end colorprofile`.
pub static COLORPROFILE: &[Rule] = &[
    r("color space", &[Name]),
    r("transform", &[Floats(9, 9)]),
    r("spectrum", &[]),
    r("white", &[Alt(&[&[Words(&["d"]), Int, Opt(&[Float])], &[Bool], &[Floats(2, 3)]])]),
    r("gamma", &[Floats(1, 2), Opt(&[Bool])]),
];

/// Statements in the header of a `hair … end hair` block, before its data.
pub static HAIR: &[Rule] = &[
    r("material", &[Name]),
    r("radius", &[Float]),
    r("approximate", &[Alt(&[&[Int], &[Approx]])]),
    r("degree", &[Int]),
    r("max size", &[Int]),
    r("max depth", &[Int]),
    r("hair n", &[]),
    r("hair m", &[Int]),
    r("hair t", &[Int]),
    r("hair u", &[Int]),
    r("hair radius", &[]),
    r("vertex n", &[]),
    r("vertex m", &[Int]),
    r("vertex t", &[Int]),
    r("vertex u", &[Int]),
    r("vertex radius", &[]),
];

/// Words that may appear in an approximation technique.
pub static APPROX_WORDS: &[&str] = &[
    "view",
    "offscreen",
    "any",
    "tree",
    "grid",
    "delaunay",
    "fine",
    "nosmoothing",
    "sharp",
    "parametric",
    "regular",
    "percent",
    "implicit",
    "length",
    "distance",
    "angle",
    "spatial",
    "curvature",
    "grading",
    "max",
    "min",
    "samples",
];

/// What an `approximate` statement may name before its technique.
pub static APPROX_TARGETS: &[&str] =
    &["surface", "displace", "trilist", "subdivision surface", "ccmesh", "curve", "space curve", "trim", "hair"];

/// Flags that may precede `approximate` in a group.
pub static APPROX_FLAGS: &[&str] = &["visible", "trace", "shadow", "caustic", "globillum"];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_are_unique_per_table() {
        for table in [
            OPTIONS,
            CAMERA,
            OUTPUT_PARAMS,
            FRAMEBUFFER,
            LIGHT,
            INSTANCE,
            INSTGROUP,
            OBJECT,
            MATERIAL,
            TEXTURE_FLAGS,
            DECLARATION,
            PHENOMENON,
            COMMANDS,
            LIGHTPROFILE,
            ASSEMBLY,
            COLORPROFILE,
            HAIR,
        ] {
            let mut keys: Vec<&str> = table.iter().map(|r| r.key).collect();
            keys.sort_unstable();
            let n = keys.len();
            keys.dedup();
            assert_eq!(n, keys.len(), "duplicate key in a table");
        }
    }
}
