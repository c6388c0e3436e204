use super::*;
use automat_iec::Elementary as E;
use automat_plant::models::crane::Crane;
use automat_runtime::PlaceType;

/// The crane's nine signals bound to bits 0..8 of bytes 0 and 1.
fn crane_sim() -> Sim {
    let bindings = (0..9)
        .map(|i| Binding {
            signal: i,
            path: format!("s{i}"),
            place: Place {
                offset: (i / 8) as u32,
                bit: Some((i % 8) as u8),
                ty: PlaceType::Elementary(E::Bool),
                slc_bit: false,
            },
        })
        .collect();
    Sim::new(Box::new(Crane::new()), bindings, 1)
}

fn bit(img: &[u8], i: usize) -> bool {
    img[i / 8] >> (i % 8) & 1 != 0
}

#[test]
fn sensors_written_actuators_read_model_stepped() {
    let mut sim = crane_sim();
    let mut img = [0u8; 2];
    sim.sync(0, &mut img);
    // l1 and l3 at rest
    assert_eq!(
        (0..5).map(|i| bit(&img, i)).collect::<Vec<_>>(),
        [false, true, false, true, false]
    );
    img[0] |= 1 << 7; // M2S: up
    sim.sync(10_000_000, &mut img);
    assert_eq!(sim.plant().quantity(1), 0.01);
    // l1 stays on within 5 cm of the bottom
    assert!(bit(&img, 1));
    // 5 ms remainder waits: the model is at 15 ms only after a sync at >= 15 ms
    sim.sync(15_500_000, &mut img);
    assert_eq!(sim.plant().quantity(1), 0.015);
}

#[test]
fn actions_in_time_order_and_overrides() {
    let mut sim = crane_sim();
    let mut img = [0u8; 2];
    sim.schedule(
        20,
        Action::Set {
            signal: 0,
            value: Value::Bool(false),
        },
    );
    sim.schedule(
        10,
        Action::Set {
            signal: 0,
            value: Value::Bool(true),
        },
    );
    sim.schedule(
        10,
        Action::Stuck {
            signal: 1,
            value: Value::Bool(false),
        },
    );
    sim.sync(0, &mut img);
    assert!(!bit(&img, 0));
    sim.sync(10, &mut img);
    assert!(bit(&img, 0), "Pornire pressed at 10");
    assert!(!bit(&img, 1), "l1 stuck at FALSE");
    sim.sync(20, &mut img);
    assert!(!bit(&img, 0), "Pornire released at 20");
    // a stuck actuator: the PLC says up, the model sees off
    sim.schedule(
        30,
        Action::Stuck {
            signal: 7,
            value: Value::Bool(false),
        },
    );
    img[0] |= 1 << 7;
    sim.sync(30, &mut img);
    sim.sync(1_000_000_000, &mut img);
    assert_eq!(sim.plant().quantity(1), 0.0);
    sim.schedule(0, Action::Unstick { signal: 7 });
    sim.sync(1_000_000_001, &mut img);
    sim.sync(1_100_000_000, &mut img);
    assert_eq!(sim.plant().quantity(1), 0.1);
    sim.schedule(
        0,
        Action::Command {
            name: "jump".into(),
            args: vec![],
        },
    );
    sim.sync(1_200_000_000, &mut img);
    assert_eq!(sim.errors.len(), 1);
    assert_eq!(sim.errors[0].0, 1_200_000_000);
}

#[test]
fn after_a_fault_the_model_sees_every_actuator_off() {
    let mut sim = crane_sim();
    let mut img = [0u8; 2];
    img[0] |= 1 << 7; // M2S: up, in the variable bound by name
    sim.sync(0, &mut img);
    sim.sync(100_000_000, &mut img);
    assert_eq!(sim.plant().quantity(1), 0.1);
    assert!(!sim.halted());
    // The runtime's safe state cleared the bound variable.
    let mut safe = img;
    safe[0] &= !(1 << 7);
    sim.safe_state(&safe);
    assert!(sim.halted());
    assert_eq!(sim.plant().get(7), Value::Bool(false));
    // The variable still says up; the model stays where it stopped.
    sim.sync(200_000_000, &mut img);
    assert!(bit(&img, 7));
    assert_eq!(sim.plant().quantity(1), 0.1);
    assert_eq!(sim.plant().get(7), Value::Bool(false));
}
