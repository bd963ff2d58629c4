//! Displacement settings of objects and of the options: the `approximate displace …`
//! statement that says how finely displaced surfaces are tessellated, and `max displace`,
//! the bound of the displacement (object-space units). The renderer's displacement stage
//! reads them; the tessellation of the undisplaced object does not.

use mi::ast::{Approximation, Arg, Geometry, GroupItem, Stmt};

/// How an object (or, as the default, the options) asks displaced surfaces to be made.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DisplaceSettings {
    /// The last `approximate displace …` statement (the object's own, or one in its
    /// groups; for the options, one ending in `all`).
    pub approximation: Option<Approximation>,
    /// `max displace d`: displacements are clamped to ±d (object-space units); `None`
    /// when not written (or not positive).
    pub max_displace: Option<f64>,
}

impl DisplaceSettings {
    /// The settings an object's statements and geometry give (later statements win).
    pub fn of_object(stmts: &[&Stmt], geometry: &[Geometry]) -> DisplaceSettings {
        let in_groups = geometry.iter().flat_map(|g| match g {
            Geometry::Group(group) => group.items.iter().collect::<Vec<_>>(),
            _ => Vec::new(),
        });
        let approximation = stmts
            .iter()
            .filter_map(|s| approx_stmt(s))
            .chain(in_groups.filter_map(|i| if let GroupItem::Approximate(a) = i { Some(a) } else { None }))
            .rfind(|a| a.target == Some("displace"))
            .cloned();
        DisplaceSettings { approximation, max_displace: max_displace(stmts) }
    }

    /// The settings of the `options` element's statements.
    pub fn of_options(stmts: &[&Stmt]) -> DisplaceSettings {
        let approximation =
            stmts.iter().filter_map(|s| approx_stmt(s)).rfind(|a| a.target == Some("displace")).cloned();
        DisplaceSettings { approximation, max_displace: max_displace(stmts) }
    }
}

/// The approximation of an `approximate` statement.
fn approx_stmt(s: &Stmt) -> Option<&Approximation> {
    match s {
        Stmt::Kw(k) if k.key == "approximate" => match k.args.first() {
            Some(Arg::Approx(a)) => Some(a),
            _ => None,
        },
        _ => None,
    }
}

/// The last positive `max displace`.
fn max_displace(stmts: &[&Stmt]) -> Option<f64> {
    crate::values::last(stmts, "max displace").and_then(|k| crate::values::f64_arg(k, 0)).filter(|d| *d > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An object's `approximate displace` (in the object or its group) and `max displace`
    /// are read; other approximations are not taken for displacement.
    #[test]
    fn object_settings_are_read() {
        let text = "object \"o\"\n max displace 0.5\n approximate surface parametric 3 3 \"s\"\n \
                    group 0 0 0 1 0 0 0 1 0 v 0 v 1 v 2 p 0 1 2\n approximate displace regular parametric 2 \
                    end group end object\n";
        let parsed = mi::parse_str("t.mi", text);
        assert!(!parsed.diagnostics.has_errors(), "{:?}", parsed.diagnostics.list);
        let Some(mi::ast::Item::Object(o)) = parsed.items.first() else { panic!("no object") };
        let stmts: Vec<&Stmt> = o.stmts.iter().collect();
        let d = DisplaceSettings::of_object(&stmts, &o.geometry);
        assert_eq!(d.max_displace, Some(0.5));
        let a = d.approximation.expect("read");
        assert_eq!(a.target, Some("displace"));
        assert_eq!(&text[a.span.lo as usize..a.span.lo as usize + 19], "approximate displac");
    }
}
