//! Real-time mode for Linux deployments (`--realtime`, `[runtime]
//! realtime = true`): the process's memory locked (no page fault in a
//! scan), the scan thread at SCHED_FIFO with a priority, optionally pinned
//! to CPUs. Entered on the thread that runs the scans, before the first
//! one; every refusal of the system is an error that says why and what
//! gives the right, never a silent fallback to normal scheduling.

/// What the real-time mode asks of the system.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Realtime {
    /// SCHED_FIFO priority, 1..=99.
    pub priority: i32,
    /// CPUs the scan thread may run on (empty: any).
    pub cpus: Vec<usize>,
}

/// The default SCHED_FIFO priority: above the kernel's threaded interrupt
/// handlers' default (50), below the watchdog and migration threads (99).
pub const DEFAULT_PRIORITY: i32 = 80;

impl Default for Realtime {
    fn default() -> Self {
        Realtime {
            priority: DEFAULT_PRIORITY,
            cpus: Vec::new(),
        }
    }
}

impl Realtime {
    /// Checks the values before anything is asked of the system.
    pub fn validate(&self) -> Result<(), String> {
        if !(1..=99).contains(&self.priority) {
            return Err(format!(
                "real-time priority {} is out of range: SCHED_FIFO priorities are 1 to 99",
                self.priority
            ));
        }
        if let Some(c) = self.cpus.iter().find(|&&c| c >= 1024) {
            return Err(format!("CPU {c} does not exist (CPUs are numbered from 0)"));
        }
        Ok(())
    }

    /// `SCHED_FIFO priority 80, memory locked, on CPUs 1`: for the note at start.
    pub fn describe(&self) -> String {
        let mut s = format!("SCHED_FIFO priority {}, memory locked", self.priority);
        if !self.cpus.is_empty() {
            let cpus: Vec<String> = self.cpus.iter().map(|c| c.to_string()).collect();
            s.push_str(&format!(", on CPU {}", cpus.join(",")));
        }
        s
    }
}

/// Parses `--cpus 1` / `"0,2-3"`: CPU numbers and ranges.
pub fn parse_cpus(text: &str) -> Result<Vec<usize>, String> {
    let mut out = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let bad = || format!("`{part}` is not a CPU number or range (such as `1` or `0,2-3`)");
        match part.split_once('-') {
            Some((a, b)) => {
                let a: usize = a.trim().parse().map_err(|_| bad())?;
                let b: usize = b.trim().parse().map_err(|_| bad())?;
                if a > b || b >= 1024 {
                    return Err(bad());
                }
                out.extend(a..=b);
            }
            None => out.push(part.parse().map_err(|_| bad())?),
        }
    }
    if out.is_empty() {
        return Err("no CPU given (such as `1` or `0,2-3`)".into());
    }
    out.sort_unstable();
    out.dedup();
    Ok(out)
}

/// Enters the real-time mode on the calling thread; `Err` says what the
/// system refused and how to grant it.
pub fn enter(rt: &Realtime) -> Result<(), String> {
    rt.validate()?;
    imp::enter(rt)
}

/// Raises the calling thread one SCHED_FIFO priority above the one it
/// inherited, when it inherited a real-time policy (the watchdog's timer
/// thread, started by the scan thread). Nothing otherwise.
pub fn above_inherited() {
    imp::above_inherited();
}

/// A note for the user when the kernel is not PREEMPT_RT (or unknown).
pub fn kernel_note() -> Option<String> {
    let rt = std::fs::read_to_string("/sys/kernel/realtime").is_ok_and(|s| s.trim() == "1");
    (!rt).then(|| {
        "the kernel is not PREEMPT_RT: SCHED_FIFO keeps other programs off the scan thread, \
         but the kernel itself can still delay a scan (--stats shows the jitter)"
            .to_string()
    })
}

#[cfg(target_os = "linux")]
mod imp {
    use super::Realtime;

    fn errno_text() -> String {
        std::io::Error::last_os_error().to_string()
    }

    pub fn enter(rt: &Realtime) -> Result<(), String> {
        // SAFETY: mlockall takes flags only and touches no Rust memory.
        if unsafe { libc::mlockall(libc::MCL_CURRENT | libc::MCL_FUTURE) } != 0 {
            let why = errno_text();
            return Err(format!(
                "real-time mode: cannot lock the process's memory (mlockall: {why}); \
                 it needs CAP_IPC_LOCK or a locked-memory limit as large as the process \
                 (`ulimit -l unlimited`; systemd: LimitMEMLOCK=infinity)"
            ));
        }
        prefault_stack();
        if !rt.cpus.is_empty() {
            // SAFETY: a zeroed cpu_set_t is a valid empty set; CPU_SET
            // indexes within it (cpus < 1024 = CPU_SETSIZE, validated).
            let mut set: libc::cpu_set_t = unsafe { std::mem::zeroed() };
            for &c in &rt.cpus {
                unsafe { libc::CPU_SET(c, &mut set) };
            }
            // SAFETY: pid 0 is the calling thread; the set outlives the call.
            let r =
                unsafe { libc::sched_setaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &set) };
            if r != 0 {
                let why = errno_text();
                return Err(format!(
                    "real-time mode: cannot pin the scan thread to CPU {} (sched_setaffinity: {why}); \
                     the CPUs this process may use are {}",
                    rt.cpus
                        .iter()
                        .map(|c| c.to_string())
                        .collect::<Vec<_>>()
                        .join(","),
                    allowed_cpus()
                ));
            }
        }
        let param = libc::sched_param {
            sched_priority: rt.priority,
        };
        // SAFETY: the calling thread's own handle, a valid sched_param.
        let r =
            unsafe { libc::pthread_setschedparam(libc::pthread_self(), libc::SCHED_FIFO, &param) };
        if r != 0 {
            // pthread_setschedparam returns the error instead of setting errno.
            let why = std::io::Error::from_raw_os_error(r);
            let hint = if r == libc::EPERM {
                format!(
                    "run it as root, give the binary CAP_SYS_NICE (`setcap cap_sys_nice,cap_ipc_lock+ep automat`), \
                     or raise the real-time priority limit (`ulimit -r {p}`; systemd: LimitRTPRIO={p})",
                    p = rt.priority
                )
            } else {
                "the kernel refused the policy".to_string()
            };
            return Err(format!(
                "real-time mode: cannot run the scan thread at SCHED_FIFO priority {} \
                 (pthread_setschedparam: {why}); {hint}",
                rt.priority
            ));
        }
        Ok(())
    }

    pub fn above_inherited() {
        let mut policy = 0;
        // SAFETY: a zeroed sched_param is valid; both pointers are ours.
        let mut param: libc::sched_param = unsafe { std::mem::zeroed() };
        let me = unsafe { libc::pthread_self() };
        if unsafe { libc::pthread_getschedparam(me, &mut policy, &mut param) } != 0 {
            return;
        }
        if policy == libc::SCHED_FIFO && param.sched_priority < 99 {
            param.sched_priority += 1;
            // SAFETY: as above. A refusal leaves the inherited priority.
            let _ = unsafe { libc::pthread_setschedparam(me, libc::SCHED_FIFO, &param) };
        }
    }

    /// Touches a stack region once so that, locked, its pages are resident
    /// before the first scan.
    fn prefault_stack() {
        let mut buf = [0u8; 64 * 1024];
        for i in (0..buf.len()).step_by(4096) {
            // SAFETY: a volatile write into our own buffer.
            unsafe { std::ptr::write_volatile(&mut buf[i], 1) };
        }
        std::hint::black_box(&buf);
    }

    fn allowed_cpus() -> String {
        // SAFETY: as above; sched_getaffinity fills the set.
        let mut set: libc::cpu_set_t = unsafe { std::mem::zeroed() };
        let r =
            unsafe { libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set) };
        if r != 0 {
            return "unknown".into();
        }
        (0..1024usize)
            .filter(|&c| unsafe { libc::CPU_ISSET(c, &set) })
            .map(|c| c.to_string())
            .collect::<Vec<_>>()
            .join(",")
    }
}

#[cfg(not(target_os = "linux"))]
mod imp {
    use super::Realtime;

    pub fn enter(_rt: &Realtime) -> Result<(), String> {
        Err("real-time mode (--realtime) needs Linux (mlockall and SCHED_FIFO)".into())
    }

    pub fn above_inherited() {}
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cpu_lists_and_ranges() {
        assert_eq!(parse_cpus("1"), Ok(vec![1]));
        assert_eq!(parse_cpus("3, 0,2-3"), Ok(vec![0, 2, 3]));
        assert!(parse_cpus("").is_err());
        assert!(parse_cpus("a").unwrap_err().contains("`a` is not a CPU"));
        assert!(parse_cpus("3-1").is_err());
        assert!(parse_cpus("0-5000").is_err());
    }

    #[test]
    fn priorities_out_of_range_are_refused_before_the_system_is_asked() {
        let rt = Realtime {
            priority: 0,
            cpus: vec![],
        };
        assert!(enter(&rt).unwrap_err().contains("1 to 99"));
        let rt = Realtime {
            priority: 100,
            cpus: vec![],
        };
        assert!(rt.validate().is_err());
        assert_eq!(
            Realtime {
                priority: 70,
                cpus: vec![1, 3]
            }
            .describe(),
            "SCHED_FIFO priority 70, memory locked, on CPU 1,3"
        );
    }
}
