//! The importer's diagnostics: each case is a small PLCopen file and the
//! `line:col: error[Ennn]` lines `automat check` must print for it (the
//! code and the XML position of the element; the message names the POU and
//! the `localId`). The checker's own errors in LD/FBD code point at the
//! XML too (a type mismatch at a pin).

use automat_base::{render, Interner, SourceMap};

const HEAD: &str = r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201">
<types><dataTypes/><pous>
"#;
const TAIL: &str = "\n</pous></types></project>\n";

/// A program `P` with `vars` (a localVars list) and an LD/FBD body.
fn program(vars: &str, lang: &str, body: &str) -> String {
    format!(
        "{HEAD}<pou name=\"P\" pouType=\"program\"><interface><localVars>{vars}</localVars></interface>\n<body><{lang}>\n{body}\n</{lang}></body></pou>{TAIL}"
    )
}

fn check(text: &str) -> String {
    let mut map = SourceMap::new();
    map.add("t.xml", text);
    let mut interner = Interner::new();
    let (_, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    render::render_report(&map, &analysis.diagnostics)
}

/// The `t.xml:L:C: error[Ennn]: message` lines of a report.
fn heads(report: &str) -> Vec<String> {
    report
        .lines()
        .filter(|l| l.starts_with("t.xml:"))
        .map(|l| l.trim_start_matches("t.xml:").to_string())
        .collect()
}

fn expect(text: &str, want: &[&str]) {
    let report = check(text);
    let got = heads(&report);
    assert_eq!(got.len(), want.len(), "{report}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            g.starts_with(w) || g.contains(w),
            "got `{g}`, want `{w}`\n{report}"
        );
    }
}

const BOOLS: &str = r#"<variable name="a"><type><BOOL/></type></variable><variable name="q"><type><BOOL/></type></variable><variable name="n"><type><INT/></type></variable>"#;

#[test]
fn not_xml() {
    expect(
        "<project><types></project>",
        &["1:17: error[E170]: not well-formed XML: expected 'types' tag, not 'project'"],
    );
    expect(
        "<other/>",
        &["1:1: error[E170]: the root element is `other`"],
    );
}

#[test]
fn missing_attributes_and_names() {
    let t = format!("{HEAD}<pou pouType=\"program\"><body><ST/></body></pou>{TAIL}");
    expect(
        &t,
        &["3:1: error[E171]: `pou` without the `name` attribute"],
    );
    let t = format!("{HEAD}<pou name=\"1P\" pouType=\"program\"><body><ST/></body></pou>{TAIL}");
    expect(
        &t,
        &["3:12: error[E177]: a POU's name `1P` is not an identifier"],
    );
    let t = format!("{HEAD}<pou name=\"P\" pouType=\"class\"><body><ST/></body></pou>{TAIL}");
    expect(&t, &["3:1: error[E171]: POU `P`: `pouType` is `class`"]);
}

#[test]
fn missing_local_id() {
    let t = program(
        BOOLS,
        "LD",
        r#"<leftPowerRail localId="1"/>
<coil localId="3"><connectionPointIn><connection refLocalId="9"/></connectionPointIn><variable>q</variable></coil>"#,
    );
    expect(
        &t,
        &["6:38: error[E172]: POU `P`, localId 3: a connection names localId 9"],
    );
}

#[test]
fn unconnected_input_and_coil_without_left() {
    let t = program(
        BOOLS,
        "LD",
        r#"<coil localId="3"><connectionPointIn/><variable>q</variable></coil>
<outVariable localId="4"><connectionPointIn/><expression>n</expression></outVariable>"#,
    );
    expect(
        &t,
        &[
            "5:1: error[E175]: POU `P`, localId 3: nothing is connected on the left",
            "6:1: error[E173]: POU `P`, localId 4: the input of this output variable is not connected",
        ],
    );
    let t = program(
        BOOLS,
        "FBD",
        r#"<inVariable localId="1"><expression>n</expression></inVariable>
<block localId="2" typeName="ADD"><inputVariables><variable formalParameter="IN1"><connectionPointIn><connection refLocalId="1"/></connectionPointIn></variable><variable formalParameter="IN2"><connectionPointIn/></variable></inputVariables><outputVariables><variable formalParameter="OUT"/></outputVariables></block>
<outVariable localId="3"><connectionPointIn><connection refLocalId="2" formalParameter="OUT"/></connectionPointIn><expression>n</expression></outVariable>"#,
    );
    // The checker then counts the arguments the call has (E050).
    expect(
        &t,
        &[
            "6:51: error[E050]",
            "6:161: error[E173]: POU `P`, localId 2: input `IN2` of `ADD` is not connected",
        ],
    );
}

#[test]
fn loop_without_feedback_variable() {
    let vars = r#"<variable name="i1"><type><derived name="TON"/></type></variable><variable name="i2"><type><derived name="TON"/></type></variable>"#;
    let t = program(
        vars,
        "FBD",
        r#"<block localId="1" typeName="TON" instanceName="i1"><inputVariables><variable formalParameter="IN"><connectionPointIn><connection refLocalId="2" formalParameter="Q"/></connectionPointIn></variable></inputVariables><outputVariables><variable formalParameter="Q"/></outputVariables></block>
<block localId="2" typeName="TON" instanceName="i2"><inputVariables><variable formalParameter="IN"><connectionPointIn><connection refLocalId="1" formalParameter="Q"/></connectionPointIn></variable></inputVariables><outputVariables><variable formalParameter="Q"/></outputVariables></block>"#,
    );
    expect(
        &t,
        &["5:1: error[E174]: POU `P`, localId 1: a loop of connections"],
    );
}

#[test]
fn vendor_block() {
    let vars = r#"<variable name="p"><type><derived name="python_eval"/></type></variable>"#;
    let t = program(
        vars,
        "FBD",
        r#"<block localId="1" typeName="python_eval" instanceName="p"><inputVariables/><outputVariables/></block>"#,
    );
    let report = check(&t);
    assert!(
        report.contains("5:1: error[E176]: POU `P`, localId 1: unknown function block `python_eval`: a Beremiz block"),
        "{report}"
    );
}

#[test]
fn type_mismatch_at_a_pin_points_at_the_wire() {
    // `n` (INT) on a contact: the checker's error is at the contact's wire.
    let t = program(
        BOOLS,
        "LD",
        r#"<leftPowerRail localId="1"/>
<contact localId="2"><connectionPointIn><connection refLocalId="1"/></connectionPointIn><variable>n</variable></contact>
<coil localId="3"><connectionPointIn><connection refLocalId="2"/></connectionPointIn><variable>q</variable></coil>"#,
    );
    let report = check(&t);
    assert!(
        report.contains("t.xml:6:41: error[E031]: POU `P`, localId 2: operator `AND` is not defined for BOOL and INT"),
        "{report}"
    );
}

#[test]
fn type_mismatch_at_a_block_pin_names_the_block() {
    // A BOOL wired to ADD's IN2: the checker's error at the wire names the block.
    let t = program(
        BOOLS,
        "FBD",
        r#"<inVariable localId="1"><connectionPointOut/><expression>n</expression></inVariable>
<inVariable localId="2"><connectionPointOut/><expression>a</expression></inVariable>
<block localId="3" typeName="ADD"><inputVariables><variable formalParameter="IN1"><connectionPointIn><connection refLocalId="1"/></connectionPointIn></variable><variable formalParameter="IN2"><connectionPointIn><connection refLocalId="2"/></connectionPointIn></variable></inputVariables><outputVariables><variable formalParameter="OUT"/></outputVariables></block>
<outVariable localId="4"><connectionPointIn><connection refLocalId="3" formalParameter="OUT"/></connectionPointIn><expression>n</expression></outVariable>"#,
    );
    // 7:212 is IN2's `connection` element.
    expect(
        &t,
        &["7:212: error[E052]: POU `P`, localId 3: the arguments of `ADD` have incompatible types INT and BOOL"],
    );
}

#[test]
fn unknown_name_in_a_contact_names_the_contact() {
    let t = program(
        BOOLS,
        "LD",
        r#"<leftPowerRail localId="1"><connectionPointOut/></leftPowerRail>
<contact localId="2"><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>nope</variable></contact>
<coil localId="3"><connectionPointIn><connection refLocalId="2"/></connectionPointIn><variable>q</variable></coil>"#,
    );
    expect(
        &t,
        &["6:120: error[E020]: POU `P`, localId 2: unknown variable `nope`"],
    );
}

#[test]
fn vendor_elements_name_their_tool() {
    let t = program(
        BOOLS,
        "FBD",
        r#"<vendorElement localId="4"><position x="0" y="0"/><alternativeText><xhtml:p xmlns:xhtml="http://www.w3.org/1999/xhtml">Python   hook</xhtml:p></alternativeText><addData><data name="http://www.beremiz.org/python" handleUnknown="discard"/></addData></vendorElement>"#,
    );
    expect(
        &t,
        &["5:1: error[E171]: POU `P`, localId 4: a vendor's element `Python hook` of `http://www.beremiz.org/python`, not an IEC 61131-3 element: automat cannot run it"],
    );
    let t = program(
        BOOLS,
        "LD",
        r#"<vendorElement localId="5"><position x="0" y="0"/><alternativeText/></vendorElement>"#,
    );
    expect(
        &t,
        &["5:1: error[E171]: POU `P`, localId 5: a vendor's element (no `addData` names its tool)"],
    );
}

#[test]
fn element_without_local_id() {
    let t = program(
        BOOLS,
        "LD",
        r#"<leftPowerRail localId="1"><connectionPointOut/></leftPowerRail>
<contact><connectionPointIn><connection refLocalId="1"/></connectionPointIn><variable>a</variable></contact>"#,
    );
    expect(
        &t,
        &["6:1: error[E171]: POU `P`: `contact` without a numeric `localId`"],
    );
}

#[test]
fn wired_sfc_conditions() {
    // Step S0, a transition back to S0 whose condition is wired to `cond`.
    let chart = |cond: &str| {
        program(
            BOOLS,
            "SFC",
            &format!(
                r#"<step localId="1" name="S0" initialStep="true"><connectionPointIn><connection refLocalId="2"/></connectionPointIn></step>
<transition localId="2"><connectionPointIn><connection refLocalId="1"/></connectionPointIn><condition><connectionPointIn><connection refLocalId="3"/></connectionPointIn></condition></transition>
{cond}"#
            ),
        )
    };
    expect(
        &chart(
            r#"<contact localId="3" edge="rising"><connectionPointIn/><variable>a</variable></contact>"#,
        ),
        &["7:1: error[E171]: POU `P`, localId 3: an edge contact in a transition condition"],
    );
    expect(
        &chart(r#"<block localId="3" typeName="AND"/>"#),
        &[
            "7:1: error[E171]: POU `P`, localId 3: `block` in a transition condition",
            "7:1: error[E171]: POU `P`: `block` in an SFC body is not supported",
        ],
    );
    expect(
        &chart(
            r#"<contact localId="3"><connectionPointIn><connection refLocalId="3"/></connectionPointIn><variable>a</variable></contact>"#,
        ),
        &["7:1: error[E174]: POU `P`, localId 3: a transition condition's wires loop"],
    );
    expect(
        &chart(r#"<contact localId="4"><connectionPointIn/><variable>a</variable></contact>"#),
        &["6:103: error[E172]: POU `P`: a transition condition's wire names localId 3"],
    );
    expect(
        &chart(r#"<contact localId="3"><connectionPointIn/><variable>a</variable></contact>"#),
        &["7:22: error[E173]: POU `P`: a transition condition's wire is not connected"],
    );
    // A condition of the wrong type: the checker's error at the wire.
    expect(
        &chart(r#"<inVariable localId="3"><expression>n</expression></inVariable>"#),
        &["6:103: error[E032]: POU `P`, localId 2: the IF condition must be BOOL, found INT"],
    );
}

/// A program `P` whose chart is S0 to the macro-step M and back, M's body
/// being `body` (the macro-step is on line 6, column 1).
fn macro_chart(body: &str) -> String {
    format!(
        "{HEAD}<pou name=\"P\" pouType=\"program\"><interface><localVars>{BOOLS}</localVars></interface>\n<body><SFC>\n<step localId=\"1\" name=\"S0\" initialStep=\"true\"><connectionPointIn><connection refLocalId=\"4\"/></connectionPointIn></step><transition localId=\"2\"><connectionPointIn><connection refLocalId=\"1\"/></connectionPointIn><condition><inline><ST>a</ST></inline></condition></transition>\n<macroStep localId=\"3\" name=\"M\"><connectionPointIn><connection refLocalId=\"2\"/></connectionPointIn>{body}</macroStep>\n<transition localId=\"4\"><connectionPointIn><connection refLocalId=\"3\"/></connectionPointIn><condition><inline><ST>q</ST></inline></condition></transition>\n</SFC></body></pou>{TAIL}"
    )
}

/// The exit step of a macro-step's body is the one step no transition of
/// the body leaves (docs/plcopen.md): none or several is E179 at the
/// macro-step, naming its localId and POU.
#[test]
fn macro_step_exit_rule() {
    const B1: &str = r#"<step localId="31" name="B1" initialStep="true"/>"#;
    const T1: &str = r#"<transition localId="32"><connectionPointIn><connection refLocalId="31"/></connectionPointIn><condition><inline><ST>a</ST></inline></condition></transition>"#;
    let ok = format!(
        r#"<body><SFC>{B1}{T1}<step localId="33" name="B2"><connectionPointIn><connection refLocalId="32"/></connectionPointIn></step></SFC></body>"#
    );
    expect(&macro_chart(&ok), &[]);
    // B2 and B3 both end the body.
    let two = format!(
        r#"<body><SFC>{B1}{T1}<step localId="33" name="B2"><connectionPointIn><connection refLocalId="32"/></connectionPointIn></step><step localId="34" name="B3"/></SFC></body>"#
    );
    expect(
        &macro_chart(&two),
        &["6:1: error[E179]: POU `P`, localId 3: macro-step `M` has no exit step: 2 steps of its body are left by no transition (`B2`, `B3`)"],
    );
    // B1 and B2 loop: every step is left.
    let none = format!(
        r#"<body><SFC>{B1}{T1}<step localId="33" name="B2"><connectionPointIn><connection refLocalId="32"/></connectionPointIn></step><transition localId="35"><connectionPointIn><connection refLocalId="33"/></connectionPointIn><condition><inline><ST>q</ST></inline></condition></transition><jumpStep localId="36" targetName="B1"><connectionPointIn><connection refLocalId="35"/></connectionPointIn></jumpStep></SFC></body>"#
    );
    expect(
        &macro_chart(&none),
        &["6:1: error[E179]: POU `P`, localId 3: macro-step `M` has no exit step: every step of its body is left by a transition"],
    );
    // No body at all.
    expect(
        &macro_chart(""),
        &["6:1: error[E171]: POU `P`, localId 3: macro-step `M` has no SFC body"],
    );
    // The chart checks run once over the chart with its bodies: a body
    // step named as a step of the chart is one E122, and a body without an
    // initial step one E123/E124.
    let clash = format!(
        r#"<body><SFC>{B1}{T1}<step localId="33" name="S0"><connectionPointIn><connection refLocalId="32"/></connectionPointIn></step></SFC></body>"#
    );
    let report = check(&macro_chart(&clash));
    assert_eq!(report.matches("error[E122]").count(), 1, "{report}");
    let no_entry = format!(
        r#"<body><SFC><step localId="31" name="B1"/>{T1}<step localId="33" name="B2"><connectionPointIn><connection refLocalId="32"/></connectionPointIn></step></SFC></body>"#
    );
    let report = check(&macro_chart(&no_entry));
    assert_eq!(heads(&report).len(), 1, "{report}");
    assert!(report.contains("error[E12"), "{report}");
}

#[test]
fn st_body_errors_keep_their_position() {
    let t = format!(
        "{HEAD}<pou name=\"P\" pouType=\"program\"><interface><localVars>{BOOLS}</localVars></interface>\n<body><ST><xhtml:p xmlns:xhtml=\"http://www.w3.org/1999/xhtml\"><![CDATA[q := a;\n  n := nope;]]></xhtml:p></ST></body></pou>{TAIL}"
    );
    expect(&t, &["5:8: error[E020]"]);
    // Entities are decoded and positions still exact.
    let t = format!(
        "{HEAD}<pou name=\"P\" pouType=\"program\"><interface><localVars>{BOOLS}</localVars></interface>\n<body><ST><xhtml:p xmlns:xhtml=\"http://www.w3.org/1999/xhtml\">q := n &lt; 3 AND nope;</xhtml:p></ST></body></pou>{TAIL}"
    );
    expect(&t, &["4:81: error[E020]"]);
}

/// Every code of the importer (E170–E179) has a case in this file.
#[test]
fn every_importer_code_is_covered() {
    let me = include_str!("diagnostics.rs");
    for c in automat_base::Code::ALL
        .iter()
        .filter(|c| c.as_str().starts_with("E17"))
    {
        let needle = format!("error[{}]", c.as_str());
        // Split so this test's own text does not count.
        assert!(
            me.matches(&needle).count() >= 1,
            "no case for {}",
            c.as_str()
        );
    }
}

#[test]
fn export_refuses_what_tc6_cannot_hold() {
    let mut map = SourceMap::new();
    map.add("g.st", "VAR_GLOBAL x : INT; END_VAR\nPROGRAM P VAR_EXTERNAL x : INT; END_VAR x := 1; END_PROGRAM\n");
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    assert!(!analysis.has_errors());
    let Err(d) = automat_plcopen::export(&units, &map, "g") else {
        panic!("exported a global outside a configuration");
    };
    let report = render::render_report(&map, &d);
    assert!(
        report.contains("g.st:1:1: error[E178]: a VAR_GLOBAL outside a CONFIGURATION"),
        "{report}"
    );
}

/// Object-oriented units (methods, EXTENDS/IMPLEMENTS, CLASS, INTERFACE):
/// TC6 2.01 has no element for them, so export refuses each (E178) rather
/// than writing the generated plain POUs, which would not read back as the
/// program that was written.
#[test]
fn export_refuses_object_oriented_units() {
    let mut map = SourceMap::new();
    map.add(
        "oop.st",
        "INTERFACE IRun\nMETHOD Start : INT\nEND_METHOD\nEND_INTERFACE\n\
         FUNCTION_BLOCK Motor IMPLEMENTS IRun\nMETHOD Start : INT\n    Start := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n\
         CLASS Keeper\nVAR v : INT; END_VAR\nMETHOD Get : INT\n    Get := v;\nEND_METHOD\nEND_CLASS\n\
         PROGRAM P\nVAR m : Motor; k : Keeper; x : INT; END_VAR\n    x := m.Start() + k.Get();\nEND_PROGRAM\n\
         CONFIGURATION C\nRESOURCE R ON PLC\nTASK T (INTERVAL := T#10ms);\nPROGRAM I WITH T : P;\nEND_RESOURCE\nEND_CONFIGURATION\n",
    );
    let mut interner = Interner::new();
    let (units, analysis) = automat_dialect::check_sources(&map, &mut interner, &[]);
    assert!(
        !analysis.has_errors(),
        "{}",
        render::render_report(&map, &analysis.diagnostics)
    );
    let Err(d) = automat_plcopen::export(&units, &map, "oop") else {
        panic!("exported object-oriented units");
    };
    let report = render::render_report(&map, &d);
    assert!(
        report
            .contains("oop.st:1:11: error[E178]: interface `IRun`: TC6 2.01 XML has no interfaces"),
        "{report}"
    );
    assert!(
        report.contains("oop.st:5:16: error[E178]: function block `Motor` has methods, inheritance or interfaces, which TC6 2.01 XML cannot hold"),
        "{report}"
    );
    assert!(
        report.contains("oop.st:10:7: error[E178]: class `Keeper`"),
        "{report}"
    );
    assert_eq!(d.len(), 3, "{report}");
}
