use super::*;

fn nm(m: f64) -> i64 {
    (m * 1e9).round() as i64
}

const A1: usize = 3;
const B1: usize = 5;
const C0: usize = 6;
const C1: usize = 7;
const BANDA_1: usize = 10;
const B_AVANSAT: usize = 15;
const C_RIDICARE: usize = 17;

fn run(s: &mut Sorter, ms: i64) {
    let mut rng = Rng::new(1);
    for _ in 0..ms {
        s.step(1_000_000, &mut rng);
    }
}

fn on(s: &mut Sorter, signal: usize, v: bool) {
    s.set(signal, Value::Bool(v));
}

fn b(s: &Sorter, signal: usize) -> bool {
    s.get(signal).as_bool()
}

/// One package of `weight` run onto the platform: belt 0 to Foto_0, then
/// both belts until it is on the platform. Returns the sorter.
fn on_platform(weight: f64) -> Sorter {
    let mut s = Sorter::new();
    assert_eq!(s.command("package", &[("weight", weight)]), Ok(()));
    on(&mut s, BANDA_0, true);
    run(&mut s, 4501);
    assert!(b(&s, FOTO_0));
    on(&mut s, BANDA_1, true);
    // from 0.9 m to 1.95 m at 0.2 m/s
    run(&mut s, 5249);
    assert!(!b(&s, FOTO_1));
    run(&mut s, 1);
    assert!(b(&s, FOTO_1) && !b(&s, FOTO_0));
    on(&mut s, BANDA_0, false);
    on(&mut s, BANDA_1, false);
    s
}

#[test]
fn a_package_reaches_the_scale_after_4_5_seconds_and_reads_its_weight() {
    let mut s = Sorter::new();
    assert_eq!(s.command("package", &[("weight", 20.0)]), Ok(()));
    assert_eq!(s.get(TRADUCTOR), Value::Int(819));
    on(&mut s, BANDA_0, true);
    run(&mut s, 4500);
    assert!(!b(&s, FOTO_0));
    run(&mut s, 1);
    assert!(b(&s, FOTO_0));
    on(&mut s, BANDA_0, false);
    // 0.5 s on the weighing section: settled; 819 + 20 * 32.76 = 1474.2
    assert_eq!(s.quantity(5), 20.0);
    assert_eq!(s.get(TRADUCTOR), Value::Int(1474));
    run(&mut s, 10_000);
    assert!(b(&s, FOTO_0), "belt 0 stopped: the package stays");
}

#[test]
fn the_scale_settles_linearly_in_200_ms() {
    let mut s = Sorter::new();
    assert_eq!(s.command("package", &[("weight", 70.0)]), Ok(()));
    on(&mut s, BANDA_0, true);
    // the centre reaches 0.8 m after 4001 steps; 100 ms later: half
    run(&mut s, 4101);
    assert!((s.quantity(5) - 35.0).abs() < 1e-9, "{}", s.quantity(5));
    run(&mut s, 100);
    assert_eq!(s.quantity(5), 70.0);
    assert_eq!(s.get(TRADUCTOR), Value::Int(3112)); // 819 + 2293.2
}

#[test]
fn a_small_package_is_lifted_and_pushed_onto_belt_2() {
    let mut s = on_platform(20.0);
    assert!(b(&s, C0));
    on(&mut s, C_RIDICARE, true);
    run(&mut s, 1484);
    assert!(!b(&s, C1) && !b(&s, FOTO_1));
    run(&mut s, 1);
    assert!(b(&s, C1));
    on(&mut s, A_AVANSAT, true);
    run(&mut s, 791);
    assert_eq!(s.quantity(2), 0.0);
    run(&mut s, 1);
    assert!(b(&s, A1));
    assert_eq!(
        (s.quantity(2), s.quantity(3), s.quantity(4)),
        (1.0, 0.0, 0.0)
    );
    assert_eq!(s.quantity(1), 0.0);
}

#[test]
fn a_small_package_pushed_by_b_is_missorted() {
    let mut s = on_platform(20.0);
    on(&mut s, C_RIDICARE, true);
    run(&mut s, 1500);
    on(&mut s, B_AVANSAT, true);
    run(&mut s, 800);
    assert!(b(&s, B1));
    assert_eq!((s.quantity(3), s.quantity(4)), (1.0, 1.0));
}

#[test]
fn pushing_below_the_top_does_nothing() {
    let mut s = on_platform(70.0);
    on(&mut s, B_AVANSAT, true);
    run(&mut s, 1000);
    assert_eq!(s.quantity(3), 0.0);
    assert!(b(&s, FOTO_1));
}

#[test]
fn the_next_package_waits_at_1_8_m_while_the_platform_is_busy() {
    let mut s = Sorter::new();
    assert_eq!(
        s.command("package", &[("weight", 20.0), ("count", 2.0)]),
        Ok(())
    );
    on(&mut s, BANDA_0, true);
    on(&mut s, BANDA_1, true);
    // the first goes on at 0 s, the second 1.25 s later (0.25 m behind)
    run(&mut s, 30_000);
    assert_eq!((s.quantity(0), s.quantity(1)), (0.0, 2.0));
    assert!(b(&s, FOTO_1));
    assert_eq!(s.line.first().map(|k| k.p), Some(WAIT_AT));
}

#[test]
fn packages_keep_their_gap_and_enter_when_the_infeed_is_clear() {
    let mut s = Sorter::new();
    assert_eq!(
        s.command("package", &[("weight", 50.0), ("count", 3.0)]),
        Ok(())
    );
    on(&mut s, BANDA_0, true);
    run(&mut s, 1);
    assert_eq!(s.quantity(0), 2.0);
    // 0.25 m at 0.2 m/s: the second one goes on 1.25 s later
    run(&mut s, 1250);
    assert_eq!(s.quantity(0), 1.0);
    run(&mut s, 10_000);
    let ps: Vec<i64> = s.line.iter().map(|k| k.p).collect();
    // the first one crossed onto belt 1 (stopped) by one step: 1.1002 m;
    // the others queue behind it at the pitch
    assert_eq!(ps, [nm(1.1002), nm(0.8502), nm(0.6002)]);
}

#[test]
fn remove_takes_the_package_off_the_scale() {
    let mut s = Sorter::new();
    assert!(s
        .command("remove", &[])
        .is_err_and(|e| e.contains("no package on the scale")));
    assert_eq!(s.command("package", &[("weight", 2.0)]), Ok(()));
    on(&mut s, BANDA_0, true);
    run(&mut s, 4501);
    on(&mut s, BANDA_0, false);
    assert_eq!(s.command("remove", &[]), Ok(()));
    assert!(!b(&s, FOTO_0));
    assert_eq!((s.quantity(1), s.quantity(8)), (0.0, 1.0));
}

#[test]
fn both_coils_conflict_and_bad_commands() {
    let mut s = Sorter::new();
    on(&mut s, C_RIDICARE, true);
    on(&mut s, C_COBORARE, true);
    run(&mut s, 40);
    assert_eq!((s.quantity(6), s.quantity(7)), (0.0, 40.0));
    assert!(s
        .command("package", &[("weight", 120.0)])
        .is_err_and(|e| e.contains("0..100")));
    assert!(s
        .command("package", &[("count", 1.0)])
        .is_err_and(|e| e.contains("needs `weight")));
    assert!(s
        .command("set", &[("size", 1.0)])
        .is_err_and(|e| e.contains("unknown parameter `size`")));
    assert!(s
        .command("lift", &[])
        .is_err_and(|e| e.contains("no command `lift`")));
    assert_eq!(is_small(4.9), None);
    assert_eq!((is_small(40.0), is_small(40.5)), (Some(true), Some(false)));
}

const A_RETRAS: usize = 14;
const C_COBORARE_: usize = 18;
const BANDA_2: usize = 11;

#[test]
fn lowering_onto_an_extended_pusher_is_one_collision() {
    let mut s = on_platform(20.0);
    on(&mut s, C_RIDICARE, true);
    run(&mut s, 1500);
    on(&mut s, A_AVANSAT, true);
    run(&mut s, 800);
    assert!(b(&s, A1));
    // the platform goes down with A still out over the shaft
    on(&mut s, C_RIDICARE, false);
    on(&mut s, C_COBORARE_, true);
    run(&mut s, 1);
    assert_eq!(s.quantity(9), 1.0);
    run(&mut s, 300);
    assert_eq!(s.quantity(9), 1.0, "one lowering, one collision");
    // stopped and lowered again: a second one
    on(&mut s, C_COBORARE_, false);
    run(&mut s, 10);
    on(&mut s, C_COBORARE_, true);
    run(&mut s, 1);
    assert_eq!(s.quantity(9), 2.0);
    // A retracted (0.8 s): lowering the rest of the way is no collision
    on(&mut s, C_COBORARE_, false);
    on(&mut s, A_AVANSAT, false);
    on(&mut s, A_RETRAS, true);
    run(&mut s, 800);
    on(&mut s, C_COBORARE_, true);
    run(&mut s, 1500);
    assert!(b(&s, C0));
    assert_eq!(s.quantity(9), 2.0);
}

/// Pushes one package of `weight` off with A (small) onto belt 2, the
/// platform back down and A back.
fn push_small(s: &mut Sorter) {
    assert_eq!(s.command("package", &[("weight", 20.0)]), Ok(()));
    on(s, BANDA_0, true);
    on(s, BANDA_1, true);
    run(s, 9751);
    assert!(b(s, FOTO_1));
    on(s, C_RIDICARE, true);
    run(s, 1500);
    on(s, C_RIDICARE, false);
    on(s, A_AVANSAT, true);
    run(s, 800);
    on(s, A_AVANSAT, false);
    on(s, A_RETRAS, true);
    run(s, 800);
    on(s, A_RETRAS, false);
    on(s, C_COBORARE_, true);
    run(s, 1500);
    on(s, C_COBORARE_, false);
}

#[test]
fn belt_2_must_run_to_clear_its_head() {
    // belt 2 stopped: the second small package lands on the first
    let mut s = Sorter::new();
    push_small(&mut s);
    assert_eq!((s.quantity(2), s.quantity(10)), (1.0, 0.0));
    push_small(&mut s);
    assert_eq!((s.quantity(2), s.quantity(10)), (2.0, 1.0));
    assert_eq!(s.quantity(9), 0.0);
    // belt 2 running: 1.25 s clears the head, every package lands free
    let mut s = Sorter::new();
    on(&mut s, BANDA_2, true);
    push_small(&mut s);
    push_small(&mut s);
    assert_eq!((s.quantity(2), s.quantity(10)), (2.0, 0.0));
}
