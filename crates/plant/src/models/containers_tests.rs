use super::*;

const BANDA_2: usize = 7;
const D_AVANS: usize = 8;
const D_RETRAGERE: usize = 9;
const E_AVANS: usize = 10;
const E_RETRAGERE: usize = 11;

fn run(p: &mut Containers, ms: i64) {
    let mut rng = Rng::new(1);
    for _ in 0..ms {
        p.step(1_000_000, &mut rng);
    }
}
fn on(p: &mut Containers, s: usize, v: bool) {
    p.set(s, Value::Bool(v));
}
fn b(p: &Containers, s: usize) -> bool {
    p.get(s).as_bool()
}

#[test]
fn signal_table_matches_the_indices() {
    assert_eq!(SIGNALS.get(BANDA_1).map(|s| s.name), Some("Banda_1"));
    assert_eq!(
        SIGNALS.get(E_RETRAGERE).map(|s| s.name),
        Some("E_retragere")
    );
    assert_eq!(SIGNALS.get(VALVA_A).map(|s| s.name), Some("Valva_A"));
    assert_eq!(QUANTITIES.get(16).map(|q| q.name), Some("C_pos"));
}

#[test]
fn initial_state() {
    let p = Containers::new();
    let s: Vec<bool> = (0..6).map(|i| b(&p, i)).collect();
    assert_eq!(s, [false, false, false, false, true, true]);
    assert_eq!(
        (p.quantity(16), p.quantity(15), p.quantity(14)),
        (-0.5, -1.0, -1.5)
    );
}

#[test]
fn belt_one_brings_c_to_position_one_and_stops_it_there() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_449);
    assert!(!b(&p, 0));
    run(&mut p, 1);
    assert!(b(&p, 0));
    assert_eq!(p.quantity(16), -0.01);
    run(&mut p, 1_000);
    assert_eq!(p.quantity(15), -0.31);
    run(&mut p, 1_000);
    // C stands at the end stop, B queues one width behind it
    assert_eq!(p.quantity(16), 0.0);
    assert_eq!(p.quantity(15), -0.2);
}

#[test]
fn the_carriage_moves_the_containers_one_pitch() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    on(&mut p, BANDA_1, false);
    on(&mut p, D_AVANS, true);
    run(&mut p, 966);
    assert!(!b(&p, 1) && !b(&p, 5));
    run(&mut p, 1);
    assert!(b(&p, 1));
    assert_eq!(p.quantity(16), 0.2901);
    assert_eq!(p.quantity(13), 0.2901);
    run(&mut p, 1_100);
    // D at its end: C at position 3
    assert!(b(&p, 2));
    assert_eq!(p.quantity(16), 0.6);
    on(&mut p, D_AVANS, false);
    on(&mut p, D_RETRAGERE, true);
    run(&mut p, 2_000);
    assert!(b(&p, 5) && b(&p, 0));
    assert_eq!(p.quantity(12), 0.0);
}

#[test]
fn valves_fill_the_container_below_or_spill() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    on(&mut p, VALVA_A, true);
    on(&mut p, VALVA_A + 1, true);
    run(&mut p, 5_000);
    assert_eq!(p.quantity(6), 5.0);
    assert_eq!(p.quantity(9), 5.0);
}

#[test]
fn e_ejects_the_container_at_position_one() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    on(&mut p, BANDA_1, false);
    on(&mut p, E_AVANS, true);
    run(&mut p, 989);
    assert!(!b(&p, 3) && !b(&p, 4));
    assert_eq!(p.quantity(10), 0.0);
    run(&mut p, 1);
    assert!(b(&p, 3));
    assert!(!b(&p, 0));
    assert_eq!(p.quantity(10), 1.0);
    // empty: not filled as the table says
    assert_eq!(p.quantity(11), 0.0);
    assert_eq!(p.quantity(16), -1.0);
    on(&mut p, E_AVANS, false);
    on(&mut p, E_RETRAGERE, true);
    run(&mut p, 1_000);
    assert!(b(&p, 4));
}

#[test]
fn a_correctly_filled_container_counts_as_good() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    // C at position 1 gets 8 l of A; fake B and C liquids straight in
    on(&mut p, VALVA_A, true);
    run(&mut p, 8_000);
    on(&mut p, VALVA_A, false);
    if let Some(c) = p.items.iter_mut().find(|c| c.id == 2) {
        c.ul[1] = 5_000_000;
        c.ul[2] = 3_040_000;
    }
    on(&mut p, BANDA_2, true);
    on(&mut p, E_AVANS, true);
    run(&mut p, 1_000);
    assert_eq!((p.quantity(10), p.quantity(11)), (1.0, 1.0));
}

#[test]
fn collisions_are_counted_once_each() {
    let mut p = Containers::new();
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    on(&mut p, BANDA_1, false);
    // D moves with E out
    on(&mut p, E_AVANS, true);
    run(&mut p, 500);
    on(&mut p, D_AVANS, true);
    run(&mut p, 500);
    assert_eq!(p.quantity(12), 1.0);
}

#[test]
fn the_carriage_pushing_a_container_against_belt_one_is_a_crash() {
    let mut p = Containers::new();
    on(&mut p, D_AVANS, true);
    run(&mut p, 1_000);
    on(&mut p, D_AVANS, false);
    on(&mut p, BANDA_1, true);
    run(&mut p, 2_500);
    on(&mut p, BANDA_1, false);
    on(&mut p, D_RETRAGERE, true);
    run(&mut p, 1_000);
    assert_eq!(p.quantity(12), 1.0);
    assert_eq!(p.quantity(16), -0.01);
}

#[test]
fn parameters_and_batches() {
    let mut p = Containers::new();
    assert!(p.command("set", &[("belt_speed", 0.5)]).is_ok());
    on(&mut p, BANDA_1, true);
    run(&mut p, 1_000);
    assert!(b(&p, 0));
    assert!(p.command("set", &[("flow", 0.0)]).is_err());
    assert!(p
        .command("set", &[("speed", 1.0)])
        .is_err_and(|e| e.contains("`speed`")));
    assert!(p.command("batch", &[]).is_ok());
    assert_eq!(p.items.len(), 3);
    assert!(p.command("explode", &[]).is_err());
}
