//! What the figures were measured on: CPU model, cores, load and build.

use std::collections::BTreeSet;

use serde::Serialize;

/// The machine and build a run was measured on.
#[derive(Clone, Debug, Serialize)]
pub struct Machine {
    /// CPU model name (`model name` in /proc/cpuinfo), or "unknown".
    pub cpu: String,
    /// Logical CPUs this process may use (`std::thread::available_parallelism`).
    pub logical_cores: usize,
    /// Distinct (physical id, core id) pairs in /proc/cpuinfo, if it lists them.
    pub physical_cores: Option<usize>,
    /// Operating system and architecture, e.g. `linux x86_64`.
    pub os: String,
    /// 1-minute load average when the run started (/proc/loadavg): above `logical_cores` means
    /// other work shared the CPU and the figures are pessimistic.
    pub load_average: Option<f64>,
    /// `release` or `debug`; debug builds are unoptimised and their figures meaningless.
    pub build: &'static str,
    /// swell's version.
    pub swell_version: &'static str,
}

impl Machine {
    /// Reads the machine's description (Linux files; elsewhere the fields are "unknown" or `None`).
    pub fn detect() -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let (cpu, physical_cores) = parse_cpuinfo(&cpuinfo);
        let load_average = std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|s| s.split_whitespace().next().and_then(|v| v.parse().ok()));
        Self {
            cpu: cpu.unwrap_or_else(|| "unknown".into()),
            logical_cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            physical_cores,
            os: format!("{} {}", std::env::consts::OS, std::env::consts::ARCH),
            load_average,
            build: if cfg!(debug_assertions) { "debug" } else { "release" },
            swell_version: env!("CARGO_PKG_VERSION"),
        }
    }

    /// One line for reports, e.g. `Intel Xeon, 2 logical cores (2 physical), linux x86_64, load 1.2`.
    pub fn summary(&self) -> String {
        let mut s = format!("{}, {} logical cores", self.cpu, self.logical_cores);
        if let Some(p) = self.physical_cores {
            s += &format!(" ({p} physical)");
        }
        s += &format!(", {}, {} build of swell {}", self.os, self.build, self.swell_version);
        if let Some(l) = self.load_average {
            s += &format!(", load average {l:.1} at start");
        }
        s
    }
}

/// The first `model name` and the number of distinct (physical id, core id) pairs.
fn parse_cpuinfo(text: &str) -> (Option<String>, Option<usize>) {
    let mut model = None;
    let mut cores = BTreeSet::new();
    let mut physical = None::<String>;
    for line in text.lines() {
        let Some((key, value)) = line.split_once(':') else { continue };
        let (key, value) = (key.trim(), value.trim());
        match key {
            "model name" if model.is_none() => model = Some(value.to_string()),
            "physical id" => physical = Some(value.to_string()),
            "core id" => {
                cores.insert((physical.clone().unwrap_or_default(), value.to_string()));
            }
            _ => {}
        }
    }
    (model, (!cores.is_empty()).then_some(cores.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_physical_cores_across_sockets_and_hyperthreads() {
        let text = "processor\t: 0\nmodel name\t: Intel(R) Core(TM) i7-7700K CPU @ 4.20GHz\nphysical id\t: 0\ncore id\t: 0\n\n\
                    processor\t: 1\nmodel name\t: Intel(R) Core(TM) i7-7700K CPU @ 4.20GHz\nphysical id\t: 0\ncore id\t: 0\n\n\
                    processor\t: 2\nmodel name\t: x\nphysical id\t: 0\ncore id\t: 1\n\n\
                    processor\t: 3\nmodel name\t: x\nphysical id\t: 1\ncore id\t: 1\n";
        let (model, cores) = parse_cpuinfo(text);
        assert_eq!(model.as_deref(), Some("Intel(R) Core(TM) i7-7700K CPU @ 4.20GHz"));
        assert_eq!(cores, Some(3));
        assert_eq!(parse_cpuinfo(""), (None, None));
    }
}
