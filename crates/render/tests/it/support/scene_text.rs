//! A builder for the `.mi` text of a small test scene: `$include`s, options "opt", camera
//! "cam" and its instance "cam_inst", lights with their instances, the caller's shaders,
//! materials and objects, and the instgroup "root" with the `render` statement. The lines
//! come out in the order the builder's calls give them (after the fixed head: includes,
//! options, camera, camera instance), one statement a line, so a scene's line numbers are
//! those of the text it replaces.

/// The matrix of a camera instance that looks straight down −y from `height` above the
/// origin (mental ray's world-to-camera transform, row by row).
pub fn looking_down(height: f32) -> String {
    format!("1 0 0 0  0 0 1 0  0 -1 0 0  0 0 -{height} 1")
}

/// The `transform` matrix (world to object) of an instance that adds (`tx`, `ty`, `tz`)
/// to a world point: its object sits at (−`tx`, −`ty`, −`tz`) in world space.
pub fn translate(tx: f32, ty: f32, tz: f32) -> String {
    format!("1 0 0 0  0 1 0 0  0 0 1 0  {tx} {ty} {tz} 1")
}

/// A directional light (`mib_light_infinite`) of colour π shining down −z: a Lambertian
/// surface facing +z shows its albedo.
pub const PI_SUN: &str = r#""mib_light_infinite" ("color" 3.14159265 3.14159265 3.14159265) direction 0 0 -1"#;

/// The `.mi` text of a test scene under construction (see the module's doc).
#[derive(Clone, Debug)]
pub struct SceneText {
    /// Files named by `$include` lines, in order.
    includes: Vec<String>,
    /// The statements inside `options "opt" … end options`.
    options: String,
    /// The camera's statements before its `resolution`.
    camera: String,
    /// The image's width and height in pixels.
    resolution: (u32, u32),
    /// The camera instance's `transform` matrix (world to camera), none for the identity.
    camera_transform: Option<String>,
    /// The lines after the camera instance, in order.
    body: Vec<String>,
    /// The instgroup "root"'s members after "cam_inst", in order.
    members: Vec<String>,
}

impl Default for SceneText {
    fn default() -> Self {
        Self::new()
    }
}

impl SceneText {
    /// A scene of a camera alone: options `filter box 1 1`, camera `focal 1 aperture 2
    /// aspect 1` (a 90° view) at 8×8 pixels at the origin looking down −z.
    pub fn new() -> Self {
        SceneText {
            includes: Vec::new(),
            options: "filter box 1 1".into(),
            camera: "focal 1 aperture 2 aspect 1".into(),
            resolution: (8, 8),
            camera_transform: None,
            body: Vec::new(),
            members: Vec::new(),
        }
    }

    /// The Ptex and texture tests' head-on view: [`SceneText::new`] at `side`² pixels with
    /// the [`PI_SUN`] light "sun".
    pub fn head_on(side: u32) -> Self {
        Self::new().resolution(side).light("sun", PI_SUN, None)
    }

    /// The Maya tests' view: `$include "mayabase.mi"`, options `options`, camera
    /// `focal 1 aperture {aperture} aspect 1` at `side`² pixels looking down from
    /// `height` above the origin.
    pub fn maya_down(options: &str, aperture: f32, side: u32, height: f32) -> Self {
        Self::new()
            .include("mayabase.mi")
            .options(options)
            .camera(&format!("focal 1 aperture {aperture} aspect 1"))
            .resolution(side)
            .camera_transform(&looking_down(height))
    }

    /// Adds `$include "{file}"` after the includes so far.
    pub fn include(mut self, file: &str) -> Self {
        self.includes.push(file.into());
        self
    }

    /// Sets the statements inside the options block.
    pub fn options(mut self, statements: &str) -> Self {
        self.options = statements.into();
        self
    }

    /// Sets the camera's statements before its resolution (focal length, aperture,
    /// aspect, outputs, volume shader).
    pub fn camera(mut self, statements: &str) -> Self {
        self.camera = statements.into();
        self
    }

    /// Sets a square image of `side` × `side` pixels.
    pub fn resolution(mut self, side: u32) -> Self {
        self.resolution = (side, side);
        self
    }

    /// Sets the camera instance's `transform` matrix (16 numbers, world to camera).
    pub fn camera_transform(mut self, matrix: &str) -> Self {
        self.camera_transform = Some(matrix.into());
        self
    }

    /// Adds light `name` (its shader and statements `definition`, between the name and
    /// `end light`; may span lines) and its instance `{name}_inst` with the `transform`
    /// matrix (world to light) when given, a member of the root group.
    pub fn light(mut self, name: &str, definition: &str, transform: Option<&str>) -> Self {
        self.body.push(format!("light \"{name}\" {definition} end light"));
        self.body.push(match transform {
            Some(m) => format!("instance \"{name}_inst\" \"{name}\" transform {m} end instance"),
            None => format!("instance \"{name}_inst\" \"{name}\" end instance"),
        });
        self.members.push(format!("{name}_inst"));
        self
    }

    /// Adds `lines` (shaders, materials, objects, instances) as they are.
    pub fn text(mut self, lines: &str) -> Self {
        self.body.push(lines.into());
        self
    }

    /// Adds instance `name` (defined in the text) to the root group.
    pub fn instance(mut self, name: &str) -> Self {
        self.members.push(name.into());
        self
    }

    /// The options, camera and camera instance lines alone (no includes, no line break
    /// after the last).
    pub fn head(&self) -> String {
        let (w, h) = self.resolution;
        let instance = match &self.camera_transform {
            Some(m) => format!("instance \"cam_inst\" \"cam\" transform {m} end instance"),
            None => "instance \"cam_inst\" \"cam\" end instance".to_string(),
        };
        format!(
            "options \"opt\" {} end options\ncamera \"cam\" {} resolution {w} {h} end camera\n{instance}",
            self.options, self.camera
        )
    }

    /// The scene's text: a blank first line, then the includes, the head, the body and
    /// the root.
    pub fn build(&self) -> String {
        let mut s = String::from("\n");
        for file in &self.includes {
            s += &format!("$include \"{file}\"\n");
        }
        s += &self.head();
        s += "\n";
        for lines in &self.body {
            s += lines;
            s += "\n";
        }
        let members: String = self.members.iter().map(|m| format!(" \"{m}\"")).collect();
        s += &format!("instgroup \"root\" \"cam_inst\"{members} end instgroup\n");
        s += "render \"root\" \"cam_inst\" \"opt\"\n";
        s
    }
}
