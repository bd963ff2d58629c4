//! Expressions and statements.
//!
//! Every node keeps its source span. Names carry a [`Resolution`], `Unresolved` after
//! parsing and filled in by the semantic pass, so that a later compiler can evaluate a body
//! without looking names up again: a [`Resolution::Param`] is replaced by the bound argument
//! (see [`crate::subst`]), a [`Resolution::Local`] by the value of its `let`/statement
//! declaration, a [`Resolution::Function`] by a call into another definition.

use mi::Span;

use super::{QualName, Type, TypeRef};

/// An expression.
#[derive(Clone, Debug)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where it was written.
    pub span: Span,
    /// Its type where the semantic pass could tell (literals, names, calls, simple operators).
    pub ty: Option<Type>,
}

impl Expr {
    /// An expression of `kind` at `span`, type not yet known.
    pub fn new(kind: ExprKind, span: Span) -> Expr {
        Expr { kind, span, ty: None }
    }
}

/// The kinds of expression.
#[derive(Clone, Debug)]
pub enum ExprKind {
    /// `true` / `false`.
    Bool(bool),
    /// An integer literal.
    Int(i64),
    /// A floating literal; `double` for a `d` suffix.
    Float {
        /// The value.
        value: f64,
        /// Written as a `double` literal.
        double: bool,
    },
    /// A string literal.
    Str(String),
    /// A name: a parameter, local, constant or enum value.
    Name(NameRef),
    /// A call of a function or material, or a constructor of a type (`color(1)`,
    /// `material(...)`, `float[](1, 2)`, `df::bsdf_component(...)`).
    Call(Call),
    /// A prefix or postfix unary operator.
    Unary {
        /// Which one.
        op: UnaryOp,
        /// Its operand.
        operand: Box<Expr>,
    },
    /// A binary operator.
    Binary {
        /// Which one.
        op: BinaryOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
    },
    /// `cond ? then : otherwise`.
    Conditional {
        /// The condition (bool).
        cond: Box<Expr>,
        /// Value when true.
        then: Box<Expr>,
        /// Value when false.
        otherwise: Box<Expr>,
    },
    /// `base.field` (struct fields, vector components `x`…`w`).
    Member {
        /// The struct or vector.
        base: Box<Expr>,
        /// The field name.
        field: String,
    },
    /// `base[index]`.
    Index {
        /// The array, vector or matrix.
        base: Box<Expr>,
        /// The index (int).
        index: Box<Expr>,
    },
    /// `let { declarations } in body`.
    Let {
        /// The declarations, in order; each sees the ones before it.
        decls: Vec<VarDecl>,
        /// The value.
        body: Box<Expr>,
    },
    /// `a, b, c`: evaluated in order, the value is the last (the step of a `for` loop only).
    Sequence(Vec<Expr>),
    /// An assignment (statement context only): `target op value`.
    Assign {
        /// `=`, `+=`, ….
        op: AssignOp,
        /// What is assigned to.
        target: Box<Expr>,
        /// The value.
        value: Box<Expr>,
    },
}

/// A name as written and what it refers to.
#[derive(Clone, Debug)]
pub struct NameRef {
    /// The name as written (`tint`, `df::scatter_reflect`, `::limits::FLOAT_MAX`).
    pub name: QualName,
    /// What the semantic pass found it to be.
    pub res: Resolution,
}

/// A call or constructor.
#[derive(Clone, Debug)]
pub struct Call {
    /// The called name (a function, material or type).
    pub callee: QualName,
    /// For array constructors `T[](…)`/`T[n](…)`: the length written.
    pub array: Option<super::ArrayLen>,
    /// Arguments in the order written.
    pub args: Vec<Arg>,
    /// What the callee is, after the semantic pass.
    pub res: Resolution,
}

/// One argument of a call.
#[derive(Clone, Debug)]
pub struct Arg {
    /// The parameter name for a named argument (`tint: c`).
    pub name: Option<String>,
    /// The value.
    pub value: Expr,
    /// Where the argument (with its name) was written.
    pub span: Span,
}

/// What a name refers to.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Resolution {
    /// Not resolved (before the semantic pass).
    #[default]
    Unresolved,
    /// Parameter number `index` of the enclosing material or function.
    Param(usize),
    /// A local declared by `let` or a statement; `id` is unique within the definition.
    Local(u32),
    /// The size symbol `N` of a deferred-size array parameter `T[<N>] p`: the length of the
    /// argument bound to parameter number `index`.
    ArraySize(usize),
    /// A module-level constant: its module and name.
    Constant {
        /// Absolute module name.
        module: String,
        /// The constant's name.
        name: String,
    },
    /// An enum value: the enum's absolute name and the value.
    EnumValue {
        /// Absolute enum type name.
        enum_type: String,
        /// The integer value.
        value: i64,
    },
    /// A function (possibly overloaded): its module and name.
    Function {
        /// Absolute module name.
        module: String,
        /// The function's name.
        name: String,
        /// Index of the chosen overload's declaration in its module's `decls` (see
        /// `ModuleSet::definition`).
        decl: usize,
    },
    /// A material definition: its module and name.
    Material {
        /// Absolute module name.
        module: String,
        /// The material's name.
        name: String,
        /// Index of its declaration in its module's `decls`.
        decl: usize,
    },
    /// A constructor of this type.
    Constructor(Type),
    /// An annotation: its module and name.
    Annotation {
        /// Absolute module name.
        module: String,
        /// The annotation's name.
        name: String,
    },
}

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-x`.
    Neg,
    /// `+x`.
    Plus,
    /// `!x`.
    Not,
    /// `~x`.
    BitNot,
    /// `++x`.
    PreInc,
    /// `--x`.
    PreDec,
    /// `x++`.
    PostInc,
    /// `x--`.
    PostDec,
}

/// Binary operators, in C's (and MDL's) precedence classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `*`.
    Mul,
    /// `/`.
    Div,
    /// `%`.
    Rem,
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `<<`.
    Shl,
    /// `>>` (arithmetic).
    Shr,
    /// `>>>` (logical).
    UShr,
    /// `<`.
    Lt,
    /// `<=`.
    Le,
    /// `>`.
    Gt,
    /// `>=`.
    Ge,
    /// `==`.
    Eq,
    /// `!=`.
    Ne,
    /// `&`.
    BitAnd,
    /// `^`.
    BitXor,
    /// `|`.
    BitOr,
    /// `&&`.
    And,
    /// `||`.
    Or,
}

impl BinaryOp {
    /// Binding strength: higher binds tighter (`*` 10 … `||` 1).
    pub fn precedence(self) -> u8 {
        match self {
            BinaryOp::Mul | BinaryOp::Div | BinaryOp::Rem => 10,
            BinaryOp::Add | BinaryOp::Sub => 9,
            BinaryOp::Shl | BinaryOp::Shr | BinaryOp::UShr => 8,
            BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge => 7,
            BinaryOp::Eq | BinaryOp::Ne => 6,
            BinaryOp::BitAnd => 5,
            BinaryOp::BitXor => 4,
            BinaryOp::BitOr => 3,
            BinaryOp::And => 2,
            BinaryOp::Or => 1,
        }
    }

    /// The operator for a punctuation token, if it is a binary operator.
    pub fn from_punct(p: &str) -> Option<BinaryOp> {
        Some(match p {
            "*" => BinaryOp::Mul,
            "/" => BinaryOp::Div,
            "%" => BinaryOp::Rem,
            "+" => BinaryOp::Add,
            "-" => BinaryOp::Sub,
            "<<" => BinaryOp::Shl,
            ">>" => BinaryOp::Shr,
            ">>>" => BinaryOp::UShr,
            "<" => BinaryOp::Lt,
            "<=" => BinaryOp::Le,
            ">" => BinaryOp::Gt,
            ">=" => BinaryOp::Ge,
            "==" => BinaryOp::Eq,
            "!=" => BinaryOp::Ne,
            "&" => BinaryOp::BitAnd,
            "^" => BinaryOp::BitXor,
            "|" => BinaryOp::BitOr,
            "&&" => BinaryOp::And,
            "||" => BinaryOp::Or,
            _ => return None,
        })
    }

    /// Whether the result is `bool` whatever the operands (comparisons and logic).
    pub fn is_boolean(self) -> bool {
        matches!(
            self,
            BinaryOp::Lt
                | BinaryOp::Le
                | BinaryOp::Gt
                | BinaryOp::Ge
                | BinaryOp::Eq
                | BinaryOp::Ne
                | BinaryOp::And
                | BinaryOp::Or
        )
    }
}

/// Assignment operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AssignOp {
    /// `=`.
    Set,
    /// A compound assignment `op=` with its binary operator.
    Compound(BinaryOp),
}

/// A variable declaration (`let` or statement): `type name = init`.
#[derive(Clone, Debug)]
pub struct VarDecl {
    /// The declared type.
    pub ty: TypeRef,
    /// The name.
    pub name: String,
    /// The initial value, if written.
    pub init: Option<Expr>,
    /// Identifier unique within the enclosing definition (what [`Resolution::Local`] holds).
    pub id: u32,
    /// Annotations written after the name.
    pub annotations: Vec<Annotation>,
    /// Where the name was written.
    pub span: Span,
}

/// A statement of a function body.
#[derive(Clone, Debug)]
pub struct Stmt {
    /// What it is.
    pub kind: StmtKind,
    /// Where it was written.
    pub span: Span,
}

/// The kinds of statement.
#[derive(Clone, Debug)]
pub enum StmtKind {
    /// `{ … }`.
    Block(Vec<Stmt>),
    /// `type a = …, b;`.
    Var(Vec<VarDecl>),
    /// An expression evaluated for its effect (assignment, increment).
    Expr(Box<Expr>),
    /// `if (cond) then else otherwise`.
    If {
        /// The condition.
        cond: Box<Expr>,
        /// Taken when true.
        then: Box<Stmt>,
        /// Taken when false.
        otherwise: Option<Box<Stmt>>,
    },
    /// `for (init; cond; step) body`.
    For {
        /// The initialiser (a declaration or expression statement).
        init: Option<Box<Stmt>>,
        /// The loop condition; absent means `true`.
        cond: Option<Box<Expr>>,
        /// The step expression.
        step: Option<Box<Expr>>,
        /// The body.
        body: Box<Stmt>,
    },
    /// `while (cond) body`.
    While {
        /// The condition.
        cond: Box<Expr>,
        /// The body.
        body: Box<Stmt>,
    },
    /// `do body while (cond);`.
    DoWhile {
        /// The body.
        body: Box<Stmt>,
        /// The condition.
        cond: Box<Expr>,
    },
    /// `switch (value) { case a: … default: … }`.
    Switch {
        /// The value switched on (an integer or an enum).
        value: Box<Expr>,
        /// The cases in order; control falls through to the next one without `break`.
        cases: Vec<SwitchCase>,
    },
    /// `return value;`.
    Return(Option<Box<Expr>>),
    /// `break;`.
    Break,
    /// `continue;`.
    Continue,
    /// `;`.
    Empty,
}

/// One `case label:` (or `default:`) of a `switch` and the statements after it.
#[derive(Clone, Debug)]
pub struct SwitchCase {
    /// The label's value; `None` for `default`.
    pub label: Option<Expr>,
    /// The statements up to the next label.
    pub body: Vec<Stmt>,
    /// Where the label was written.
    pub span: Span,
}

/// An annotation application `name(args)` inside `[[ … ]]`.
#[derive(Clone, Debug)]
pub struct Annotation {
    /// The annotation's name as written (`anno::display_name`).
    pub name: QualName,
    /// Its arguments.
    pub args: Vec<Arg>,
    /// What it resolved to.
    pub res: Resolution,
    /// Where it was written.
    pub span: Span,
}

impl Annotation {
    /// The first argument if it is a string literal (`display_name("x")` gives `x`).
    pub fn string_arg(&self) -> Option<&str> {
        match &self.args.first()?.value.kind {
            ExprKind::Str(s) => Some(s),
            _ => None,
        }
    }
}
