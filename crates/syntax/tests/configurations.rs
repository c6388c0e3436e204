mod common;
use automat_syntax::ast::*;
use common::{addr, ok, Out};

fn config(out: &Out) -> &Configuration {
    out.unit
        .items
        .iter()
        .find_map(|i| match i {
            Item::Config(c) => Some(c),
            _ => None,
        })
        .expect("a configuration")
}

const FULL: &str = "CONFIGURATION Cell
  VAR_GLOBAL
    start : BOOL;
  END_VAR
  RESOURCE Res ON PLC_CPU
    VAR_GLOBAL RETAIN counter : DINT; END_VAR
    TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
    TASK Trig (SINGLE := start, PRIORITY := 5);
    PROGRAM RETAIN Main WITH Fast : MainProg (in := start, out => lamp);
    PROGRAM Aux : AuxProg;
  END_RESOURCE
  VAR_ACCESS
    LampAcc : Res.Main.lamp : BOOL READ_ONLY;
    CntAcc : Res.Main.cnt : DINT READ_WRITE;
    Raw : %IW2 : INT;
  END_VAR
  VAR_CONFIG
    Res.Main.fb.x AT %QX1.0 : BOOL := TRUE;
    Res.Aux.speed : INT := 5;
  END_VAR
END_CONFIGURATION
";

#[test]
fn full_configuration() {
    let out = ok(FULL);
    let c = config(&out);
    assert_eq!(out.name(c.name), "Cell");
    assert_eq!(c.globals.len(), 1);
    assert_eq!(c.resources.len(), 1);
    let r = &c.resources[0];
    assert_eq!(
        (out.name(r.name), r.on.map(|o| out.name(o)), r.implicit),
        ("Res".into(), Some("PLC_CPU".into()), false)
    );
    assert_eq!(r.globals[0].retain, Retain::Retain);
    let tasks: Vec<String> = r
        .tasks
        .iter()
        .map(|t| {
            let props: Vec<String> = t
                .props
                .iter()
                .map(|p| format!("{}={}", out.name(p.name), out.expr(&p.value)))
                .collect();
            format!("{}({})", out.name(t.name), props.join(","))
        })
        .collect();
    assert_eq!(
        tasks,
        vec![
            "Fast(INTERVAL=T#10000000ns,PRIORITY=1)",
            "Trig(SINGLE=start,PRIORITY=5)"
        ]
    );
    let main = &r.programs[0];
    assert_eq!(main.retain, Retain::Retain);
    assert_eq!(out.name(main.name), "Main");
    assert_eq!(main.task.map(|t| out.name(t)), Some("Fast".into()));
    assert_eq!(out.name(main.ty), "MainProg");
    let conns: Vec<String> = main.conns.iter().map(|a| out.arg(a)).collect();
    assert_eq!(conns, vec!["(in := start)", "(out => lamp)"]);
    assert_eq!(r.programs[1].task, None);
    assert!(r.programs[1].conns.is_empty());

    let acc: Vec<String> = c
        .access
        .iter()
        .map(|a| {
            format!(
                "{} {} {} {:?}",
                out.name(a.name),
                out.expr(&a.path),
                out.ty(&a.ty),
                a.direction
            )
        })
        .collect();
    assert_eq!(
        acc,
        vec![
            "LampAcc (. (. Res Main) lamp) BOOL Some(ReadOnly)",
            "CntAcc (. (. Res Main) cnt) DINT Some(ReadWrite)",
            "Raw %IW2 INT None",
        ]
    );
    let vc: Vec<String> = c
        .var_config
        .iter()
        .map(|v| {
            format!(
                "{} {} {} {}",
                out.expr(&v.path),
                v.location
                    .as_ref()
                    .map(|l| addr(&l.addr))
                    .unwrap_or_default(),
                out.ty(&v.ty),
                v.init.as_ref().map(|i| out.init(i)).unwrap_or_default()
            )
        })
        .collect();
    assert_eq!(
        vc,
        vec![
            "(. (. (. Res Main) fb) x) %QX1.0 BOOL TRUE",
            "(. (. Res Aux) speed)  INT 5"
        ]
    );
}

#[test]
fn configuration_without_resource_has_an_implicit_one() {
    let out = ok("CONFIGURATION C\n  TASK t (INTERVAL := T#5ms);\n  PROGRAM p WITH t : Main;\nEND_CONFIGURATION\n");
    let c = config(&out);
    assert_eq!(c.resources.len(), 1);
    let r = &c.resources[0];
    assert!(r.implicit);
    assert_eq!(out.name(r.name), "C");
    assert_eq!((r.tasks.len(), r.programs.len()), (1, 1));

    let empty = ok("CONFIGURATION C END_CONFIGURATION");
    let r = &config(&empty).resources;
    assert_eq!(r.len(), 1);
    assert!(r[0].implicit && r[0].tasks.is_empty());
}

#[test]
fn several_resources() {
    let out = ok("CONFIGURATION C\n\
        RESOURCE A ON X END_RESOURCE\n\
        RESOURCE B ON Y PROGRAM q : Q; END_RESOURCE\n\
        END_CONFIGURATION");
    let c = config(&out);
    let names: Vec<String> = c.resources.iter().map(|r| out.name(r.name)).collect();
    assert_eq!(names, vec!["A", "B"]);
    assert!(c.resources.iter().all(|r| !r.implicit));
}

#[test]
fn configuration_next_to_pous_and_types() {
    let out = ok("TYPE T : INT; END_TYPE\nPROGRAM Main END_PROGRAM\nCONFIGURATION C RESOURCE R ON P TASK t(INTERVAL := T#1s); PROGRAM m WITH t : Main; END_RESOURCE END_CONFIGURATION\n");
    assert_eq!(out.unit.items.len(), 3);
    assert!(matches!(out.unit.items[2], Item::Config(_)));
}
