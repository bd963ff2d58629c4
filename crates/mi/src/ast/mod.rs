//! The syntax tree of a `.mi` file.
//!
//! The tree records what the file says, in the file's own terms: names are strings, numbers
//! keep whether they were written as integers, and every node keeps its source [`Span`].
//! Meaning (name resolution, defaults, instancing) belongs to the scene layer.
//!
//! Flat keyword statements (the inside of `options`, `camera`, `light`, `instance`, object
//! flags, …) are [`Stmt`]s checked against the grammar tables of [`crate::grammar`]; elements
//! with structure of their own (shader lists, declarations, geometry) have their own nodes.

mod geometry;

pub use geometry::*;

use crate::preprocess::IncludeTarget;
use crate::source::Span;

/// A name or string as written (quoted or not), with where it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Name {
    /// The text, escapes resolved.
    pub text: String,
    /// Where it was written.
    pub span: Span,
}

impl Name {
    /// The text.
    pub fn as_str(&self) -> &str {
        &self.text
    }
}

/// A number as written: integer or floating point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Num {
    /// Written without a point or exponent.
    Int(i64),
    /// Written with a point or exponent.
    Float(f64),
}

impl Num {
    /// The value as `f64`.
    pub fn as_f64(self) -> f64 {
        match self {
            Num::Int(i) => i as f64,
            Num::Float(f) => f,
        }
    }
}

/// A value given to a shader parameter (or a declaration default, or a string option).
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    /// `null`: no shader/texture/light.
    Null,
    /// `on`, `off`, `true`, `false`.
    Bool(bool),
    /// One number.
    Num(Num),
    /// Several numbers in a row: a colour, vector or transform (`0.5 0.5 0.5 1`).
    Tuple(Vec<Num>),
    /// A string, or the name of a texture, light, material, instance or data element.
    Str(Name),
    /// `= "shader"` or `= "shader.member"`: the result of another shader, evaluated lazily.
    Connect(Name),
    /// `= interface "param"`: inside a phenomenon, the phenomenon's own parameter.
    Interface(Name),
    /// `= [incremental] shader "name" …`: a named shader defined in place and connected.
    Define(Box<ShaderItem>),
    /// `{ "a" 1, "b" 2 }`
    Struct(Vec<Param>),
    /// `[ v, v, … ]`
    Array(Vec<Value>),
    /// Several values of different kinds in a row (rare; kept as written).
    Seq(Vec<Value>),
}

/// `"name" value` inside a shader call or struct value.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The parameter name.
    pub name: Name,
    /// `colorprofile "p"` written after the name, if any.
    pub colorprofile: Option<Name>,
    /// Its value.
    pub value: Value,
    /// The whole `"name" value`.
    pub span: Span,
}

/// One entry of a shader list.
#[derive(Clone, Debug, PartialEq)]
pub enum ShaderItem {
    /// `"declaration" (params)`: an anonymous instance of a declared shader.
    Call {
        /// The declaration's name (`"mib_illum_phong"`, `"mdl::…::flex_material"`).
        decl: Name,
        /// The parameters given.
        params: Vec<Param>,
        /// The whole call.
        span: Span,
    },
    /// `= "name"`: a named shader defined earlier.
    Ref(Name),
    /// `= [incremental] shader "name" list`: a named shader defined in place and referenced.
    Define {
        /// Re-opens an existing named shader.
        incremental: bool,
        /// Its name.
        name: Name,
        /// Its definition.
        list: ShaderList,
    },
}

/// Shaders run in sequence sharing one result (mental ray shader lists).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ShaderList(pub Vec<ShaderItem>);

/// A top-level element, command or preprocessor record.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// `options "name" … end options`
    Options(Block),
    /// `camera "name" … end camera`
    Camera(Block),
    /// `light "name" … end light`
    Light(Block),
    /// `material "name" … end material`
    Material(Material),
    /// `color|scalar|vector texture "name" …`
    Texture(Texture),
    /// `object "name" … end object`
    Object(Object),
    /// `instance "name" "element" … end instance`
    Instance(Instance),
    /// `instgroup "name" … end instgroup`
    Instgroup(Instgroup),
    /// `shader "name" shader_list`
    Shader(ShaderDef),
    /// `declare shader|phenomenon|data … end declare`
    Declare(Declaration),
    /// `data "name" …`
    Data(Data),
    /// `lightprofile "name" … end lightprofile`
    Lightprofile(Block),
    /// `assembly "name" … end assembly`
    Assembly(Block),
    /// `colorprofile "name" … end colorprofile`
    Colorprofile(Block),
    /// `spectrum "name" wavelength value … end spectrum`
    Spectrum(Spectrum),
    /// A top-level `gui "name" { … }` block.
    Gui(Gui),
    /// `namespace "name" … end namespace`
    Namespace(Namespace),
    /// An element with prefixes: `incremental` (re-opens an existing element, its old
    /// contents acting as defaults), `private`, `session depth N`.
    Modified {
        /// The prefixes, in order.
        prefixes: Vec<KwStmt>,
        /// The element.
        item: Box<Item>,
    },
    /// `delete "name"`
    Delete(Name),
    /// `render "root_instgroup" "camera_instance" "options"`
    Render(Render),
    /// `$include "file"`, with the items of the file.
    Include(Include),
    /// `registry "{key}" … end registry`
    Registry(Registry),
    /// A command: `link`, `code`, `$code`, `system`, `verbose`, `echo`, `version`, `set`, …
    Command(Command),
}

/// An element made of a name and keyword statements: options, camera, light, lightprofile,
/// assembly.
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// The element's name.
    pub name: Name,
    /// The statements, in order.
    pub stmts: Vec<Stmt>,
    /// From the keyword to `end …`.
    pub span: Span,
}

/// A statement inside an element block.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    /// A keyword statement of the grammar tables (`trace depth 2 2 4`, `focal 0.035`).
    Kw(KwStmt),
    /// `"name" value…`: a string option (options), unknown names allowed.
    StringOption {
        /// The option's name.
        name: Name,
        /// Its value.
        value: Value,
    },
    /// `attribute type "name" value…` (Iray).
    Attribute(Attribute),
    /// A shader list given without keyword (the light shader of a light).
    Shaders(ShaderList),
    /// `output …` in a camera.
    Output(Output),
    /// `framebuffer "name" …` in a camera (mental ray 3.10+).
    Framebuffer(Framebuffer),
}

/// A keyword statement: its key (the keywords as one space-separated string, exactly as in
/// the grammar tables) and its arguments in order.
#[derive(Clone, Debug, PartialEq)]
pub struct KwStmt {
    /// E.g. `"trace depth"`, `"shadowmap resolution"`, `"rectangle"`.
    pub key: &'static str,
    /// The arguments, in the order written.
    pub args: Vec<Arg>,
    /// The whole statement.
    pub span: Span,
}

/// One argument of a keyword statement.
#[derive(Clone, Debug, PartialEq)]
pub enum Arg {
    /// `on`/`off`/`true`/`false`.
    Bool(bool),
    /// An integer.
    Int(i64),
    /// A number where a float is expected.
    Float(f64),
    /// A string or name.
    Name(Name),
    /// A keyword from a fixed set (`gauss`, `only`, `infinity`).
    Word(&'static str),
    /// A fixed-size group of numbers: colour (3 or 4), vector (3), matrix (16).
    Floats(Vec<f64>),
    /// A shader list.
    Shaders(ShaderList),
    /// `[ "a", "b" ]`
    Names(Vec<Name>),
    /// A number kept as written (where mental ray tells `4` from `4.`).
    Num(Num),
    /// `[ shader, shader ]`: a bracketed, comma-separated shader list (`state`).
    ShaderArray(ShaderList),
    /// `a, b, c`: comma-separated names without brackets (`apply material, shadow`).
    List(Vec<Name>),
    /// A bracketed token tree kept as written.
    Tree(TokenTree),
    /// An approximation.
    Approx(Box<Approximation>),
    /// `,` (between the parts of `call`).
    Comma,
    /// Hexadecimal byte strings (`code 'c0de…'`).
    Bytes(Vec<Vec<u8>>),
}

/// `attribute [override] {const|global} type "name" value` (Iray and mental ray 3.8+): a
/// typed key/value on an element; or `attribute [override] flag [value]` for the flag forms
/// (`attribute visible on`, `attribute tag 3`, `attribute face front`).
#[derive(Clone, Debug, PartialEq)]
pub struct Attribute {
    /// `override`, `const`, `global`.
    pub modifiers: Vec<Name>,
    /// The type (`boolean`, `integer`, `scalar`, `string`, `color`, `vector`) or the flag.
    pub ty: Name,
    /// The attribute name (typed form only).
    pub name: Option<Name>,
    /// The value (absent for bare flags such as `attribute caustic`).
    pub value: Option<Value>,
    /// The whole statement.
    pub span: Span,
}

/// `output "types" "format" [option] "file"` or `output "types" = shader_list`.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// `colorprofile "p"`, if given.
    pub colorprofile: Option<Name>,
    /// The frame buffer types (`"+rgba,fb0"`); absent for the `output "format" "file"` form.
    pub types: Option<Name>,
    /// What the output does.
    pub kind: OutputKind,
    /// The whole statement.
    pub span: Span,
}

/// What an `output` statement does.
#[derive(Clone, Debug, PartialEq)]
pub enum OutputKind {
    /// Writes a file.
    File {
        /// The file format (`"exr"`).
        format: Name,
        /// Format options such as `quality 90` (keyword statements).
        options: Vec<KwStmt>,
        /// The file name.
        file: Name,
    },
    /// Runs output shaders over the frame buffers.
    Shader(ShaderList),
    /// A bare `output`: clears the outputs defined so far.
    Clear,
}

/// `framebuffer "name" field… ` inside a camera (mental ray 3.10+).
#[derive(Clone, Debug, PartialEq)]
pub struct Framebuffer {
    /// Buffer name.
    pub name: Name,
    /// Its fields (`datatype "rgba_fp"`, `filtering on`, …).
    pub fields: Vec<Stmt>,
    /// The whole block.
    pub span: Span,
}

/// `material "name" … end material`.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Material name.
    pub name: Name,
    /// The main (material) shader list.
    pub shaders: Option<ShaderList>,
    /// `opaque`, `nocontour`, other slots (`shadow …`, `photon …`), attributes.
    pub stmts: Vec<Stmt>,
    /// The whole element.
    pub span: Span,
}

/// The kind of values a texture holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureKind {
    /// `color texture`
    Color,
    /// `scalar texture`
    Scalar,
    /// `vector texture`
    Vector,
}

/// `[local] [filter [s]] [writable] color|scalar|vector texture "name" [colorprofile "p"] source`.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Texture name.
    pub name: Name,
    /// Colour, scalar or vector.
    pub kind: TextureKind,
    /// Flags written before the type (`local`, `filter 0.5`, `writable`).
    pub flags: Vec<KwStmt>,
    /// `colorprofile "p"`, if given.
    pub colorprofile: Option<Name>,
    /// Where the pixels come from.
    pub source: TextureSource,
    /// The whole element.
    pub span: Span,
}

/// Where a texture's pixels come from.
#[derive(Clone, Debug, PartialEq)]
pub enum TextureSource {
    /// An image file: `"file" ["filetype" ["fileformat"]] [ [w h [depth]] ]`.
    File {
        /// The file name.
        file: Name,
        /// For writable textures: the file type and format.
        filetype: Vec<Name>,
        /// `[ w h [depth] ]` size hint, if given.
        size: Option<Vec<i64>>,
    },
    /// Inline pixels: `[ w h [depth] ]` then hexadecimal byte strings.
    Pixels {
        /// Width, height and optional bytes per component, as written.
        dims: Vec<i64>,
        /// The byte strings as written (each at most 1024 bytes).
        pieces: Vec<Vec<u8>>,
    },
    /// A texture shader.
    Shader(ShaderList),
}

/// `instance "name" "element" | geometry shader … end instance`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Instance name.
    pub name: Name,
    /// What is instanced.
    pub target: InstanceTarget,
    /// Flags, transform, materials, light lists, attributes.
    pub stmts: Vec<Stmt>,
    /// `( params )`: instance parameters for inheritance/traversal shaders.
    pub params: Option<Vec<Param>>,
    /// The whole element.
    pub span: Span,
}

/// What an instance instances.
#[derive(Clone, Debug, PartialEq)]
pub enum InstanceTarget {
    /// An object, light, camera or instgroup by name.
    Element(Name),
    /// `geometry shader_list`: procedural geometry.
    Geometry(ShaderList),
    /// Nothing given (allowed for incremental changes).
    None,
}

/// `instgroup "name" … end instgroup`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instgroup {
    /// Group name.
    pub name: Name,
    /// `merge`, `tag`, `data`, attributes.
    pub stmts: Vec<Stmt>,
    /// The instances (or instgroups) it holds.
    pub members: Vec<Name>,
    /// The whole element.
    pub span: Span,
}

/// `shader "name" shader_list`: a named shader instance.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaderDef {
    /// The instance name.
    pub name: Name,
    /// What it runs.
    pub list: ShaderList,
    /// The whole statement.
    pub span: Span,
}

/// `data "name" …`: user data.
#[derive(Clone, Debug, PartialEq)]
pub struct Data {
    /// Data element name.
    pub name: Name,
    /// `tag N`, if given.
    pub tag: Option<i64>,
    /// The payload.
    pub body: DataBody,
    /// The whole element.
    pub span: Span,
}

/// The payload of a `data` element.
#[derive(Clone, Debug, PartialEq)]
pub enum DataBody {
    /// `"declaration" (params)`: typed user data.
    Params {
        /// The `declare data` name.
        decl: Name,
        /// The values.
        params: Vec<Param>,
    },
    /// `<size> [ 'hex' … ]`: raw bytes as hexadecimal byte strings.
    Bytes {
        /// The declared size in bytes.
        size: i64,
        /// The byte strings as written (each at most 1024 bytes).
        pieces: Vec<Vec<u8>>,
    },
    /// `"file"`: bytes read from a file.
    File(Name),
}

/// `spectrum "name" wavelength value … end spectrum`.
#[derive(Clone, Debug, PartialEq)]
pub struct Spectrum {
    /// The spectrum's name.
    pub name: Name,
    /// (wavelength, value) pairs, flattened.
    pub values: Vec<f64>,
    /// The whole element.
    pub span: Span,
}

/// `namespace "name" … end namespace`.
#[derive(Clone, Debug, PartialEq)]
pub struct Namespace {
    /// The namespace name (elements inside are named `name::element`).
    pub name: Name,
    /// What it contains.
    pub items: Vec<Item>,
    /// The whole block.
    pub span: Span,
}

/// `render "root" "camera_instance" "options"`.
#[derive(Clone, Debug, PartialEq)]
pub struct Render {
    /// The root instgroup.
    pub root: Name,
    /// The camera instance.
    pub camera: Name,
    /// The options element.
    pub options: Name,
    /// The whole statement.
    pub span: Span,
}

/// `$include`, with the items of the included file.
#[derive(Clone, Debug, PartialEq)]
pub struct Include {
    /// The file name as written.
    pub path: Name,
    /// `<file>` form.
    pub angle: bool,
    /// What it resolved to.
    pub target: IncludeTarget,
    /// The included file's items (empty for MDL modules and missing files).
    pub items: Vec<Item>,
}

/// `registry "{key}" … end registry`.
#[derive(Clone, Debug, PartialEq)]
pub struct Registry {
    /// The key (with braces as written).
    pub key: Name,
    /// Its entries: `value "v"`, `link "…"`, `mi "…"`, `"k" "v"` …, as (field, value).
    pub entries: Vec<(Name, Name)>,
    /// The whole block.
    pub span: Span,
}

/// A command: statements that act at once rather than define an element.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// A keyword command from the grammar table (`link "base.so"`, `verbose on`,
    /// `min version "3.6"`, `set "x" "y"`, `$lookup "{k}"` …). `link`, `code` and `system`
    /// are recorded and never executed.
    Kw(KwStmt),
    /// `$code … $end code`: inline C source, recorded, never compiled.
    CodeBlock {
        /// The source text.
        text: String,
        /// Where it was.
        span: Span,
    },
}

/// `declare shader|phenomenon|data … end declare`.
#[derive(Clone, Debug, PartialEq)]
pub struct Declaration {
    /// What is declared.
    pub kind: DeclKind,
    /// Written in the old style, `declare color "name" (…)` without `shader`.
    pub legacy: bool,
    /// The return type (omitted means `color`).
    pub ret: Option<ParamType>,
    /// The declared name.
    pub name: Name,
    /// Parameters, in order.
    pub params: Vec<ParamDecl>,
    /// Everything after the parameter list up to `end declare`.
    pub body: Vec<DeclItem>,
    /// The whole declaration.
    pub span: Span,
}

/// What a declaration declares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DeclKind {
    /// A shader (C code in a library; mira's built-ins).
    Shader,
    /// A phenomenon: a shader built from other shaders.
    Phenomenon,
    /// A user data type.
    Data,
}

/// The type of a declared parameter or return value.
#[derive(Clone, Debug, PartialEq)]
pub enum ParamType {
    /// `boolean`
    Boolean,
    /// `integer`
    Integer,
    /// `scalar`
    Scalar,
    /// `string`
    String,
    /// `color`
    Color,
    /// `vector`
    Vector,
    /// `transform`
    Transform,
    /// `shader`
    Shader,
    /// `data`
    Data,
    /// `light`
    Light,
    /// `material`
    Material,
    /// `geometry`
    Geometry,
    /// `lightprofile`
    Lightprofile,
    /// `spectrum`
    Spectrum,
    /// `color texture`
    ColorTexture,
    /// `scalar texture`
    ScalarTexture,
    /// `vector texture`
    VectorTexture,
    /// `struct { … }`
    Struct(Vec<ParamDecl>),
    /// `array T`
    Array(Box<ParamType>),
}

/// One declared parameter: `type "name" [default value]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamDecl {
    /// Its type.
    pub ty: ParamType,
    /// Its name.
    pub name: Name,
    /// `default …`, if given.
    pub default: Option<Value>,
    /// The whole declaration.
    pub span: Span,
}

/// Something in a declaration after its parameter list.
#[derive(Clone, Debug, PartialEq)]
pub enum DeclItem {
    /// A keyword statement: `version 3`, `apply material, shadow`, `scanline off`,
    /// `trace on`, `derivative 1`, `root material "m"`, …
    Kw(KwStmt),
    /// A `gui "name" { … }` block (user-interface hints; kept as a token tree).
    Gui(Gui),
    /// An element defined inside a phenomenon (shaders, materials, lights, instances, …).
    Item(Item),
}

/// `gui "name" { control … }`: interface hints, kept as written.
#[derive(Clone, Debug, PartialEq)]
pub struct Gui {
    /// The gui name, if given.
    pub name: Option<Name>,
    /// The body.
    pub body: Vec<TokenTree>,
    /// The whole block.
    pub span: Span,
}

/// A generic bracketed token tree, for parts of the language that carry no meaning for
/// rendering and are kept only to be printed back (gui blocks).
#[derive(Clone, Debug, PartialEq)]
pub enum TokenTree {
    /// A word, string, number or punctuation.
    Atom(Atom),
    /// `( … )`
    Paren(Vec<TokenTree>),
    /// `[ … ]`
    Bracket(Vec<TokenTree>),
    /// `{ … }`
    Brace(Vec<TokenTree>),
}

/// One token of a [`TokenTree`].
#[derive(Clone, Debug, PartialEq)]
pub enum Atom {
    /// An unquoted word.
    Word(String),
    /// A quoted string.
    Str(String),
    /// A number.
    Num(Num),
    /// `,`
    Comma,
    /// `=`
    Equals,
    /// `%`
    Percent,
}
