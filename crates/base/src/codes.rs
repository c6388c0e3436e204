//! The table of diagnostic codes. One row per code: the enum, `automat explain`
//! and `docs/diagnostics.md` all come from this table, so a code's meaning is
//! written once. Codes are stable: never renumber, only add.
//!
//! Ranges: E000–E019 lexing and syntax, E020–E029 names, E030–E039 types,
//! E040–E049 assignment, E050–E059 calls, E060–E069 control flow, E070–E079
//! constants, E080–E089 configuration and addresses; W0xx warnings.
//! Later stages take E1xx (SFC, IL, dialects, PLCopen), E200–E219 object orientation (methods,
//! classes, interfaces), E3xx (projects, plants).

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

    // ---- instruction list (IL) ----
    E100 => "no current result",
        "An IL instruction uses the current result (ST, S, R, AND, ADD, a conditional jump, ...) where there is none: at the start of the instruction list or of a parenthesised group, or after an unconditional JMP, RET, CAL or FB input operator. Begin with `LD`.";
    E101 => "current result undefined after a label",
        "An instruction right after a label uses the current result, so every way into the label must bring one: the line above (not after a CAL, or at the start of the list) and each jump to it (`JMPC` brings TRUE, `JMPCN` FALSE, `JMP` its own current result). Only a Boolean current result continues across a label; otherwise load a new one after the label (`LD`, `LDN`, a formal function call).";
    E102 => "missing IL operand",
        "The IL operator needs an operand on the same line (`LD x`, `JMP label`, `CAL fb`); an instruction ends at the end of its line.";
    E103 => "unexpected IL operand",
        "The IL operator takes no operand (`NOT`, `RET`), or more text follows the instruction on its line: IL has one instruction per line.";
    E104 => "unknown IL operator",
        "The word at the start of an IL instruction is neither an IL operator (LD, ST, S, R, AND, OR, XOR, NOT, ADD, SUB, MUL, DIV, MOD, GT, GE, EQ, NE, LE, LT, JMP, CAL, RET with their N and C modifiers, FB input operators S1 R1 CLK CU CD PV IN PT) nor a function name, or it carries a modifier the operator does not take (`STC`, `ADDN`, `JMPN`).";
    E105 => "duplicate label",
        "Two labels of one body have the same name: a jump could not know where to go.";
    E106 => "unknown label",
        "A jump names a label that the body does not declare.";
    E107 => "jump into a block",
        "A jump may leave nested statements but never enter them: its label must be in the same statement list as the jump or in an enclosing one.";
    E108 => "not allowed inside IL parentheses",
        "A parenthesised IL group (`AND( ... )`) computes one value: inside it only `LD`/`LDN`, the operators that combine the current result (AND, ADD, GT, ...), `NOT` and function calls are allowed; no ST, S, R, jumps, calls of function blocks, RET or labels.";
    E109 => "unbalanced IL parentheses",
        "A `)` closes no parenthesised group, or a group opened by `AND(` (or another operator) is not closed before the end of the instruction list.";
    E110 => "invalid IL operand",
        "The operand cannot be used by this operator: ST, S and R need a variable (not a literal or an expression), a jump needs a label name, CAL and the FB input operators need a function block instance.";

    // ---- sequential function charts (textual SFC) ----
    E120 => "SFC body in a function",
        "A chart (STEP, TRANSITION, ACTION) is the body of a FUNCTION. SFC keeps state between calls (active steps, step times), so only a PROGRAM or FUNCTION_BLOCK body can be a chart.";
    E121 => "unknown step",
        "A transition's FROM or TO list names a step that the chart does not declare.";
    E122 => "duplicate chart element",
        "Two steps, two actions, two transitions, or a step and an action share a name, or a step or action has the name of a variable of the POU (`s.X`, `s.T`, `a.Q` and `a.A` are read through that name).";
    E123 => "chart without an initial step",
        "Every chart needs exactly one INITIAL_STEP: the step active when the POU starts.";
    E124 => "several initial steps",
        "A chart has more than one INITIAL_STEP. Start parallel sequences with a simultaneous divergence from a single initial step instead. (The ISaGRAF and PL7 dialects allow several initial steps, as those tools do.)";
    E125 => "unknown action",
        "A step's action association names neither an ACTION of the chart nor a variable of the POU.";
    E126 => "invalid action qualifier",
        "The qualifier of an action association is not one of N, R, S, P, P1, P0, L, D, SD, DS, SL; a timed qualifier (L, D, SD, DS, SL) lacks its duration or another one has one; or P1/P0 (which only run code) is used with a BOOL variable.";
    E127 => "side effect in a transition condition",
        "A transition condition calls a function block instance, passes an output with `=>`, or calls a function with VAR_IN_OUT or VAR_OUTPUT parameters. Conditions are evaluated every cycle while the transition is enabled and must not change state.";
    E128 => "timed associations of one action active together",
        "Two timed associations (L, D, SD, DS, SL) of one action can be active at the same time (in one step, or in steps active together): the action has a single timer.";
    E129 => "SD and SL on one action",
        "An action is associated with both SD (stored and delayed) and SL (stored and limited); IEC 61131-3 forbids the combination.";
    E130 => "invalid transition priority",
        "`(PRIORITY := n)` of a transition needs a non-negative integer literal.";
    E131 => "step listed twice in a transition",
        "A step appears twice in one transition's FROM list or twice in its TO list.";

    // ---- vendor dialects (automat-dialect: --lib isagraf / pl7) ----
    E150 => "misplaced TIMER variable",
        "ISaGRAF dialect: a TIMER keeps counting between calls, so it must be a VAR, VAR_OUTPUT, VAR_GLOBAL or VAR_EXTERNAL of a PROGRAM or FUNCTION_BLOCK (or of a global variable list); not a FUNCTION variable, an input, an in-out, a VAR_TEMP, an array element or a structure member.";
    E151 => "TSTART/TSTOP without a TIMER",
        "ISaGRAF dialect: `TSTART(t);` and `TSTOP(t);` are statements whose one argument is a TIMER variable declared in (or VAR_EXTERNAL of) the same POU.";
    E152 => "unknown section",
        "ISaGRAF dialect: a `{section ...}` pragma names a section other than begin, sequential or end.";
    E153 => "section pragma not before a PROGRAM",
        "ISaGRAF dialect: a `{section ...}` pragma places the PROGRAM that follows it; nothing else (a function block, a type, a global list) may come between them.";
    E154 => "SFC program outside the sequential section",
        "ISaGRAF dialect: Begin and End programs run straight through once per cycle; charts belong to the sequential section.";
    E155 => "child control without a child program",
        "ISaGRAF dialect: GSTART, GKILL, GFREEZE, GRST and GSTATUS take the name of a PROGRAM of the project (the child chart) as their one argument.";
    E156 => "invalid child hierarchy",
        "ISaGRAF dialect: a child chart has exactly one parent, and a program cannot control itself.";
    E157 => "invalid qualifier for a child program",
        "ISaGRAF dialect: a step association naming a child program starts it (`child(N)` until the step is left, `child(S)` for good) or kills it (`child(R)`); other qualifiers do not apply.";
    E158 => "child program not written in SFC",
        "ISaGRAF dialect: only an SFC chart can be started, killed, frozen or restarted as a child: its steps are what the commands act on.";
    E159 => "PL7 step number used twice",
        "PL7 dialect: step objects `%Xi` are global, so a step number names one step of one chart.";

    // ---- PLCopen TC6 XML (automat-plcopen) ----
    E160 => "VAR_STAT or VAR_INST not allowed here",
        "CODESYS variable sections, read with the CODESYS dialect only (`--lib codesys`): `VAR_STAT` (variables that keep their values between calls, one copy shared by every call and every instance) in a FUNCTION, FUNCTION_BLOCK, PROGRAM or METHOD; `VAR_INST` (variables of a METHOD kept in its function block's instance) only in a METHOD.";
    E161 => "ACTION not supported here",
        "CODESYS dialect: a V2.3 text export writes a POU's actions after it (`ACTION name: ... END_ACTION`). automat reads those of a FUNCTION_BLOCK as methods without parameters (`name();` in its body, `inst.name();` outside), those of a PROGRAM or FUNCTION in place of their calls `name();` in its body, and those of a PROGRAM also from other POUs as `Program.name();`; such an action cannot RETURN (it would leave the whole POU: use IF). An action before any POU, or outside the CODESYS dialect, is this error too.";
    E162 => "misused __NEW or __DELETE",
        "CODESYS dialect: `__NEW(T)` and `__NEW(T, n)` take a type (and a count) and return a `POINTER TO T` into the heap, 0 when it is full; `__DELETE(p)` is a statement of its own that frees what `p` points to and sets `p` to 0.";
    E163 => "misused __ISVALIDREF",
        "CODESYS dialect: `__ISVALIDREF(r)` takes one variable declared `REFERENCE TO T` (a variable, member or element) and tells whether it is bound (`r REF= x;`). A pointer or `REF_TO` is tested with `p <> 0` or `p <> NULL` instead; without `--lib codesys` there are no references and no `__ISVALIDREF`.";
    E164 => "program parameter reached from other POUs connected in a configuration",
        "CODESYS dialect: a PROGRAM variable another POU names (`Main.count`) or an action called from another POU uses (`Main.Reset();`) is one hidden global `Main.count`, shared by every POU that names it; a configuration's `PROGRAM inst WITH t : Main(count := g);` cannot connect it as the instance's parameter. Give it its value in a POU (`Main.count := g;`), or connect an input no other POU names (those stay the instance's own).";
    E170 => "malformed PLCopen XML",
        "A `.xml` source is not well-formed XML, or its root element is not a PLCopen TC6 `project` (schema 2.01 or 2.0). The message gives the XML parser's reason; the location is where it stopped.";
    E171 => "unsupported PLCopen element",
        "An element of the PLCopen file is not one the importer reads (the supported subset is in `docs/plcopen.md`), or lacks an attribute it needs (a `pou` without `name` or `pouType`, a `variable` without `type`). `addData` is always ignored.";
    E172 => "reference to a missing localId",
        "A `connection refLocalId` of an LD or FBD body names no element of that body, a `continuation` names no `connector`, or two elements share one `localId`.";
    E173 => "unconnected input",
        "An input of an LD or FBD element (a block input, an output variable, a jump, a return, a connector) has no connection, so it has no value. Connect it or remove the element.";
    E174 => "cycle without a feedback variable",
        "The connections of an LD or FBD body form a loop. A value can only flow back through an explicit variable: write it with an output variable and read it with an input variable (the read then sees the previous write).";
    E175 => "coil or contact without a left connection",
        "An LD contact or coil has nothing on its left: no connection to the left power rail or to another element, so it carries no power flow.";
    E176 => "vendor function block",
        "A block names a function block of one vendor's tool (Beremiz `python_eval`, `python_poll`, `python_gear`, SVGHMI blocks, ...), not an IEC 61131-3 or user block; automat does not have it.";
    E177 => "invalid name in PLCopen XML",
        "A `name`, `typeName`, `instanceName`, `label` or a variable of a contact or coil is not an IEC 61131-3 identifier (letters, digits and underscores, not starting with a digit).";
    E178 => "not expressible in PLCopen XML",
        "`automat export` met a construct TC6 XML has no place for: a VAR_GLOBAL outside a CONFIGURATION, VAR_ACCESS or VAR_CONFIG, connections of a program instance, an `ARRAY [*]`, an R_EDGE/F_EDGE input, a vendor dialect, a class, interface or NAMESPACE (and a POU's USING). Move it into a form the format has (globals into a configuration) or leave the project in ST.";
    E179 => "macro-step body without one exit step",
        "A PLCopen `macroStep` is left when its body's exit step is active, and TC6 2.01 does not mark that step: automat takes the one step of the body that no transition of the body leaves. A body where every step is left by a transition, or where several are left by none, has no exit step: end the body with one step without an outgoing transition.";
    E180 => "invalid operand",
        "Festo FST dialect: the operand cannot be written by this instruction: inputs (`In.m`, `IWn`) are read-only (FST's \"invalid operand, I0.0\"), SET/RESET/SHIFT take a bit operand, INC/DEC a word, and a LOAD's destinations must have the type of what it loaded.";
    E181 => "SET or RESET missing",
        "Festo FST dialect: a THEN or OTHRW part names a bit operand without an instruction; write `SET x` or `RESET x`.";
    E182 => "unknown symbol",
        "Festo FST dialect: a word is neither an operand (`I0.1`, `TP3`, ...) nor a symbol of the allocation list `allocation.txt`.";
    E183 => "operand out of range",
        "Festo FST dialect: an operand's number or bit, a constant or a module number is outside its range (I/O words 0-31, bits 0-15, flags, timers, counters, registers and function units 0-255, programs 0-63, modules 0-99, constants -32768 to 65535).";
    E184 => "invalid allocation list entry",
        "Festo FST dialect: an `allocation.txt` line is `OPERAND SYMBOL [comment]`; a symbol has at most 9 letters, digits or `_`, does not start with a digit, is not a keyword, not spelled like an operand, and is defined once.";
    E185 => "IF in an executive program",
        "Festo FST dialect: an executive program (one that does not start with STEP, IF or THEN) is a plain list of instructions, all executed; it has no IF.";
    E186 => "STL syntax error",
        "Festo FST dialect: the statement list does not follow FST's form: steps begin with `STEP name`, sentences with `IF condition THEN ...` (only the first sentence of a step or program may be incomplete, `THEN ...`), LOAD needs TO, JMP TO names a step of the program.";
    E187 => "PSE not usable on the FEC",
        "Festo FST dialect: PSE (program section end) is not available on the FEC controller; end a step with its last sentence or JMP TO.";
    E188 => "invalid STL program or module",
        "Festo FST dialect: an STL file is named P<n>.stl (n = 0-63) or B<n>.stl (n = 0-99) and a number is used once; P0 must exist; SET/RESET Pn and CMP n need that program or module; a module has no steps and does not call itself; CFM manufacturer modules are not available.";
    E189 => "bit and word mixed",
        "Festo FST dialect: an operation mixes a single-bit operand with a word, a condition is a word (compare it: `(CW1 = V5)`), N is applied to a word (use INV), or an accumulator operation (SHL, INV, ...) follows a bit.";
    E190 => "function block instance declared CONSTANT",
        "A function block instance (or an array of them) cannot be declared in a CONSTANT block (VAR CONSTANT, VAR_GLOBAL CONSTANT, VAR_EXTERNAL CONSTANT, VAR_INPUT CONSTANT): calling it changes its state. Declare it in a block without CONSTANT.";
    E191 => "embedded C code",
        "`{{ ... }}` is MatIEC's embedded C code (Beremiz and OpenPLC write it), copied by that compiler into its C output: automat compiles Structured Text only and cannot run it. Write what it does in Structured Text (a function block of your own), or leave the POU out.";
    E200 => "unknown base or interface",
        "`EXTENDS` names no function block or class (a class extends a class, a function block a function block), or `IMPLEMENTS`/an interface's `EXTENDS` names no interface.";
    E201 => "FINAL class or method overridden",
        "A function block or class declared FINAL cannot be extended, and a method declared FINAL cannot be overridden in a derived class.";
    E202 => "cyclic inheritance",
        "A class extends itself through its chain of bases, or an interface through its chain of EXTENDS.";
    E203 => "abstract method not implemented",
        "A class that is not ABSTRACT has an ABSTRACT method (its own or inherited) without an implementation, or a method declared ABSTRACT has a body. Implement it in the class, or declare the class ABSTRACT.";
    E204 => "instance of an abstract class",
        "An ABSTRACT function block or class cannot be instantiated: declare a variable of a derived, non-abstract class (a REF_TO or an interface may still designate it).";
    E205 => "interface method missing",
        "A class that IMPLEMENTS an interface must implement every method and property of it (and of the interfaces it extends), with the same return type.";
    E206 => "unknown method",
        "The call names no method of the class or interface of its instance (methods are looked up in the class and its bases, and for interface variables in the interface and the interfaces it extends).";
    E207 => "member not accessible",
        "A PRIVATE method, property or variable (`VAR PRIVATE`) is reachable only from the methods and body of its own class, a PROTECTED one also from derived classes, an INTERNAL one from code of the same namespace (not the nested ones; a class outside any namespace: code outside namespaces).";
    E208 => "THIS or SUPER out of place",
        "`THIS` is the current instance, inside a method or the body of a function block or class; `SUPER` its base part, only in a class that EXTENDS another. Write them dereferenced: `THIS^.x`, `SUPER^.m()`.";
    E209 => "duplicate method",
        "A class, function block or interface declares two methods or properties of one name, or a method named like one of its variables.";
    E210 => "property without accessor",
        "The property is read but has no GET, or written but has no SET.";
    E211 => "OVERRIDE without a base method",
        "A method marked OVERRIDE overrides nothing: no base class declares a method of that name.";
    E212 => "interface assignment",
        "An interface variable takes an instance of a class that implements the interface (directly, through a base, or through an interface that extends it), or another interface variable of the same interface or of one that extends it.";
    E213 => "inheritance too large",
        "A class has more than 64 levels of bases, or the project's classes need more than 50,000 method bodies (every class compiles its own copy of each inherited method). Flatten the hierarchy.";
    E214 => "bad __QUERYINTERFACE or __QUERYPOINTER",
        "CODESYS's `__QUERYINTERFACE(source, dest)` takes two arguments: an interface value (a variable, member, element or call result; assign an instance to an interface variable first) and an interface variable, member or element, which it sets to the source's instance when that instance's class implements dest's interface (the result TRUE), or to no instance (FALSE). `__QUERYPOINTER(source, dest)` takes an interface value and a pointer variable, which it sets to the address of the source's instance (TRUE) or to 0 (FALSE).";

    E215 => "unknown namespace",
        "A `USING` names a namespace that no `NAMESPACE ... END_NAMESPACE` of the project declares (namespaces are named from the global one: `USING Plant.Motion;`, or relative to the enclosing namespace).";
    E216 => "ambiguous name from USING",
        "The name is declared in none of the enclosing namespaces but in two or more of the namespaces named by `USING`: qualify it (`Motion.Clamp`) to say which one is meant.";
    E217 => "item of an INTERNAL namespace used outside",
        "The item belongs to a `NAMESPACE INTERNAL N` (or to a namespace nested in one): it is visible in the namespace that encloses `N` and in everything nested there, for an INTERNAL namespace at the top only inside `N` itself. Use it from there, or drop INTERNAL.";

    // ---- Allen-Bradley SLC-500 ladder (automat-dialect, slc/) ----
    E230 => "unknown SLC-500 instruction",
        "A word of a rung is no SLC-500 instruction (nor `BST`, `NXB`, `BND`, `SOR`, `EOR`). docs/allen-bradley.md lists the instructions automat runs.";
    E231 => "SLC-500 instruction not implemented",
        "The instruction exists on the SLC-500 but automat does not run it (yet). It is refused, never skipped: a rung that silently did nothing would not be the program. docs/allen-bradley.md lists the instructions automat runs.";
    E232 => "wrong operand kind",
        "An operand is not of the kind its instruction takes: OTE, XIC and the other bit instructions take a bit (`B3/1`, `I:1/1`, `T4:0/DN`), TON/TOF/RTO a timer element (`T4:0`), CTU/CTD a counter (`C5:0`), RES a timer, counter or control element, math and compare instructions words (`N7:0`, `T4:0.ACC`, `F8:1`) or constants, bitwise instructions integer words, a time base 0.01 or 1.0.";
    E233 => "missing operand",
        "The instruction is followed by fewer operands than it takes (RSLogix order: `TON T4:0 0.01 300 0`, `CTU C5:0 7 0`, `MOV N7:0 N7:1`, `LIM 10 N7:0 20`).";
    E234 => "address beyond a declared file",
        "The address names an element past the size the data-file table (`DATA N7 10`) gives its file. Enlarge the file or correct the address.";
    E235 => "rung structure",
        "A branch is not closed (`BST` without `BND`), `NXB` or `BND` has no `BST`, a rung started with `SOR` has no `EOR`, or branches nest deeper than 15.";
    E236 => "bad SLC address",
        "The operand is not an SLC-500 address (`N7:15`, `T4:7.ACC`, `B3:64/15`, `B3/18`, `I:1/1`, `O:3/2`, `S:1/15`, `F8:2`) nor a symbol of the table; the message says why (file type and number, element 0-255, bit 0-15, slot 0-30, a named sub-element of the element's type). Indexed (`#N7:0`) and indirect (`N7:[N7:0]`) addresses are not implemented yet.";
    E237 => "program file structure",
        "A `LAD n` line is wrong or repeated, the project has no program file 2, a JSR names a missing file or recurses (the SLC has no recursion) or nests deeper than 8, a JMP has no LBL of its number in its file, a label is defined twice, LBL is not the first instruction of its rung, or SBR is not the first instruction of a subroutine.";
    E238 => "bad table line",
        "A `SYM ADDRESS NAME [\"description\"]` or `DATA FILE ELEMENTS [= values]` line is malformed: a symbol defined twice or spelled like an address, file or instruction; a data file declared twice, of the wrong type for its number, with 0 or too many elements or initial values.";

    // ---- projects, plants and scenarios (automat-project, automat-scenario) ----
    E300 => "invalid project file",
        "`automat.toml` is not valid TOML, or a key has the wrong type or is unknown. The project file has the tables `[project]` (name, description, sources, program, cycle_time), `[plant]` (model, seed), `[plant.params]`, `[bind]`, `[tasks.NAME]` (watchdog, sensitivity; NAME a task of the program, see docs/watchdog.md), `[retain]`, `[safe_state]`, `[users.NAME]`, `[modbus]` (see docs/modbus.md), `[opcua]` (see docs/opcua.md) and `[runtime]` (realtime, priority 1 to 99, cpus such as `1` or `0,2-3`; see docs/realtime.md).";
    E301 => "unknown plant model",
        "`[plant] model` names no model of the plant library. The message lists every known model.";
    E302 => "unknown plant signal",
        "A `[bind]` entry or a scenario names a signal the plant model does not have. The message lists the model's signals.";
    E303 => "binding to an unknown variable",
        "A signal is bound to a PLC variable path or direct address that does not exist in the compiled program.";
    E304 => "binding type mismatch",
        "A BOOL signal is bound to a variable that is not BOOL, or an integer or real signal to a variable that is not numeric.";
    E305 => "unbound actuator",
        "An actuator of the plant is bound to nothing: no `[bind]` entry names it and no variable of the same name exists, so the plant could never move. Bind it in `[bind]`.";
    E306 => "unbound sensor (warning)",
        "A sensor or operator signal of the plant is bound to nothing: the PLC never sees it. This is a warning; bind it in `[bind]` if the program should read it.";
    E307 => "invalid plant parameter",
        "A `[plant.params]` entry or a scenario `plant` command is refused by the model (unknown key or value out of range); the message gives the model's own reason.";
    E308 => "project has no sources",
        "The project's `sources` (or, by default, the `*.st` files beside `automat.toml`) name no readable Structured Text file.";
    E310 => "plant program unreadable",
        "`[plant] program = \"FILE\"` names a Structured Text file (relative to `automat.toml`) that cannot be read. A plant written in ST is a PROGRAM in that file; see docs/plants-in-st.md.";
    E311 => "no plant PROGRAM",
        "The plant program file must hold exactly one PROGRAM (functions and function blocks beside it are fine) and no CONFIGURATION: the plant runs that PROGRAM once per plant step on its own clock.";
    E312 => "unbound plant input",
        "A VAR_INPUT of the plant program (an actuator: what the controller drives) is bound to no controller variable: there is no `[bind]` entry for it and no controller variable of the same name. Rename one of them or add `NAME = \"<variable or %Q address>\"` under `[bind]`.";
    E313 => "unbound plant output (warning)",
        "A VAR_OUTPUT of the plant program (a sensor: what the controller reads) is bound to no controller variable: the controller never sees it. It is still visible as `plant.NAME` in scenarios, traces and the live view.";
    E314 => "plant signal type",
        "A VAR_INPUT or VAR_OUTPUT of the plant program has a type a signal cannot have: signals are BOOL, integers, bit strings, enumerations or reals (STRING, TIME, arrays, structures and function blocks stay in VAR).";
    E315 => "invalid plant operator signal",
        "An entry of `[plant] operators` names no VAR_OUTPUT of the plant program. Operator signals are VAR_OUTPUTs the plant never computes: push-buttons and selectors that scenarios and the live view of `automat run` `press` and `set`.";
    E320 => "scenario syntax error",
        "A line of a `.scn` scenario file does not follow the scenario language (docs/scenarios.md): `name`, `duration`, `seed`, `at TIME ACTION`, `when EVENT [after TIME] then ACTION` and `expect ...` lines; conditions with `= <> < <= > >= AND OR XOR NOT`, arithmetic `+ - * / MOD`, parentheses and the functions rise, fall, change, prev, count, abs, min and max; at most 256 operands and 32 levels of nesting.";
    E321 => "unknown name in a scenario",
        "A scenario names something that is neither a signal of the plant model, a quantity `plant.<name>`, nor a variable of the program (a path such as `Ctrl.fb.Q`, a direct address such as `%IX0.1`, or a dialect operand such as FST `I0.1`).";
    E322 => "scenario type mismatch",
        "A scenario compares, computes with or sets values of incompatible types (a BOOL with a number, a TIME plus a number, an enumeration value of another type), or presses a signal that is not a BOOL operator signal.";
    E323 => "scenario without duration",
        "Every scenario needs a `duration` line: the PLC time it simulates.";
    E324 => "scenario outside a project",
        "A `.scn` file must lie in a project folder: a folder with `automat.toml` at or above it.";
    E325 => "scenario needs a plant",
        "The project has no `[plant]`, and the scenario uses what only a plant model has: a `plant.<quantity>`, `stuck`, `unstick` or `noise` on a signal, or a `plant` command. Without a plant a scenario drives the program's own variables (`set`, `press`, `release` on variable paths and direct addresses) and checks them; see docs/scenarios.md.";
    E326 => "misplaced scenario function",
        "A function of the scenario language is used where it has no meaning: `count(...)` outside an expectation with a window (`expect C during A..B`, `expect at T C`, `expect always C`) or inside another function's argument; `rise`, `fall`, `change` or `prev` inside one another (they compare one scan with the one before and take plain values). See docs/scenarios.md.";

    // ---- Modbus (automat-fieldbus, `[modbus]` in automat.toml, docs/modbus.md) ----
    E340 => "invalid Modbus configuration",
        "A `[modbus.server]`, `[[modbus.server.map]]`, `[[modbus.client]]` or block table of `automat.toml` has a key of the wrong form: an address that is not ADDR:PORT, a table that is not coils, discrete_inputs, input_registers or holding_registers, a Modbus address or count out of range (addresses 0..=65535, counts within the protocol's limits), a duration that does not parse, a block with neither or both of `to` and `from`, two devices of one name, or a server on a non-loopback address with neither `allow` nor `read_only = true` (Modbus has no passwords: anyone who reaches it could write).";
    E341 => "Modbus entry names an unknown variable",
        "A Modbus map entry, a client block or a device's status variable names a path or direct address that does not exist in the compiled program.";
    E342 => "Modbus entry of the wrong type or size",
        "The variable does not fit the Modbus table: coils and discrete inputs take BOOLs (or a bit address such as `%IX0.0`), registers take one elementary value of 8 to 64 bits (or a word address such as `%IW0`); a count that differs from what the variables hold, a block reaching past the end of its area, or a status variable that is not BOOL (connected) or an integer (errors, last_error).";
    E343 => "overlapping Modbus addresses",
        "Two explicit `[[modbus.server.map]]` entries give the same Modbus address of one table: each address of a table maps to one place.";
    E344 => "read-only variable mapped for writing",
        "A CONSTANT or compiler-generated variable (an SFC step flag or time) is mapped where a Modbus client or device would write it: as a coil or holding register of the server, or as the target of a client's read block or status variable. Map it as a discrete input or input register instead.";
    E345 => "invalid Modbus RTU serial line",
        "A `[modbus.rtu_server]` or `[[modbus.rtu_device]]` table has a serial setting out of range or in conflict: `device` empty or missing, `baud` outside 50..=4000000, `parity` not none, even or odd, `stop_bits` not 1 or 2, a unit outside 1..=247 (0 is the broadcast address, 248-255 are reserved); a TCP device with serial settings or an RTU device with an `address`; devices on one port with different settings or the same unit; or one port used both by the slave and by devices (a port is either the slave's or the master's). See docs/modbus.md, \"Modbus RTU\".";
    E346 => "invalid OPC UA configuration",
        "The `[opcua]` table of `automat.toml` has a key of the wrong form: `listen` that is not PORT or ADDR:PORT (a port alone binds 127.0.0.1), a key that is not `listen`, `pki_dir` or `trust_client_certs`, or a value of the wrong type. See docs/opcua.md.";

    // ---- warnings ----
    W001 => "unused variable",
        "A local variable is declared but never read or written.";
    W002 => "unreachable code",
        "A statement follows RETURN, EXIT or CONTINUE in the same block and can never run.";
    W003 => "implicit narrowing in a constant",
        "A constant is converted to a smaller type; the value fits, so the program is accepted.";
    W004 => "integer division assigned to a real",
        "An integer division is assigned to a REAL or LREAL: it is computed in the integer type and truncated toward zero before the conversion (`r := i / 2` with `i = 7` gives 3.0, not 3.5). Convert an operand first: `r := INT_TO_REAL(i) / 2.0`.";
    W120 => "unreachable step",
        "No sequence of transitions from the initial step can activate this step.";
    W121 => "step without a way out",
        "No transition leaves this step: once active it stays active (intended only for the final step of a sequence).";
    W122 => "unused action",
        "An ACTION of the chart is associated with no step, so it never runs.";
    W150 => "section ignored",
        "ISaGRAF dialect: the project has a CONFIGURATION, whose tasks decide which programs run and in what order; `{section ...}` pragmas are then ignored.";
    W160 => "pragma ignored",
        "CODESYS dialect: `{attribute ...}`, `{flag ...}` and the other pragmas of a file are accepted and not interpreted (automat has no such settings); the warning is given once per file, at its first pragma, with their number.";
    W161 => "implicit narrowing conversion",
        "CODESYS dialect: a value is assigned or passed where a narrower type is expected (DINT to INT, WORD to BYTE, REAL to INT, LREAL to REAL). CODESYS converts it implicitly, as the `X_TO_Y` conversion function would (integers and bit strings keep their low bits, reals are rounded); automat does the same and warns, since the value may not fit. Without the dialect this is error E030.";
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
