//! Unit tests of instance flags: instance modes forcing bits on or off, and the closest
//! instance winning over the object and the defaults.

use super::*;

fn stmts(text: &str) -> Vec<Stmt> {
    let parsed = mi::parse_str("f.mi", &format!("instance \"i\" \"o\"\n{text}\nend instance"));
    assert!(!parsed.diagnostics.has_errors(), "{}", parsed.diagnostics.render(&parsed.sources));
    let mi::Item::Instance(i) = &parsed.items[0] else { panic!() };
    i.stmts.clone()
}

#[test]
fn instance_modes_force_bits_on_or_off() {
    let f = FlagSet::read(&stmts("shadow 6\nreflection 2\ntrace off"), FlagOwner::Instance);
    assert_eq!(f.shadow, ModeSet { cast: Some(false), receive: Some(true) });
    // `trace off` on an instance forces reflection and refraction off, after `reflection 2`.
    assert_eq!(f.reflection, ModeSet::both(false));
    let f = FlagSet::read(&stmts("reflection 2"), FlagOwner::Instance);
    assert_eq!(f.reflection, ModeSet { cast: None, receive: Some(true) });
}

#[test]
fn closest_instance_wins_then_object_then_defaults() {
    let object = FlagSet::read(&stmts("visible off\nshadow 1\ntrace off"), FlagOwner::Object);
    let parent = FlagSet::read(&stmts("visible on\nshadow 8"), FlagOwner::Instance);
    let child = FlagSet::read(&stmts("visible off"), FlagOwner::Instance);
    let flags = child.or(parent).or(object).resolve(Face::Both);
    assert!(!flags.visible);
    assert_eq!(flags.shadow, Mode { cast: true, receive: false });
    // Object `trace off`: not seen by reflections, still reflects.
    assert_eq!(flags.reflection, Mode { cast: false, receive: true });
    assert_eq!(flags.transparency, Mode::BOTH);
    let flags = FlagSet::default().resolve(Face::Front);
    assert_eq!(flags.face, Face::Front);
    assert!(flags.visible);
}
