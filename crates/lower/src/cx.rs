//! The state shared while lowering a project: the model, the layout, the
//! image allocator, globals, static frames, sites and diagnostics.

use crate::layout::{align_up64, narrow, Layout};
use automat_base::{Code, Diagnostic, Interner, SourceMap, Span, Symbol};
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
    /// End of the allocated image, exact (64 bits), so the image-size
    /// limit is checked on what the program really needs.
    pub top: u64,
    pub sites: Vec<Site>,
    pub diags: Vec<Diagnostic>,
    /// Hidden EN/ENO bytes: stored where, read anywhere (`gen/lean.rs`).
    pub hidden: crate::gen::lean::Hidden,
}

impl Cx<'_> {
    /// Allocates `size` bytes aligned to `align` at the end of the image.
    pub fn alloc(&mut self, size: impl Into<u64>, align: u32) -> u32 {
        let at = align_up64(self.top, align);
        self.top = at.saturating_add(size.into());
        narrow(at)
    }

    /// The image-size limit on what is allocated so far.
    pub fn too_large(&self) -> Option<Diagnostic> {
        if self.layout.too_deep {
            return Some(Diagnostic::error(
                Code::E091,
                Span::default(),
                format!(
                    "types nest more than {} levels deep (arrays, structures and FB instances within each other)",
                    crate::layout::MAX_DEPTH
                ),
            ));
        }
        (self.top > u64::from(crate::MAX_IMAGE)).then(|| {
            Diagnostic::error(
                Code::E091,
                Span::default(),
                format!(
                    "the program needs {} bytes of memory, more than the {} bytes supported",
                    self.top,
                    crate::MAX_IMAGE
                ),
            )
        })
    }
}
