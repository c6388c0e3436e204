//! The PLC's symbol tree (`automat_session::symbols`) as an OPC UA address
//! space under Objects: a folder per program instance and one, `Globals`,
//! for the global variables; FB instances and structs as objects;
//! elementary variables as variables; an array of elementary values as one
//! variable holding the array (its elements listed by the symbol tree, at
//! most 256). NodeIds are `ns=1;s=<path as declared>` (`ns=1;s=Main.tank.level`).

use crate::values;
use automat_runtime::{Place, PlaceType};
use automat_session::{Node, Session};
use opcua::nodes::{AccessLevel, ObjectBuilder, VariableBuilder};
use opcua::server::address_space::AddressSpace;
use opcua::types::{DataTypeId, NodeId, ObjectId, ObjectTypeId, Variant, VariantScalarTypeId};

/// What a variable node reads from the image.
#[derive(Clone, Debug)]
pub enum Source {
    One(Place),
    /// An array: each element's path and place, in order.
    Array(Vec<(String, Place)>, VariantScalarTypeId),
}

/// A variable node of the PLC.
#[derive(Clone, Debug)]
pub struct Var {
    pub id: NodeId,
    pub path: String,
    pub source: Source,
    pub writable: bool,
}

impl Var {
    /// The node's value in `image`.
    pub fn value(&self, image: &[u8]) -> Variant {
        match &self.source {
            Source::One(p) => values::read(image, p),
            Source::Array(items, ty) => {
                let v: Vec<Variant> = items.iter().map(|(_, p)| values::read(image, p)).collect();
                Variant::from((*ty, v))
            }
        }
    }
}

fn scalar_type(dt: DataTypeId) -> VariantScalarTypeId {
    match dt {
        DataTypeId::Boolean => VariantScalarTypeId::Boolean,
        DataTypeId::SByte => VariantScalarTypeId::SByte,
        DataTypeId::Byte => VariantScalarTypeId::Byte,
        DataTypeId::Int16 => VariantScalarTypeId::Int16,
        DataTypeId::UInt16 => VariantScalarTypeId::UInt16,
        DataTypeId::Int32 => VariantScalarTypeId::Int32,
        DataTypeId::UInt32 => VariantScalarTypeId::UInt32,
        DataTypeId::Int64 => VariantScalarTypeId::Int64,
        DataTypeId::UInt64 => VariantScalarTypeId::UInt64,
        DataTypeId::Float => VariantScalarTypeId::Float,
        DataTypeId::Double | DataTypeId::Duration => VariantScalarTypeId::Double,
        _ => VariantScalarTypeId::String,
    }
}

pub struct Builder<'a> {
    pub ns: u16,
    pub session: &'a Session,
    pub space: &'a mut AddressSpace,
    pub vars: Vec<Var>,
    pub image: &'a [u8],
}

impl Builder<'_> {
    fn id(&self, path: &str) -> NodeId {
        NodeId::new(self.ns, path.to_string())
    }

    /// Every root of the tree under Objects.
    pub fn roots(&mut self, roots: &[Node]) {
        let objects: NodeId = ObjectId::ObjectsFolder.into();
        let globals: Vec<&Node> = roots.iter().filter(|n| n.ty != "PROGRAM").collect();
        for r in roots.iter().filter(|n| n.ty == "PROGRAM") {
            let id = self.id(&r.path);
            ObjectBuilder::new(&id, r.name.as_str(), r.name.as_str())
                .is_folder()
                .organized_by(objects.clone())
                .insert(self.space);
            for c in &r.children {
                self.node(c, &id, true);
            }
        }
        if !globals.is_empty() {
            let id = self.id("Globals");
            ObjectBuilder::new(&id, "Globals", "Globals")
                .is_folder()
                .organized_by(objects.clone())
                .insert(self.space);
            for g in globals {
                self.node(g, &id, true);
            }
        }
    }

    /// `node` below `parent` (a folder organises, an object has components).
    fn node(&mut self, node: &Node, parent: &NodeId, in_folder: bool) {
        let id = self.id(&node.path);
        if let Some(source) = self.array(node) {
            return self.variable(node, id, parent, in_folder, source);
        }
        if node.children.is_empty() && !node.ty.starts_with("ARRAY") {
            if let Ok(place) = self.session.place(&node.path) {
                return self.variable(node, id, parent, in_folder, Source::One(place));
            }
            return;
        }
        let b = ObjectBuilder::new(&id, node.name.as_str(), node.name.as_str())
            .has_type_definition(ObjectTypeId::BaseObjectType);
        let b = if in_folder {
            b.organized_by(parent.clone())
        } else {
            b.component_of(parent.clone())
        };
        b.insert(self.space);
        for c in &node.children {
            self.node(c, &id, false);
        }
    }

    /// An array whose listed elements are all elementary, of one type.
    fn array(&self, node: &Node) -> Option<Source> {
        if !node.ty.starts_with("ARRAY") || node.children.is_empty() {
            return None;
        }
        let mut items = Vec::new();
        let mut ty: Option<PlaceType> = None;
        for c in &node.children {
            if !c.children.is_empty() {
                return None;
            }
            let p = self.session.place(&c.path).ok()?;
            match &ty {
                None => ty = Some(p.ty.clone()),
                Some(t) if *t != p.ty => return None,
                Some(_) => {}
            }
            items.push((c.path.clone(), p));
        }
        let dt = values::data_type(ty.as_ref()?);
        Some(Source::Array(items, scalar_type(dt)))
    }

    fn variable(
        &mut self,
        node: &Node,
        id: NodeId,
        parent: &NodeId,
        in_folder: bool,
        source: Source,
    ) {
        let (dt, rank, dims) = match &source {
            Source::One(p) => (values::data_type(&p.ty), -1, None),
            Source::Array(items, _) => (
                values::data_type(&items[0].1.ty),
                1,
                Some([items.len() as u32]),
            ),
        };
        let writable = node.writable
            || matches!(&source, Source::Array(..)) && node.children.iter().all(|c| c.writable);
        let access = if writable {
            AccessLevel::CURRENT_READ | AccessLevel::CURRENT_WRITE
        } else {
            AccessLevel::CURRENT_READ
        };
        let var = Var {
            id: id.clone(),
            path: node.path.clone(),
            source,
            writable,
        };
        let mut b = VariableBuilder::new(&id, node.name.as_str(), node.name.as_str())
            .data_type(dt)
            .value_rank(rank)
            .access_level(access)
            .user_access_level(access)
            .value(var.value(self.image));
        if let Some(d) = &dims {
            b = b.array_dimensions(d);
        }
        let b = if in_folder {
            b.organized_by(parent.clone())
        } else {
            b.component_of(parent.clone())
        };
        b.insert(self.space);
        self.vars.push(var);
    }
}
