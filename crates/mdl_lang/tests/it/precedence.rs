//! Operators group as in C (MDL takes C's precedence and associativity): each expression is
//! parsed and printed back fully parenthesised.

use mdl_lang::ast::*;
use mdl_lang::{MdlSearchPath, ModuleSet};

fn op(o: BinaryOp) -> &'static str {
    match o {
        BinaryOp::Mul => "*",
        BinaryOp::Div => "/",
        BinaryOp::Rem => "%",
        BinaryOp::Add => "+",
        BinaryOp::Sub => "-",
        BinaryOp::Shl => "<<",
        BinaryOp::Shr => ">>",
        BinaryOp::UShr => ">>>",
        BinaryOp::Lt => "<",
        BinaryOp::Le => "<=",
        BinaryOp::Gt => ">",
        BinaryOp::Ge => ">=",
        BinaryOp::Eq => "==",
        BinaryOp::Ne => "!=",
        BinaryOp::BitAnd => "&",
        BinaryOp::BitXor => "^",
        BinaryOp::BitOr => "|",
        BinaryOp::And => "&&",
        BinaryOp::Or => "||",
    }
}

fn show(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Int(i) => i.to_string(),
        ExprKind::Bool(b) => b.to_string(),
        ExprKind::Name(n) => n.name.to_string(),
        ExprKind::Binary { op: o, lhs, rhs } => format!("({} {} {})", show(lhs), op(*o), show(rhs)),
        ExprKind::Unary { op: UnaryOp::Neg, operand } => format!("(-{})", show(operand)),
        ExprKind::Unary { op: UnaryOp::Not, operand } => format!("(!{})", show(operand)),
        ExprKind::Unary { op: UnaryOp::BitNot, operand } => format!("(~{})", show(operand)),
        ExprKind::Conditional { cond, then, otherwise } => {
            format!("({} ? {} : {})", show(cond), show(then), show(otherwise))
        }
        ExprKind::Member { base, field } => format!("{}.{field}", show(base)),
        ExprKind::Index { base, index } => format!("{}[{}]", show(base), show(index)),
        ExprKind::Call(c) => {
            let args: Vec<String> = c.args.iter().map(|a| show(&a.value)).collect();
            format!("{}({})", c.callee, args.join(", "))
        }
        other => panic!("not printed: {other:?}"),
    }
}

/// Parses `e` as the body of `int f(int a, …)` and prints it back.
fn grouped(e: &str) -> String {
    let text = format!(
        "mdl 1.7;\nint g(int x) = x;\nexport int f(int a, int b, int c, int d, int e, int[2] v, bool p, bool q) = {e};\n"
    );
    let mut set = ModuleSet::new(MdlSearchPath::new());
    let m = set.load_source("::prec", &text).unwrap_or_else(|err| panic!("{e}: {err}"));
    let f = m.functions().find(|f| f.name == "f").unwrap();
    match &f.body {
        Body::Expr(x) => show(x),
        _ => unreachable!(),
    }
}

#[test]
fn multiplicative_binds_tighter_than_additive_and_both_group_left() {
    assert_eq!(grouped("a + b * c"), "(a + (b * c))");
    assert_eq!(grouped("a - b - c"), "((a - b) - c)");
    assert_eq!(grouped("a / b * c % d"), "(((a / b) * c) % d)");
    assert_eq!(grouped("a * (b + c)"), "(a * (b + c))");
}

#[test]
fn shifts_comparisons_equality_and_bit_operators_in_c_order() {
    assert_eq!(grouped("a << b + c"), "(a << (b + c))");
    assert_eq!(grouped("a < b << c ? 1 : 0"), "((a < (b << c)) ? 1 : 0)");
    assert_eq!(grouped("a < b == c > d ? 1 : 0"), "(((a < b) == (c > d)) ? 1 : 0)");
    assert_eq!(grouped("a & b ^ c | d"), "(((a & b) ^ c) | d)");
    assert_eq!(grouped("a == b & c"), "((a == b) & c)");
}

#[test]
fn logical_operators_and_the_conditional() {
    assert_eq!(grouped("p || q && a > b ? 1 : 2"), "((p || (q && (a > b))) ? 1 : 2)");
    assert_eq!(grouped("p ? a : q ? b : c"), "(p ? a : (q ? b : c))");
    assert_eq!(grouped("p ? q ? a : b : c"), "(p ? (q ? a : b) : c)");
}

#[test]
fn unary_and_postfix_bind_tightest() {
    assert_eq!(grouped("-a * b"), "((-a) * b)");
    assert_eq!(grouped("-v[1] + g(a) * ~b"), "((-v[1]) + (g(a) * (~b)))");
    assert_eq!(grouped("!p && q ? 1 : 0"), "(((!p) && q) ? 1 : 0)");
    assert_eq!(grouped("a - -b"), "(a - (-b))");
}
