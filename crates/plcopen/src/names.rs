//! Names from attributes and element text, checked before they are written
//! into the generated Structured Text.

use crate::xml::{self, Text};
use crate::Imp;
use automat_base::Code;
use roxmltree::Node;

pub use automat_syntax::graphic::is_identifier;

impl Imp<'_> {
    /// The identifier in attribute `attr` of `n`, or an error naming `what`.
    pub fn name_attr(&mut self, n: Node, attr: &str, what: &str) -> Option<Text> {
        let Some(t) = xml::attr(self.src, n, attr) else {
            let sp = self.span(n);
            self.error(
                Code::E171,
                sp,
                format!(
                    "`{}` without the `{attr}` attribute ({what})",
                    n.tag_name().name()
                ),
            );
            return None;
        };
        let t = t.trimmed();
        if !is_identifier(&t.text) {
            let sp = t.span(self.file);
            self.error(
                Code::E177,
                sp,
                format!("{what} `{}` is not an identifier", t.text),
            );
            return None;
        }
        Some(t)
    }
}
