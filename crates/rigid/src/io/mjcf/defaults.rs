//! `<default>` classes: a tree of named classes, each holding default attributes per element kind
//! (`<joint>`, `<geom>`, `<site>`, `<mesh>`, `<material>`, ...), inheriting its parent's.
//!
//! MuJoCo's semantics (`mjXReader::Default` and `mjXReader::Body`, `src/xml/xml_native_reader.cc`):
//! the top-level `<default>` is the class `main`; a nested `<default class="name">` starts from a
//! copy of its parent's values. An element takes its own `class`, else the `childclass` of the
//! nearest enclosing body or frame that has one, else `main`; its own attributes then override
//! the class's one by one. Two attributes are not plain overrides, because MuJoCo reads them into
//! a struct that the class filled first:
//!
//! - the orientation alternatives (`axisangle`, `xyaxes`, `zaxis`, `euler`): one given by the
//!   element replaces the class's, and any alternative (the element's or the class's) wins over
//!   `quat`;
//! - `size` and `friction` may give fewer numbers than they hold: those replace the first
//!   components only, the rest keep the class's values.
//!
//! `<freejoint>` takes no defaults.

use super::xml::Element;
use super::{MjcfError, Reader};
use std::collections::HashMap;

/// The orientation alternatives (at most one per element).
pub(super) const ALTERNATIVES: [&str; 4] = ["axisangle", "xyaxes", "zaxis", "euler"];

/// Attributes that may give fewer numbers than they hold, with their length.
const PARTIAL: [(&str, usize); 2] = [("size", 3), ("friction", 3)];

/// An element's attributes after defaults: the class's, overridden by the element's own.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Attrs(Vec<(String, String)>);

impl From<Vec<(String, String)>> for Attrs {
    fn from(v: Vec<(String, String)>) -> Self {
        Self(v)
    }
}

impl Attrs {
    /// The value of `name`.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// `base` overridden by `over` (with the two rules of the module documentation).
    fn overlay(base: &Self, over: &[(String, String)]) -> Self {
        let mut out = base.0.clone();
        if over.iter().any(|(k, _)| ALTERNATIVES.contains(&k.as_str())) {
            out.retain(|(k, _)| !ALTERNATIVES.contains(&k.as_str()));
        }
        for (k, v) in over {
            let merged = match PARTIAL.iter().find(|(p, _)| p == k) {
                Some(&(_, len)) => match out.iter().find(|(o, _)| o == k) {
                    Some((_, old)) => partial(old, v, len),
                    None => v.clone(),
                },
                None => v.clone(),
            };
            match out.iter_mut().find(|(o, _)| o == k) {
                Some(slot) => slot.1 = merged,
                None => out.push((k.clone(), merged)),
            }
        }
        Self(out)
    }
}

/// The numbers of `new` followed by those of `old` beyond them (at most `len`).
fn partial(old: &str, new: &str, len: usize) -> String {
    let n: Vec<&str> = new.split_whitespace().collect();
    let o: Vec<&str> = old.split_whitespace().collect();
    let mut all: Vec<&str> = n.clone();
    if n.len() < len {
        all.extend(o.iter().skip(n.len()).take(len - n.len()));
    }
    all.join(" ")
}

/// One class: its parent and its attributes per element kind (already merged with the
/// parent's).
#[derive(Clone, Debug, Default)]
struct Class {
    kinds: HashMap<String, Attrs>,
}

/// Every default class of a model.
#[derive(Clone, Debug)]
pub(super) struct Defaults {
    classes: HashMap<String, Class>,
}

/// The name of the top-level class.
pub(super) const MAIN: &str = "main";

impl Defaults {
    /// The classes of the `<default>` children of `root`.
    ///
    /// # Errors
    /// A nested `<default>` without a class name, a class name used twice, or a top-level class
    /// not called `main`.
    pub fn read(root: &Element, r: &Reader) -> Result<Self, MjcfError> {
        let mut d = Self {
            classes: HashMap::from([(MAIN.to_string(), Class::default())]),
        };
        for section in root.children_named("default") {
            if let Some(name) = section.attr("class") {
                if name != MAIN {
                    return Err(r.invalid(
                        section,
                        format!(
                            "the top-level default class is \"main\" and cannot be renamed \
                             (class \"{name}\")"
                        ),
                    ));
                }
            }
            d.read_class(section, MAIN, None, r)?;
        }
        Ok(d)
    }

    fn read_class(
        &mut self,
        section: &Element,
        name: &str,
        parent: Option<&str>,
        r: &Reader,
    ) -> Result<(), MjcfError> {
        let mut class = match parent {
            Some(p) => self.classes[p].clone(),
            None => self.classes[MAIN].clone(),
        };
        for e in section.children.iter().filter(|e| e.tag != "default") {
            let base = class.kinds.get(&e.tag).cloned().unwrap_or_default();
            let own: Vec<(String, String)> = e
                .attrs
                .iter()
                .filter(|(k, _)| k != "class" && k != "name")
                .cloned()
                .collect();
            check_alternatives(e, r)?;
            class
                .kinds
                .insert(e.tag.clone(), Attrs::overlay(&base, &own));
        }
        self.classes.insert(name.to_string(), class);
        for child in section.children_named("default") {
            let Some(child_name) = child.attr("class").filter(|n| !n.is_empty()) else {
                return Err(r.invalid(child, "a nested <default> needs a \"class\" name".into()));
            };
            if self.classes.contains_key(child_name) {
                return Err(r.invalid(
                    child,
                    format!("default class \"{child_name}\" is defined twice"),
                ));
            }
            self.read_class(child, child_name, Some(name), r)?;
        }
        Ok(())
    }

    /// Whether class `name` exists.
    pub fn has(&self, name: &str) -> bool {
        self.classes.contains_key(name)
    }

    /// The attributes of element `e` (of kind `e.tag`) under class `class` (the element's own
    /// `class` attribute wins over it).
    ///
    /// # Errors
    /// An unknown class, or two orientation alternatives on the element.
    pub fn resolve(&self, e: &Element, class: &str, r: &Reader) -> Result<Attrs, MjcfError> {
        self.resolve_as(e, class, &e.tag, r)
    }

    /// As [`resolve`](Self::resolve), with the defaults of kind `kind` (`equality` for a
    /// `<connect>`, `tendon` for a `<spatial>`, ...).
    ///
    /// # Errors
    /// As [`resolve`](Self::resolve).
    pub fn resolve_as(
        &self,
        e: &Element,
        class: &str,
        kind: &str,
        r: &Reader,
    ) -> Result<Attrs, MjcfError> {
        let class = self.class_of(e, class, r)?;
        check_alternatives(e, r)?;
        let base = self.classes[class]
            .kinds
            .get(kind)
            .cloned()
            .unwrap_or_default();
        Ok(Attrs::overlay(&base, &e.attrs))
    }

    /// The class an element takes: its own `class`, else `inherited`.
    ///
    /// # Errors
    /// An unknown class.
    pub fn class_of<'a>(
        &self,
        e: &'a Element,
        inherited: &'a str,
        r: &Reader,
    ) -> Result<&'a str, MjcfError> {
        let name = e.attr("class").unwrap_or(inherited);
        if self.has(name) {
            Ok(name)
        } else {
            Err(r.invalid(e, format!("unknown default class \"{name}\"")))
        }
    }
}

/// MuJoCo refuses an element that writes its orientation twice (`quat` counts).
fn check_alternatives(e: &Element, r: &Reader) -> Result<(), MjcfError> {
    let given: Vec<&str> = std::iter::once("quat")
        .chain(ALTERNATIVES)
        .filter(|k| e.attr(k).is_some())
        .collect();
    if given.len() > 1 {
        return Err(r.invalid(
            e,
            format!(
                "the orientation is given twice ({}); give one of quat, axisangle, xyaxes, \
                 zaxis, euler",
                given.join(", ")
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partial_sizes_keep_the_class_components_beyond_those_given() {
        assert_eq!(partial("1 2 3", "7", 3), "7 2 3");
        assert_eq!(partial("1 2 3", "7 8 9", 3), "7 8 9");
        assert_eq!(partial("1", "7 8", 3), "7 8");
    }

    #[test]
    fn an_alternative_of_the_element_replaces_the_class_alternative() {
        let base = Attrs(vec![("euler".into(), "0 0 90".into())]);
        let over = [("zaxis".to_string(), "1 0 0".to_string())];
        let a = Attrs::overlay(&base, &over);
        assert_eq!((a.get("euler"), a.get("zaxis")), (None, Some("1 0 0")));
        let quat = [("quat".to_string(), "1 0 0 0".to_string())];
        let b = Attrs::overlay(&base, &quat);
        assert_eq!(
            (b.get("euler"), b.get("quat")),
            (Some("0 0 90"), Some("1 0 0 0"))
        );
    }
}
