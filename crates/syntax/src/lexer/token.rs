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
            /// The canonical (upper-case) spelling.
            pub fn text(self) -> &'static str {
                match self { $(Kw::$kw => $text),* }
            }

            /// The keyword spelled by `upper` (already upper-cased), if any.
            pub fn from_upper(upper: &[u8]) -> Option<Kw> {
                // A match on byte strings compiles to a length switch plus
                // comparisons: no allocation, no hashing.
                match upper { $($text => Some(Kw::$kw),)* _ => None }
            }
        }
    };
}

// `match` on `&[u8]` needs byte-string patterns; the macro takes `b"..."`.
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
}

impl Kw {
    /// The spelling as a `&str` (every keyword is ASCII).
    pub fn name(self) -> &'static str {
        std::str::from_utf8(self.text()).unwrap_or("?")
    }

    /// Words that are keywords only in one place (configurations, `POINTER
    /// TO`) and are common variable names elsewhere: where a name is expected
    /// they are accepted as identifiers.
    pub fn is_contextual(self) -> bool {
        matches!(
            self,
            Kw::Pointer | Kw::On | Kw::Task | Kw::With | Kw::ReadWrite | Kw::ReadOnly
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
    fn keyword_lookup_is_exact() {
        assert_eq!(Kw::from_upper(b"END_IF"), Some(Kw::EndIf));
        assert_eq!(Kw::from_upper(b"END_FUNCTION_BLOCK"), Some(Kw::EndFunctionBlock));
        assert_eq!(Kw::from_upper(b"END_I"), None);
        assert_eq!(Kw::from_upper(b"end_if"), None);
        assert_eq!(Kw::EndIf.name(), "END_IF");
    }
}
