//! The table of diagnostic codes. One row per code: the enum, `automat explain`
//! and `docs/diagnostics.md` all come from this table, so a code's meaning is
//! written once. Codes are stable: never renumber, only add.
//!
//! Ranges: E000–E019 lexing and syntax, E020–E029 names, E030–E039 types,
//! E040–E049 assignment, E050–E059 calls, E060–E069 control flow, E070–E079
//! constants, E080–E089 configuration and addresses; W0xx warnings.
//! Later stages take E1xx (SFC, IL), E2xx (runtime faults), E3xx (projects, plants).

macro_rules! codes {
    ($($code:ident => $title:literal, $explain:literal;)*) => {
        /// A stable diagnostic code.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code { $($code),* }

        impl Code {
            pub const ALL: &'static [Code] = &[$(Code::$code),*];

            /// `"E030"`.
            pub fn as_str(self) -> &'static str {
                match self { $(Code::$code => stringify!($code)),* }
            }

            /// One line: what the code is about.
            pub fn title(self) -> &'static str {
                match self { $(Code::$code => $title),* }
            }

            /// A paragraph for `automat explain`.
            pub fn explain(self) -> &'static str {
                match self { $(Code::$code => $explain),* }
            }

            pub fn parse(s: &str) -> Option<Code> {
                Code::ALL.iter().copied().find(|c| c.as_str().eq_ignore_ascii_case(s))
            }
        }
    };
}

codes! {
    // ---- lexing and syntax ----
    E001 => "invalid character",
        "The source contains a character that cannot start any token of Structured Text.";
    E002 => "unterminated comment",
        "A `(*` comment (comments nest) or a `/*` comment is not closed before the end of the file.";
    E003 => "unterminated string literal",
        "A string literal is not closed on its line, or uses an unknown `$` escape.";
    E004 => "malformed literal",
        "A numeric, time, date or time-of-day literal does not follow IEC 61131-3 syntax (for example `16#G0`, `T#5x`, `D#2024-13-01`).";
    E005 => "syntax error",
        "The parser expected one thing and found another. The parser skips to the next statement or declaration and goes on, so later errors are still reported.";
    E006 => "literal out of range",
        "An integer literal does not fit in 64 bits, or a typed literal does not fit its type (for example `SINT#300`).";
    E007 => "invalid direct address",
        "A located variable's address is not of the form `%` I|Q|M, an optional size X|B|W|D|L, then numbers separated by dots (or `*` for a partly specified address).";

    // ---- names ----
    E020 => "unknown name",
        "A variable, constant or enumeration value is used that is not declared in the POU, as a global visible through VAR_EXTERNAL, or as an enumeration value.";
    E021 => "unknown type",
        "A declaration names a type that is neither elementary, a derived type from a TYPE block, nor a function block.";
    E022 => "unknown POU",
        "A call or a program instance names a function, function block or program that does not exist.";
    E023 => "duplicate declaration",
        "A name is declared twice in the same scope: two variables of one POU, two POUs or types of one project, two members of a structure, two values of one enumeration.";
    E024 => "unknown member",
        "`a.b` names a member that the structure, function block or program instance `a` does not have, or a member that is not visible from outside (only inputs and outputs of a function block are).";
    E025 => "VAR_EXTERNAL without a global",
        "A VAR_EXTERNAL declaration needs a VAR_GLOBAL of the same name and type in the configuration, resource or project.";
    E026 => "name is not a variable",
        "A type, POU or other non-variable name is used where a value is expected.";
    E027 => "recursive type",
        "A type is defined in terms of itself: a structure that contains itself (directly or through arrays and other structures) or a cycle of type aliases. A structure may point to its own type through `REF_TO`.";

    // ---- types ----
    E030 => "type mismatch",
        "A value of one type is used where another type is required and IEC 61131-3 allows no implicit conversion between them. Only widening conversions are implicit (SINT→INT→DINT→LINT, USINT→UINT→UDINT→ULINT, unsigned to a wider signed type, integers to REAL/LREAL where exact, REAL→LREAL, BYTE→WORD→DWORD→LWORD). Use an explicit conversion function such as `DINT_TO_INT`.";
    E031 => "operator not defined for these types",
        "An operator is applied to operands it is not defined for (for example `TRUE + 1`, `NOT 1.5`, `'a' * 2`).";
    E032 => "condition is not BOOL",
        "IF, ELSIF, WHILE and UNTIL conditions must be of type BOOL.";
    E033 => "CASE label does not match the selector",
        "A CASE label must be a constant of the selector's type: integer constants or ranges for an integer selector, values of the enumeration for an enumerated selector.";
    E034 => "wrong number of array indexes",
        "An array is indexed with a different number of subscripts than it has dimensions.";
    E035 => "constant index out of range",
        "An array subscript that is a constant lies outside the declared bounds.";
    E036 => "not indexable",
        "Subscripts `[...]` are applied to a value that is not an array, or `.` member access to a value that has no members.";
    E037 => "invalid bit access",
        "A bit access `v.n` or `v.%Xn` needs an ANY_BIT or integer variable and a bit number below its width.";
    E038 => "value out of subrange",
        "A constant assigned to a subrange variable (or its initial value) lies outside the subrange.";
    E039 => "invalid initial value",
        "An initial value does not fit the declared type: wrong type, too many array elements, unknown structure member.";

    // ---- assignment ----
    E040 => "assignment to a constant",
        "A variable declared in a CONSTANT section cannot be assigned.";
    E041 => "assignment to an input",
        "A VAR_INPUT is read-only inside its own POU.";
    E042 => "not assignable",
        "The left side of `:=` (or an output binding `=>`, or a VAR_IN_OUT argument) must be a variable, not an expression or a literal.";

    // ---- calls ----
    E050 => "wrong number of arguments",
        "A call passes more or fewer arguments than the function declares.";
    E051 => "unknown parameter",
        "A formal argument `name := value` names a parameter the function or function block does not have.";
    E052 => "argument type mismatch",
        "An argument's type does not match the parameter's and cannot be converted implicitly.";
    E053 => "function block used as a function",
        "A function block type is called like a function. Declare an instance (`t1 : TON;`) and call the instance (`t1(IN := x, PT := T#1s);`).";
    E054 => "not callable",
        "A call is applied to something that is neither a function nor a function block instance (for example a function called through an instance, or a variable of elementary type).";
    E055 => "mixed formal and non-formal arguments",
        "A call uses both `name := value` and positional arguments; function block calls must be formal.";
    E056 => "duplicate argument",
        "The same parameter is given twice in one call.";
    E057 => "missing VAR_IN_OUT argument",
        "Every VAR_IN_OUT parameter must be bound to a variable in each call.";

    // ---- control flow ----
    E060 => "EXIT outside a loop",
        "EXIT leaves the innermost FOR, WHILE or REPEAT loop, so it must appear inside one.";
    E061 => "CONTINUE outside a loop",
        "CONTINUE jumps to the next iteration of the innermost loop, so it must appear inside one.";
    E062 => "invalid FOR loop",
        "The control variable of a FOR loop must be a local integer variable; its start, end and step must have compatible integer types; a constant step must not be zero.";
    E063 => "statement has no effect",
        "An expression used as a statement must be a call.";

    // ---- constants ----
    E070 => "not a constant expression",
        "Array bounds, string lengths, subrange limits, CASE labels and enumeration values must be computable at compile time from literals and CONSTANT variables.";
    E071 => "division by zero in a constant expression",
        "A constant expression divides by zero.";
    E072 => "invalid range",
        "The lower bound of an array dimension or a subrange is greater than its upper bound, or a string length is not positive.";
    E073 => "constant overflow",
        "A constant expression overflows the range of its type.";

    // ---- configuration and addresses ----
    E080 => "unknown task",
        "A program instance is attached WITH a task that the resource does not declare.";
    E081 => "invalid task property",
        "A TASK accepts INTERVAL (TIME), PRIORITY (integer) and SINGLE (BOOL), each once.";
    E082 => "not a PROGRAM",
        "Only PROGRAM types can be instantiated in a resource.";
    E083 => "unknown access path",
        "A VAR_ACCESS or VAR_CONFIG path does not name an existing variable.";
    E084 => "invalid location",
        "A located variable's address size does not fit its type (`%IX` needs BOOL, `%IW` a 16-bit type, ...), or a partly specified address `%I*` is used outside a program, function block or VAR_CONFIG.";

    // ---- lowering (code generation) ----
    E090 => "no program to run",
        "Without a CONFIGURATION the project must declare exactly one PROGRAM, or name the one to run with `--program`; the name given must be a PROGRAM of the project.";
    E091 => "not supported by code generation",
        "The construct is valid IEC 61131-3 but automat cannot execute it yet (the message names it).";
    E092 => "recursive call",
        "IEC 61131-3 forbids recursion: a function or function block calls itself, directly or through others. Every POU has one static frame.";

    // ---- warnings ----
    W001 => "unused variable",
        "A local variable is declared but never read or written.";
    W002 => "unreachable code",
        "A statement follows RETURN, EXIT or CONTINUE in the same block and can never run.";
    W003 => "implicit narrowing in a constant",
        "A constant is converted to a smaller type; the value fits, so the program is accepted.";
}

/// The code table as Markdown: the content of `docs/diagnostics.md`
/// (a test keeps that file equal to this).
pub fn markdown() -> String {
    let mut s = String::from(
        "# Diagnostic codes\n\nGenerated by `automat explain --list` from `crates/base/src/codes.rs`; do not edit by hand.\n\n| Code | Title | Explanation |\n|---|---|---|\n",
    );
    for c in Code::ALL {
        s.push_str(&format!(
            "| {} | {} | {} |\n",
            c.as_str(),
            c.title(),
            c.explain()
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_are_unique_and_parse_back() {
        for c in Code::ALL {
            assert_eq!(Code::parse(c.as_str()), Some(*c));
            assert!(!c.title().is_empty() && !c.explain().is_empty());
        }
        assert_eq!(Code::parse("e030"), Some(Code::E030));
        assert_eq!(Code::parse("E999"), None);
    }
}
