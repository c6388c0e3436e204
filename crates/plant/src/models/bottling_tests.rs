use super::*;

const A_AVANS: usize = 11;
const A_RETRAGERE: usize = 12;
const B_AVANS: usize = 13;
const B_RETRAGERE: usize = 14;
const C_AVANS: usize = 15;
const C_RETRAGERE: usize = 16;

fn run(p: &mut Bottling, ms: i64) {
    let mut rng = Rng::new(1);
    for _ in 0..ms {
        p.step(1_000_000, &mut rng);
    }
}
fn on(p: &mut Bottling, s: usize, v: bool) {
    p.set(s, Value::Bool(v));
}
fn b(p: &Bottling, s: usize) -> bool {
    p.get(s).as_bool()
}

#[test]
fn signal_table_matches_the_indices() {
    assert_eq!(SIGNALS.get(BANDA).map(|s| s.name), Some("Banda"));
    assert_eq!(SIGNALS.get(A_AVANS).map(|s| s.name), Some("A_avans"));
    assert_eq!(
        SIGNALS.get(C_RETRAGERE).map(|s| s.name),
        Some("C_retragere")
    );
    assert_eq!(SIGNALS.get(INSURUBARE).map(|s| s.name), Some("Insurubare"));
}

#[test]
fn rest_state() {
    let p = Bottling::new();
    let s: Vec<bool> = (0..10).map(|i| b(&p, i)).collect();
    assert_eq!(
        s,
        [true, false, true, false, true, false, false, false, false, false]
    );
}

#[test]
fn photocells_see_bottles_at_the_stations() {
    let mut p = Bottling::new();
    on(&mut p, BANDA, true);
    // the bottle at 0.7 m reaches 0.97 m after 2.7 s
    run(&mut p, 2_699);
    assert!(!b(&p, 8));
    run(&mut p, 1);
    assert!(b(&p, 8) && !b(&p, 9));
    // one pitch later both stations see a bottle at the same instant
    run(&mut p, 600);
    assert!(b(&p, 8));
    run(&mut p, 1);
    assert!(!b(&p, 8) && !b(&p, 9));
    run(&mut p, 2_398);
    assert!(!b(&p, 8) && !b(&p, 9));
    run(&mut p, 1);
    assert!(b(&p, 8) && b(&p, 9));
}

#[test]
fn a_bottle_filled_capped_and_good() {
    let mut p = Bottling::new();
    on(&mut p, BANDA, true);
    run(&mut p, 3_000);
    on(&mut p, BANDA, false);
    assert_eq!(p.quantity(7), 0.0);
    on(&mut p, A_AVANS, true);
    run(&mut p, 990);
    assert!(b(&p, 1));
    assert_eq!(p.quantity(7), 1.0);
    on(&mut p, A_AVANS, false);
    on(&mut p, A_RETRAGERE, true);
    // cap preparation: C to F6, B to F7 takes the cap, C back
    on(&mut p, C_AVANS, true);
    run(&mut p, 495);
    assert!(b(&p, 5));
    on(&mut p, B_AVANS, true);
    run(&mut p, 389);
    assert!(!b(&p, 6));
    run(&mut p, 1);
    assert!(b(&p, 6));
    on(&mut p, B_AVANS, false);
    assert!(p.b_cap && !p.c_cap);
    on(&mut p, C_AVANS, false);
    on(&mut p, C_RETRAGERE, true);
    run(&mut p, 500);
    assert!(b(&p, 4) && p.c_cap);
    // move the filled bottle to the capping station
    on(&mut p, BANDA, true);
    run(&mut p, 3_000);
    on(&mut p, BANDA, false);
    assert!(b(&p, 9));
    on(&mut p, B_AVANS, true);
    run(&mut p, 610);
    assert!(b(&p, 3));
    on(&mut p, INSURUBARE, true);
    run(&mut p, 1_499);
    assert!(!b(&p, 7));
    run(&mut p, 1);
    assert!(b(&p, 7));
    assert_eq!(p.quantity(8), 1.0);
    on(&mut p, INSURUBARE, false);
    on(&mut p, B_AVANS, false);
    on(&mut p, B_RETRAGERE, true);
    run(&mut p, 1_000);
    assert!(b(&p, 2) && !b(&p, 7));
    on(&mut p, BANDA, true);
    run(&mut p, 8_000);
    assert_eq!(p.quantity(0), 1.0);
    assert_eq!(p.quantity(5), 0.0);
}

#[test]
fn spills_crashes_and_lost_caps() {
    let mut p = Bottling::new();
    on(&mut p, A_AVANS, true);
    run(&mut p, 1_000);
    assert_eq!(p.quantity(3), 1.0);
    on(&mut p, C_AVANS, true);
    run(&mut p, 500);
    on(&mut p, B_AVANS, true);
    run(&mut p, 1_000);
    // B went past F7 while C stood under it
    assert_eq!(p.quantity(5), 1.0);
    // it took the cap on the way and lost it: no bottle below
    assert_eq!(p.quantity(4), 1.0);
}

#[test]
fn random_spacing_and_parameters() {
    let mut p = Bottling::new();
    assert!(p.command("set", &[("random", 1.0)]).is_ok());
    on(&mut p, BANDA, true);
    run(&mut p, 60_000);
    let xs: Vec<i64> = p.bottles.iter().map(|b| b.x).collect();
    assert!(
        xs.windows(2)
            .all(|w| w[0] - w[1] >= 150_000 && w[0] - w[1] <= 450_000),
        "{xs:?}"
    );
    assert!(xs.windows(2).any(|w| w[0] - w[1] != PITCH));
    assert!(p.command("set", &[("speed", -1.0)]).is_err());
    assert!(p.command("set", &[("colour", 1.0)]).is_err());
    assert!(p.command("fill", &[]).is_err());
}
