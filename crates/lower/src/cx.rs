//! The state shared while lowering a project: the model, the layout, the
//! image allocator, globals, static frames, sites and diagnostics.

use crate::layout::{align_up, Layout};
use automat_base::{Diagnostic, Interner, SourceMap, Symbol};
use automat_ir::Site;
use automat_sema::types::TypeId;
use automat_sema::Model;
use automat_syntax::ast::SourceUnit;
use rustc_hash::FxHashMap;

pub struct Cx<'a> {
    pub model: &'a Model,
    pub interner: &'a Interner,
    pub units: &'a [SourceUnit],
    pub sources: &'a SourceMap,
    pub layout: Layout<'a>,
    /// Global variables: absolute offset, bit, type.
    pub globals: FxHashMap<Symbol, (u32, Option<u8>, TypeId)>,
    /// Per POU (index = PouId): the static frame of a function.
    pub frames: Vec<Option<u32>>,
    /// Per POU: a pristine copy of its frame or instance, never written by
    /// code, copied from to re-initialise temporaries and locals.
    pub templates: Vec<Option<u32>>,
    /// Constant bytes to place in the initial image (string literals).
    pub consts: Vec<(u32, Vec<u8>)>,
    /// End of the allocated image.
    pub top: u32,
    pub sites: Vec<Site>,
    pub diags: Vec<Diagnostic>,
    /// Hidden EN/ENO bytes: stored where, read anywhere (`gen/lean.rs`).
    pub hidden: crate::gen::lean::Hidden,
}

impl Cx<'_> {
    /// Allocates `size` bytes aligned to `align` at the end of the image.
    pub fn alloc(&mut self, size: u32, align: u32) -> u32 {
        let at = align_up(self.top, align);
        self.top = at.saturating_add(size);
        at
    }
}
