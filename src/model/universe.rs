//! The finite domain: PDDL types with their inheritance, and the objects of each type.
//!
//! Objects come from the PDDL domain's `:constants` (`table`, `none`, `open`, ...) and from
//! the manifest's `[objects]` (`cup = ["cup1", "cup2"]`). Each has one type; an object of a
//! type is also an object of every ancestor type. Ids are dense and ordered (constants
//! first, in declaration order, then manifest objects), so everything built on them —
//! ground atoms, states, counterexamples — comes out in the same order on every run.

use crate::syntax::manifest::Manifest;
use crate::syntax::pddl::Domain;
use crate::syntax::{Diagnostic, Span};
use std::collections::HashMap;
use std::sync::Arc;

/// A type's index in the [`Universe`]; `TypeId::OBJECT` is PDDL's root type `object`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TypeId(pub u16);

impl TypeId {
    /// PDDL's root type `object`.
    pub const OBJECT: TypeId = TypeId(0);
}

/// An object's index in the [`Universe`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ObjectId(pub u16);

/// Where an object was declared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// A PDDL `:constants` entry.
    Constant(Span),
    /// A manifest `[objects]` entry.
    Manifest(Span),
}

impl Origin {
    /// The declaration's span.
    pub fn span(self) -> Span {
        match self {
            Origin::Constant(s) | Origin::Manifest(s) => s,
        }
    }
}

#[derive(Clone, Debug)]
struct TypeInfo {
    name: Arc<str>,
    parent: Option<TypeId>,
    /// Every object of this type or a subtype, by id.
    objects: Vec<ObjectId>,
}

#[derive(Clone, Debug)]
struct ObjectInfo {
    name: Arc<str>,
    ty: TypeId,
    origin: Origin,
}

/// Types and objects of one project.
#[derive(Clone, Debug)]
pub struct Universe {
    types: Vec<TypeInfo>,
    objects: Vec<ObjectInfo>,
    type_ids: HashMap<Arc<str>, TypeId>,
    object_ids: HashMap<Arc<str>, ObjectId>,
    /// The type `number` of `[bounds] numbers`, whose objects are integers.
    number_type: Option<TypeId>,
}

/// The name of the type of `[bounds] numbers`.
pub const NUMBER_TYPE: &str = "number";

impl Universe {
    /// Builds the domain from the PDDL types and constants and the manifest's objects.
    /// Errors (located in the manifest): an unknown type, an object declared twice or that
    /// is also a PDDL constant, more objects than ids.
    pub fn build(domain: &Domain, manifest: &Manifest) -> Result<Universe, Vec<Diagnostic>> {
        let mut errors = Vec::new();
        let mut u = Universe {
            types: vec![TypeInfo {
                name: "object".into(),
                parent: None,
                objects: Vec::new(),
            }],
            objects: Vec::new(),
            type_ids: HashMap::new(),
            object_ids: HashMap::new(),
            number_type: None,
        };
        u.type_ids.insert("object".into(), TypeId::OBJECT);
        for t in &domain.types {
            if !u.type_ids.contains_key(t.name.as_str()) {
                let id = TypeId(u.types.len() as u16);
                u.types.push(TypeInfo {
                    name: t.name.as_str().into(),
                    parent: None,
                    objects: Vec::new(),
                });
                u.type_ids.insert(t.name.as_str().into(), id);
            }
        }
        // Parents after all names are known: types may be declared in any order. The PDDL
        // front end has already refused cycles and undeclared parents.
        for t in &domain.types {
            let id = u.type_ids[t.name.as_str()];
            if id != TypeId::OBJECT {
                u.types[id.0 as usize].parent = Some(
                    u.type_ids
                        .get(t.parent.as_str())
                        .copied()
                        .unwrap_or(TypeId::OBJECT),
                );
            }
        }
        for c in &domain.constants {
            let ty = u
                .type_ids
                .get(c.ty.as_str())
                .copied()
                .unwrap_or(TypeId::OBJECT);
            u.add_object(&c.name, ty, Origin::Constant(c.span), &mut errors);
        }
        for group in &manifest.objects {
            let Some(&ty) = u.type_ids.get(group.name.value.as_str()) else {
                let known: Vec<&str> = u.types.iter().map(|t| &*t.name).collect();
                errors.push(
                    Diagnostic::error(
                        "input",
                        format!("`{}` is not a type of the PDDL domain", group.name.value),
                    )
                    .with_label(group.name.span, "unknown type")
                    .with_help(format!("the domain's types are: {}", known.join(", "))),
                );
                continue;
            };
            for o in &group.objects {
                u.add_object(&o.value, ty, Origin::Manifest(o.span), &mut errors);
            }
        }
        if let Some(n) = &manifest.bounds.numbers {
            // Integers as objects of their own type, so mental notes can hold counters.
            let ty = match u.type_ids.get(NUMBER_TYPE) {
                Some(&t) => t,
                None => {
                    let id = TypeId(u.types.len() as u16);
                    u.types.push(TypeInfo {
                        name: NUMBER_TYPE.into(),
                        parent: Some(TypeId::OBJECT),
                        objects: Vec::new(),
                    });
                    u.type_ids.insert(NUMBER_TYPE.into(), id);
                    id
                }
            };
            u.number_type = Some(ty);
            let (lo, hi) = n.value;
            for i in lo..=hi {
                u.add_object(&i.to_string(), ty, Origin::Manifest(n.span), &mut errors);
            }
        }
        for (i, o) in u.objects.iter().enumerate() {
            let mut t = Some(o.ty);
            while let Some(ty) = t {
                u.types[ty.0 as usize].objects.push(ObjectId(i as u16));
                t = u.types[ty.0 as usize].parent;
            }
        }
        if errors.is_empty() {
            Ok(u)
        } else {
            Err(errors)
        }
    }

    fn add_object(&mut self, name: &str, ty: TypeId, origin: Origin, errors: &mut Vec<Diagnostic>) {
        if let Some(&prev) = self.object_ids.get(name) {
            let what = match self.objects[prev.0 as usize].origin {
                Origin::Constant(_) => "a constant of the PDDL domain",
                Origin::Manifest(_) => "an object already",
            };
            errors.push(
                Diagnostic::error("input", format!("`{name}` is {what}"))
                    .with_label(origin.span(), "declared again here")
                    .with_secondary(
                        self.objects[prev.0 as usize].origin.span(),
                        "first declared here",
                    ),
            );
            return;
        }
        if self.objects.len() >= u16::MAX as usize {
            errors.push(
                Diagnostic::error("input", "more than 65535 objects")
                    .with_label(origin.span(), "here"),
            );
            return;
        }
        let id = ObjectId(self.objects.len() as u16);
        let name: Arc<str> = name.into();
        self.object_ids.insert(name.clone(), id);
        self.objects.push(ObjectInfo { name, ty, origin });
    }

    /// The type with this name.
    pub fn type_id(&self, name: &str) -> Option<TypeId> {
        self.type_ids.get(name).copied()
    }

    /// A type's name.
    pub fn type_name(&self, t: TypeId) -> &str {
        &self.types[t.0 as usize].name
    }

    /// Number of types, `object` included.
    pub fn type_count(&self) -> usize {
        self.types.len()
    }

    /// Whether `a` is `b` or a descendant of `b`.
    pub fn is_subtype(&self, a: TypeId, b: TypeId) -> bool {
        let mut t = Some(a);
        while let Some(ty) = t {
            if ty == b {
                return true;
            }
            t = self.types[ty.0 as usize].parent;
        }
        false
    }

    /// The more specific of two related types, or `None` when neither is a subtype of the
    /// other (no object can have both).
    pub fn meet(&self, a: TypeId, b: TypeId) -> Option<TypeId> {
        if self.is_subtype(a, b) {
            Some(a)
        } else if self.is_subtype(b, a) {
            Some(b)
        } else {
            None
        }
    }

    /// Every object of a type or of its subtypes, in id order.
    pub fn objects_of(&self, t: TypeId) -> &[ObjectId] {
        &self.types[t.0 as usize].objects
    }

    /// The object with this name.
    pub fn object(&self, name: &str) -> Option<ObjectId> {
        self.object_ids.get(name).copied()
    }

    /// An object's name.
    pub fn object_name(&self, o: ObjectId) -> &str {
        &self.objects[o.0 as usize].name
    }

    /// The object a ground term stands for: an atom by its name, an integer among
    /// `[bounds] numbers`.
    pub fn object_of(&self, t: &crate::model::Term) -> Option<ObjectId> {
        match t {
            crate::model::Term::Atom(n) => self.object(n),
            crate::model::Term::Num(n) if self.number_type.is_some() => {
                let o = self.object(&n.as_i64()?.to_string())?;
                (Some(self.objects[o.0 as usize].ty) == self.number_type).then_some(o)
            }
            _ => None,
        }
    }

    /// The term an object stands for: a number for the objects of `[bounds] numbers`, else
    /// the atom of its name.
    pub fn object_term(&self, o: ObjectId) -> crate::model::Term {
        let info = &self.objects[o.0 as usize];
        if Some(info.ty) == self.number_type {
            if let Ok(i) = info.name.parse::<i64>() {
                return crate::model::Term::int(i);
            }
        }
        crate::model::Term::atom(&info.name)
    }

    /// An object's name, shared.
    pub fn object_name_arc(&self, o: ObjectId) -> Arc<str> {
        self.objects[o.0 as usize].name.clone()
    }

    /// An object's own (most specific) type.
    pub fn object_type(&self, o: ObjectId) -> TypeId {
        self.objects[o.0 as usize].ty
    }

    /// Where an object was declared.
    pub fn object_origin(&self, o: ObjectId) -> Origin {
        self.objects[o.0 as usize].origin
    }

    /// Every object, in id order.
    pub fn objects(&self) -> impl Iterator<Item = ObjectId> {
        (0..self.objects.len() as u16).map(ObjectId)
    }

    /// Number of objects.
    pub fn object_count(&self) -> usize {
        self.objects.len()
    }
}
