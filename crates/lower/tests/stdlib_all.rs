//! Every standard function of sema's table (`crates/sema/src/stdlib/`)
//! lowers: a call of each fixed-name function and of every conversion the
//! checker accepts is checked and lowered, and none may give E091.

mod common;
use automat_iec::Elementary as E;
use automat_sema::stdlib::{lookup, Kind, PDir, PTy, RTy, Sig};
use common::*;

/// The fixed names, read from the table's source so a new entry is covered.
fn fixed_names() -> Vec<String> {
    let src = include_str!("../../sema/src/stdlib/table.rs");
    src.lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let rest = l.strip_prefix('"')?;
            let (name, tail) = rest.split_once('"')?;
            tail.trim_start()
                .starts_with("=>")
                .then(|| name.to_string())
        })
        .collect()
}

/// Every conversion name over the elementary types, STRING and WSTRING.
fn conversion_names() -> Vec<String> {
    let mut tys: Vec<String> = E::ALL
        .iter()
        .filter(|e| !matches!(e, E::String | E::Wstring))
        .map(|e| e.to_string())
        .collect();
    tys.push("STRING".into());
    tys.push("WSTRING".into());
    let mut out = Vec::new();
    for a in &tys {
        out.push(format!("TO_{a}"));
        out.push(format!("TRUNC_{a}"));
        out.push(format!("BCD_TO_{a}"));
        out.push(format!("{a}_TO_BCD"));
        for b in &tys {
            for n in [
                format!("{a}_TO_{b}"),
                format!("{a}_TRUNC_{b}"),
                format!("{a}_BCD_TO_{b}"),
                format!("{a}_TO_BCD_{b}"),
            ] {
                out.push(n);
            }
        }
    }
    out.retain(|n| lookup(n).is_some());
    out
}

/// A variable of the given kind.
fn kind_var(k: Kind) -> &'static str {
    match k {
        Kind::AnyReal => "v_LREAL",
        Kind::AnyBit => "v_WORD",
        Kind::AnyString => "s",
        Kind::AnyDate => "v_DATE",
        Kind::AnyDuration => "v_TIME",
        _ => "v_DINT",
    }
}

fn var_of(t: PTy) -> String {
    match t {
        PTy::Gen(k) | PTy::Free(k) => kind_var(k).into(),
        PTy::Elem(e) => format!("v_{}", elem_name(e)),
        PTy::Str(w) => if w { "ws" } else { "s" }.into(),
        PTy::Array => "arr".into(),
    }
}

fn elem_name(e: automat_sema::types::Elem) -> String {
    format!("{e:?}").to_ascii_uppercase()
}

/// One statement calling `sig` with an argument of the right kind per parameter.
fn call_of(sig: &Sig) -> String {
    let mut args = Vec::new();
    let mut gen_var = None;
    for (i, p) in sig.params.iter().enumerate() {
        let v = match (sig.name.as_str(), i) {
            ("LOWER_BOUND" | "UPPER_BOUND", 1) => "1".to_string(),
            _ => var_of(p.ty),
        };
        if let PTy::Gen(_) = p.ty {
            gen_var.get_or_insert_with(|| v.clone());
        }
        match p.dir {
            PDir::Out => args.push(format!("{} => {v}", p.name)),
            _ => args.push(format!("{} := {v}", p.name)),
        }
    }
    if let Some(ext) = sig.ext {
        let v = var_of(ext.ty);
        if let PTy::Gen(_) = ext.ty {
            gen_var.get_or_insert_with(|| v.clone());
        }
        for k in 0..ext.min.max(2) {
            args.push(format!("{}{} := {v}", ext.prefix, ext.first + k));
        }
    }
    let call = format!("{}({})", sig.name, args.join(", "));
    match sig.ret {
        RTy::Void => format!("{call};"),
        RTy::Gen => format!("{} := {call};", gen_var.unwrap_or_else(|| "v_DINT".into())),
        RTy::Elem(e) => format!("v_{} := {call};", elem_name(e)),
        RTy::Str(w) => format!("{} := {call};", if w { "ws" } else { "s" }),
        RTy::RefToArg => format!("r := {call};"),
    }
}

fn program(stmt: &str) -> String {
    let mut vars = String::new();
    for e in E::ALL {
        if matches!(e, E::String | E::Wstring) {
            continue;
        }
        vars.push_str(&format!("v_{e} : {e}; "));
    }
    format!(
        "PROGRAM Main
         VAR {vars} s : STRING; ws : WSTRING; arr : ARRAY[1..3] OF INT; r : REF_TO DINT; END_VAR
         {stmt}
         END_PROGRAM"
    )
}

#[test]
fn every_standard_function_lowers() {
    let mut names = fixed_names();
    assert!(names.len() > 80, "table names: {}", names.len());
    let conv = conversion_names();
    assert!(conv.len() > 500, "conversions: {}", conv.len());
    names.extend(conv);
    let mut lowered = 0;
    let mut rejected = Vec::new();
    let mut unsupported = Vec::new();
    for n in &names {
        let Some(sig) = lookup(n) else {
            panic!("{n} is in the table but lookup does not find it");
        };
        // REF and ADR of the DINT variable, so `r := REF(v_DINT)` type-checks.
        let stmt = match n.as_str() {
            "REF" | "ADR" => format!("r := {n}(v_DINT);"),
            _ => call_of(&sig),
        };
        let src = program(&stmt);
        match try_build(&src, &Default::default()) {
            Ok(_) => lowered += 1,
            Err(d) => {
                if d.iter().any(|d| d.code.as_str() == "E091") {
                    unsupported.push(format!(
                        "{stmt}: {:?}",
                        d.iter().map(|d| &d.message).collect::<Vec<_>>()
                    ));
                } else {
                    rejected.push(format!(
                        "{stmt}: {:?}",
                        d.iter()
                            .map(|d| format!("{} {}", d.code.as_str(), d.message))
                            .collect::<Vec<_>>()
                    ));
                }
            }
        }
    }
    assert!(
        unsupported.is_empty(),
        "E091 for:\n{}",
        unsupported.join("\n")
    );
    assert!(
        rejected.is_empty(),
        "checker rejected:\n{}",
        rejected.join("\n")
    );
    assert_eq!(lowered, names.len());
}
