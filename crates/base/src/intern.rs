//! Case-insensitive identifier interning.
//!
//! IEC 61131-3 names are case-insensitive: `Motor`, `MOTOR` and `motor` are one
//! name. The interner folds ASCII case once, so later stages compare names as
//! `u32`s. The first spelling seen is kept for messages.

use rustc_hash::FxHashMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Symbol(pub u32);

#[derive(Default)]
pub struct Interner {
    map: FxHashMap<Box<str>, Symbol>,
    spellings: Vec<Box<str>>,
    scratch: String,
}

impl Interner {
    pub fn new() -> Interner {
        Interner::default()
    }

    pub fn intern(&mut self, name: &str) -> Symbol {
        self.scratch.clear();
        self.scratch.push_str(name);
        self.scratch.make_ascii_uppercase();
        if let Some(&sym) = self.map.get(self.scratch.as_str()) {
            return sym;
        }
        let sym = Symbol(self.spellings.len() as u32);
        self.map.insert(self.scratch.clone().into_boxed_str(), sym);
        self.spellings.push(name.into());
        sym
    }

    /// The symbol of a name if it was ever interned.
    pub fn lookup(&self, name: &str) -> Option<Symbol> {
        self.map.get(name.to_ascii_uppercase().as_str()).copied()
    }

    /// The first spelling seen of this name.
    pub fn name(&self, sym: Symbol) -> &str {
        self.spellings
            .get(sym.0 as usize)
            .map(|s| &**s)
            .unwrap_or("<?>")
    }

    pub fn len(&self) -> usize {
        self.spellings.len()
    }

    pub fn is_empty(&self) -> bool {
        self.spellings.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn folds_case_and_keeps_first_spelling() {
        let mut i = Interner::new();
        let a = i.intern("Motor");
        assert_eq!(i.intern("MOTOR"), a);
        assert_eq!(i.intern("motor"), a);
        assert_ne!(i.intern("Motor1"), a);
        assert_eq!(i.name(a), "Motor");
        assert_eq!(i.lookup("mOtOr"), Some(a));
    }
}
