//! `automat plant NAME --modbus-server [ADDR:]PORT`: one of the virtual
//! plants in real time as a Modbus TCP device, so any PLC (this one,
//! OpenPLC, CODESYS) can control it. The map is printed first
//! (`--map` prints it alone); `automat-fieldbus::plant` documents it.

use crate::Outcome;
use automat_fieldbus::plant::{self, PlantDevice};
use automat_fieldbus::server;
use clap::Args;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

/// Run a virtual plant as a Modbus TCP device (docs/modbus.md): its
/// sensors as discrete inputs and input registers, its actuators as coils
/// and holding registers, in real time until Ctrl-C.
#[derive(Args)]
pub struct PlantArgs {
    /// The plant model (`crane`, `capping`, …; see crates/plant/README.md).
    #[arg(value_name = "NAME")]
    name: String,
    /// Serve it on 127.0.0.1:PORT or ADDR:PORT.
    #[arg(long, value_name = "[ADDR:]PORT", required_unless_present = "map")]
    modbus_server: Option<String>,
    /// Print the Modbus map and exit.
    #[arg(long)]
    map: bool,
    /// The seed of the plant's random generator.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// A model parameter, as `[plant.params]` gives it (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    params: Vec<String>,
    /// Plant time runs this many times faster than wall time.
    #[arg(long, default_value_t = 1.0)]
    speed: f64,
    /// Stop after this long of wall time (`30s`) instead of at Ctrl-C;
    /// the plant's quantities are printed at the end.
    #[arg(long, value_name = "TIME", value_parser = automat_runtime::timearg::parse_duration)]
    duration: Option<i64>,
}

fn bad(msg: impl std::fmt::Display) -> Outcome {
    eprintln!("error: {msg}");
    Outcome::BadInput
}

pub fn run(args: &PlantArgs) -> Outcome {
    let Some(mut model) = automat_plant::models::by_name(&args.name) else {
        return bad(format!(
            "unknown plant model `{}` (known models: {})",
            args.name,
            automat_plant::models::NAMES.join(", ")
        ));
    };
    for p in &args.params {
        let Some((k, v)) = p.split_once('=') else {
            return bad(format!("--set {p}: expected KEY=VALUE"));
        };
        let Ok(v) = v.trim().parse::<f64>() else {
            return bad(format!("--set {p}: `{v}` is not a number"));
        };
        if let Err(e) = model.command("set", &[(k.trim(), v)]) {
            return bad(format!("--set {p}: {e}"));
        }
    }
    if !(args.speed.is_finite() && args.speed > 0.0) {
        return bad("--speed must be a number greater than 0");
    }
    let dev = Arc::new(PlantDevice::new(model.as_ref()));
    print!("{}", dev.map.describe(model.as_ref()));
    let Some(addr) = &args.modbus_server else {
        return Outcome::Ok;
    };
    let addr = match server::parse_addr(addr) {
        Ok(a) => a,
        Err(e) => return bad(format!("--modbus-server: {e}")),
    };
    let options = server::Options::new(addr);
    // A plant's actuators are written over Modbus: the same rule as a PLC.
    if let Some(why) = options.open_to_writes(false) {
        return bad(format!(
            "--modbus-server: {why}: serve a plant on 127.0.0.1 (or a tunnel to it) only"
        ));
    }
    let srv = match server::start(Arc::clone(&dev) as Arc<dyn server::Device>, options) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    eprintln!(
        "automat: plant {} as a Modbus TCP device on {}; Ctrl-C stops",
        args.name, srv.addr
    );
    let stop = Arc::new(AtomicBool::new(false));
    crate::cmd_run::stop_on_signals(&stop);
    let duration = args
        .duration
        .map(|ns| std::time::Duration::from_nanos(ns.max(0) as u64));
    plant::run(model.as_mut(), &dev, args.seed, args.speed, &stop, duration);
    drop(srv);
    for (i, q) in model.quantities().iter().enumerate() {
        println!("plant.{} = {}", q.name, model.quantity(i));
    }
    Outcome::Ok
}
