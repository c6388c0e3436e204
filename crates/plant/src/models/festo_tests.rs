use super::*;

fn run(p: &mut Festo, ms: i64) {
    let mut rng = Rng::new(1);
    for _ in 0..ms {
        p.step(1_000_000, &mut rng);
    }
}
fn on(p: &mut Festo, s: usize, v: bool) {
    p.set(s, Value::Bool(v));
}
fn b(p: &Festo, s: usize) -> bool {
    p.get(s).as_bool()
}

#[test]
fn signal_table_matches_the_indices() {
    assert_eq!(SIGNALS.get(START).map(|s| s.name), Some("START"));
    assert_eq!(SIGNALS.get(EJECT_OUT).map(|s| s.name), Some("EjectOut"));
    assert_eq!(SIGNALS.get(ARM_TO_NXT).map(|s| s.name), Some("ArmToNxt"));
}

#[test]
fn rest_position() {
    let p = Festo::new();
    let s: Vec<bool> = (0..9).map(|i| b(&p, i)).collect();
    assert_eq!(
        s,
        [true, false, false, false, true, true, false, true, false]
    );
    assert_eq!(p.quantity(0), 3.0);
}

/// One workpiece through the whole sequence, with the exact times.
#[test]
fn one_workpiece_delivered() {
    let mut p = Festo::new();
    on(&mut p, EJECT_OUT, true);
    run(&mut p, 494);
    assert!(!b(&p, 1));
    run(&mut p, 1);
    assert!(b(&p, 1) && !b(&p, 5), "front, slot empty");
    on(&mut p, ARM_TO_MAG, true);
    run(&mut p, 990);
    assert!(b(&p, 3));
    on(&mut p, VAC_ON, true);
    run(&mut p, 299);
    assert!(!b(&p, 2));
    run(&mut p, 1);
    assert!(b(&p, 2));
    on(&mut p, EJECT_OUT, false);
    run(&mut p, 495);
    assert!(b(&p, 0));
    // the next workpiece fell into the slot
    assert!(b(&p, 5));
    assert_eq!(p.quantity(0), 2.0);
    on(&mut p, ARM_TO_MAG, false);
    on(&mut p, ARM_TO_NXT, true);
    run(&mut p, 1_000);
    assert!(b(&p, 4) && b(&p, 2));
    on(&mut p, VAC_ON, false);
    on(&mut p, VAC_OFF, true);
    run(&mut p, 20);
    // 300 ms of vacuum gone at 10x in 20 ms: 100 ms left, no longer held
    assert_eq!(p.quantity(1), 1.0);
    assert!(!b(&p, 2));
    assert_eq!(
        (p.quantity(2), p.quantity(5), p.quantity(6)),
        (0.0, 0.0, 0.0)
    );
}

#[test]
fn no_vacuum_without_a_workpiece_and_losing_it_on_the_way() {
    let mut p = Festo::new();
    on(&mut p, ARM_TO_MAG, true);
    run(&mut p, 1_000);
    on(&mut p, VAC_ON, true);
    run(&mut p, 1_000);
    assert!(!b(&p, 2));
    assert_eq!(p.quantity(4), 0.0);
    // now with a workpiece, then the vacuum switched off mid-swivel
    on(&mut p, EJECT_OUT, true);
    run(&mut p, 500);
    run(&mut p, 300);
    assert!(b(&p, 2));
    on(&mut p, ARM_TO_MAG, false);
    on(&mut p, ARM_TO_NXT, true);
    run(&mut p, 300);
    on(&mut p, VAC_ON, false);
    run(&mut p, 300);
    assert_eq!(p.quantity(2), 1.0);
}

#[test]
fn empty_magazine_and_a_jam() {
    let mut p = Festo::new();
    assert!(p.command("set", &[("stack", 0.0)]).is_ok());
    on(&mut p, EJECT_OUT, true);
    run(&mut p, 500);
    on(&mut p, EJECT_OUT, false);
    run(&mut p, 500);
    // the workpiece is at the pick-up point, no other in the magazine
    assert!(!b(&p, 5));
    assert!(p.command("set", &[("stack", 1.0)]).is_ok());
    run(&mut p, 1);
    assert!(b(&p, 5));
    on(&mut p, EJECT_OUT, true);
    run(&mut p, 500);
    assert_eq!(p.quantity(5), 1.0);
    assert!(!b(&p, 1));
}

#[test]
fn parameters_and_conflicts() {
    let mut p = Festo::new();
    on(&mut p, ARM_TO_MAG, true);
    on(&mut p, ARM_TO_NXT, true);
    on(&mut p, VAC_ON, true);
    on(&mut p, VAC_OFF, true);
    run(&mut p, 10);
    assert_eq!(p.quantity(6), 20.0);
    assert!(p.command("set", &[("stack", -1.0)]).is_err());
    assert!(p.command("set", &[("swivel_time", 2.0)]).is_ok());
    assert!(p.command("set", &[("colour", 2.0)]).is_err());
    assert!(p.command("go", &[]).is_err());
    on(&mut p, START + 1, false);
    assert!(!b(&p, START + 1));
}
