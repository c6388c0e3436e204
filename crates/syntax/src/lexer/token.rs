//! Tokens: small `Copy` values with a byte range. Identifiers carry their
//! interned symbol; literals carry an index into the lexer's literal table so
//! that decoded strings are not copied around with every token.

use automat_base::Symbol;

/// One token: what it is and where it is (`start..end` in bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token {
    pub tok: Tok,
    pub start: u32,
    pub end: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tok {
    Ident(Symbol),
    Kw(Kw),
    /// A well-formed literal: index into the literal table.
    Lit(u32),
    /// A malformed literal; its diagnostic was already reported.
    BadLit,
    /// `%IX0.1`, `%QW*`, `%X3`: decoded by the parser, which knows whether
    /// a located address or a partial access is meant.
    Addr,
    ColonEq,
    Arrow,
    Colon,
    Semi,
    Comma,
    Dot,
    DotDot,
    LParen,
    RParen,
    LBracket,
    RBracket,
    Plus,
    Minus,
    Star,
    StarStar,
    Slash,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Amp,
    Caret,
    Eof,
}

impl Tok {
    /// The fixed spelling of a punctuation token, for messages.
    pub fn punct_text(self) -> Option<&'static str> {
        Some(match self {
            Tok::ColonEq => ":=",
            Tok::Arrow => "=>",
            Tok::Colon => ":",
            Tok::Semi => ";",
            Tok::Comma => ",",
            Tok::Dot => ".",
            Tok::DotDot => "..",
            Tok::LParen => "(",
            Tok::RParen => ")",
            Tok::LBracket => "[",
            Tok::RBracket => "]",
            Tok::Plus => "+",
            Tok::Minus => "-",
            Tok::Star => "*",
            Tok::StarStar => "**",
            Tok::Slash => "/",
            Tok::Eq => "=",
            Tok::Ne => "<>",
            Tok::Lt => "<",
            Tok::Le => "<=",
            Tok::Gt => ">",
            Tok::Ge => ">=",
            Tok::Amp => "&",
            Tok::Caret => "^",
            _ => return None,
        })
    }
}

macro_rules! keywords {
    ($($kw:ident => $text:literal,)*) => {
        /// Reserved words (and a few contextual ones, see [`Kw::is_contextual`]).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Kw { $($kw),* }

        impl Kw {
            const ALL: &'static [Kw] = &[$(Kw::$kw),*];
            const TEXTS: &'static [&'static [u8]] = &[$($text),*];

            /// The canonical (upper-case) spelling.
            pub fn text(self) -> &'static [u8] {
                match self { $(Kw::$kw => $text),* }
            }
        }
    };
}

/// Keyword lookup by a perfect hash: the multiplier was chosen so that no
/// two keywords share a slot (checked when the table is built, at compile
/// time). One hash over the word, one case-insensitive comparison.
const KW_HASH_MUL: u32 = 358;

/// One step of the keyword hash. Clearing bit 5 folds ASCII case (it also
/// merges a few non-letters, which only costs a comparison, never a wrong
/// answer: a lookup always compares the whole word).
#[inline]
pub(crate) const fn kw_hash_step(h: u32, c: u8) -> u32 {
    h.wrapping_mul(KW_HASH_MUL).wrapping_add((c & 0xDF) as u32)
}

const fn kw_slot(h: u32) -> usize {
    ((h ^ (h >> 7)) & 511) as usize
}

/// Slot → index + 1 into `Kw::ALL` (0 = no keyword).
const KW_TABLE: [u8; 512] = {
    let mut table = [0u8; 512];
    let mut i = 0;
    while i < Kw::TEXTS.len() {
        let w = Kw::TEXTS[i];
        let mut h = 0u32;
        let mut j = 0;
        while j < w.len() {
            h = kw_hash_step(h, w[j]);
            j += 1;
        }
        let slot = kw_slot(h);
        assert!(
            table[slot] == 0,
            "keyword hash collision: change KW_HASH_MUL"
        );
        table[slot] = (i + 1) as u8;
        i += 1;
    }
    table
};

impl Kw {
    /// The keyword spelled by `word` in any case, if any.
    #[inline]
    pub fn lookup(word: &[u8]) -> Option<Kw> {
        let h = word.iter().fold(0u32, |h, &c| kw_hash_step(h, c));
        Kw::lookup_hashed(word, h)
    }

    /// As [`Kw::lookup`], with the hash already computed by `kw_hash_step`.
    #[inline]
    pub(crate) fn lookup_hashed(word: &[u8], h: u32) -> Option<Kw> {
        let i = usize::from(KW_TABLE[kw_slot(h)]).checked_sub(1)?;
        let text = Kw::TEXTS.get(i)?;
        if text.eq_ignore_ascii_case(word) {
            Kw::ALL.get(i).copied()
        } else {
            None
        }
    }
}

keywords! {
    Program => b"PROGRAM",
    EndProgram => b"END_PROGRAM",
    Function => b"FUNCTION",
    EndFunction => b"END_FUNCTION",
    FunctionBlock => b"FUNCTION_BLOCK",
    EndFunctionBlock => b"END_FUNCTION_BLOCK",
    Type => b"TYPE",
    EndType => b"END_TYPE",
    Struct => b"STRUCT",
    EndStruct => b"END_STRUCT",
    Var => b"VAR",
    VarInput => b"VAR_INPUT",
    VarOutput => b"VAR_OUTPUT",
    VarInOut => b"VAR_IN_OUT",
    VarExternal => b"VAR_EXTERNAL",
    VarGlobal => b"VAR_GLOBAL",
    VarTemp => b"VAR_TEMP",
    VarStat => b"VAR_STAT",
    VarInst => b"VAR_INST",
    VarAccess => b"VAR_ACCESS",
    VarConfig => b"VAR_CONFIG",
    EndVar => b"END_VAR",
    Constant => b"CONSTANT",
    Retain => b"RETAIN",
    NonRetain => b"NON_RETAIN",
    At => b"AT",
    Array => b"ARRAY",
    Of => b"OF",
    String => b"STRING",
    WString => b"WSTRING",
    RefTo => b"REF_TO",
    Pointer => b"POINTER",
    To => b"TO",
    REdge => b"R_EDGE",
    FEdge => b"F_EDGE",
    If => b"IF",
    Then => b"THEN",
    Elsif => b"ELSIF",
    Else => b"ELSE",
    EndIf => b"END_IF",
    Case => b"CASE",
    EndCase => b"END_CASE",
    For => b"FOR",
    By => b"BY",
    Do => b"DO",
    EndFor => b"END_FOR",
    While => b"WHILE",
    EndWhile => b"END_WHILE",
    Repeat => b"REPEAT",
    Until => b"UNTIL",
    EndRepeat => b"END_REPEAT",
    Exit => b"EXIT",
    Continue => b"CONTINUE",
    Return => b"RETURN",
    And => b"AND",
    Or => b"OR",
    Xor => b"XOR",
    Not => b"NOT",
    Mod => b"MOD",
    True => b"TRUE",
    False => b"FALSE",
    Configuration => b"CONFIGURATION",
    EndConfiguration => b"END_CONFIGURATION",
    Resource => b"RESOURCE",
    On => b"ON",
    EndResource => b"END_RESOURCE",
    Task => b"TASK",
    With => b"WITH",
    ReadWrite => b"READ_WRITE",
    ReadOnly => b"READ_ONLY",
    InitialStep => b"INITIAL_STEP",
    Step => b"STEP",
    EndStep => b"END_STEP",
    Transition => b"TRANSITION",
    EndTransition => b"END_TRANSITION",
    Action => b"ACTION",
    EndAction => b"END_ACTION",
}

impl Kw {
    /// The spelling as a `&str` (every keyword is ASCII).
    pub fn name(self) -> &'static str {
        std::str::from_utf8(self.text()).unwrap_or("?")
    }

    /// Words that are keywords only in one place (configurations, `POINTER
    /// TO`, the SFC elements `STEP`, `TRANSITION`, `ACTION`, the edge
    /// qualifiers `R_EDGE` / `F_EDGE` after an input's type) and are common
    /// variable names elsewhere (OSCAT's `MANUAL_1` keeps a `r_edge`, as
    /// CODESYS allows): where a name is expected they are accepted as
    /// identifiers.
    pub fn is_contextual(self) -> bool {
        matches!(
            self,
            Kw::Pointer
                | Kw::On
                | Kw::Task
                | Kw::With
                | Kw::ReadWrite
                | Kw::ReadOnly
                | Kw::Step
                | Kw::Transition
                | Kw::Action
                | Kw::REdge
                | Kw::FEdge
        )
    }

    /// Keywords that end or continue an enclosing statement.
    pub fn is_stmt_closer(self) -> bool {
        matches!(
            self,
            Kw::EndIf
                | Kw::EndCase
                | Kw::EndFor
                | Kw::EndWhile
                | Kw::EndRepeat
                | Kw::Else
                | Kw::Elsif
                | Kw::Until
                | Kw::EndStep
                | Kw::EndTransition
                | Kw::EndAction
        )
    }

    /// Keywords that begin a top-level declaration.
    pub fn is_item_start(self) -> bool {
        matches!(
            self,
            Kw::Program | Kw::Function | Kw::FunctionBlock | Kw::Type | Kw::Configuration
        )
    }

    /// Keywords that end a declaration-level construct.
    pub fn is_decl_end(self) -> bool {
        matches!(
            self,
            Kw::EndProgram
                | Kw::EndFunction
                | Kw::EndFunctionBlock
                | Kw::EndVar
                | Kw::EndType
                | Kw::EndStruct
                | Kw::EndConfiguration
                | Kw::EndResource
        )
    }

    /// Keywords that open a variable section.
    pub fn is_var_block(self) -> bool {
        matches!(
            self,
            Kw::Var
                | Kw::VarInput
                | Kw::VarOutput
                | Kw::VarInOut
                | Kw::VarExternal
                | Kw::VarGlobal
                | Kw::VarTemp
                | Kw::VarStat
                | Kw::VarInst
                | Kw::VarAccess
                | Kw::VarConfig
        )
    }

    /// Keywords that begin a statement.
    pub fn starts_stmt(self) -> bool {
        matches!(
            self,
            Kw::If
                | Kw::Case
                | Kw::For
                | Kw::While
                | Kw::Repeat
                | Kw::Exit
                | Kw::Continue
                | Kw::Return
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keyword_lookup_finds_every_keyword_in_any_case() {
        for &kw in Kw::ALL {
            assert_eq!(Kw::lookup(kw.text()), Some(kw));
            assert_eq!(
                Kw::lookup(kw.name().to_ascii_lowercase().as_bytes()),
                Some(kw)
            );
        }
        assert_eq!(Kw::lookup(b"End_If"), Some(Kw::EndIf));
        assert_eq!(Kw::lookup(b"END_I"), None);
        assert_eq!(Kw::lookup(b"INT"), None);
        assert_eq!(Kw::lookup(b""), None);
        assert_eq!(Kw::lookup(b"END_IFX"), None);
        assert_eq!(Kw::EndIf.name(), "END_IF");
    }
}
