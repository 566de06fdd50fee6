//! `--shard auto`: the shard of a bake taken from a batch system's array-job variables.
//!
//! | system | index | count |
//! |---|---|---|
//! | Slurm job array (`sbatch --array=A-B[:S]`) | `(SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) / SLURM_ARRAY_TASK_STEP` | `SLURM_ARRAY_TASK_COUNT` |
//! | Kubernetes indexed job | `JOB_COMPLETION_INDEX` | `auto/N` or `SWELL_SHARD_COUNT` (the job's `completions`) |
//! | AWS Batch array job | `AWS_BATCH_JOB_ARRAY_INDEX` | `AWS_BATCH_JOB_ARRAY_SIZE` |
//!
//! Slurm numbers tasks from the first id of `--array` (`--array=1-16` gives ids 1 to 16), so the
//! index is counted from `SLURM_ARRAY_TASK_MIN` (0 when unset) in steps of
//! `SLURM_ARRAY_TASK_STEP` (1 when unset); arrays must be one range `A-B` or `A-B:S`, not a list.
//! A count written as `auto/N` (or `SWELL_SHARD_COUNT`) must agree with the system's own count
//! when both exist. Exactly one system's index variable must be set.
//!
//! [`resolve_shard`] is a pure function of the option's text and a variable lookup, so it is
//! tested without touching the process environment.

use super::frame_range::{Shard, MAX_SHARDS};
use crate::error::{Error, Result};

/// Environment variable giving the shard count where the batch system does not (Kubernetes), or
/// overriding nothing where it does (it must then agree). A whole number in [1, [`MAX_SHARDS`]].
pub const SHARD_COUNT_VAR: &str = "SWELL_SHARD_COUNT";

/// The shard a `--shard` option resolved to, and where it came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ResolvedShard {
    /// The shard to bake.
    pub shard: Shard,
    /// For `auto`: the batch system and the variables read, in words (printed on stderr);
    /// `None` for an explicit `I/N`.
    pub source: Option<String>,
}

/// One batch system's array-job variables.
struct ArraySystem {
    /// Name in messages.
    name: &'static str,
    /// The variable holding this task's index (or Slurm's task id).
    index_var: &'static str,
    /// The variable holding the number of tasks, if the system sets one.
    count_var: Option<&'static str>,
}

/// The systems `auto` knows, in the order they are looked for.
const SYSTEMS: [ArraySystem; 3] = [
    ArraySystem {
        name: "Slurm job array",
        index_var: "SLURM_ARRAY_TASK_ID",
        count_var: Some("SLURM_ARRAY_TASK_COUNT"),
    },
    ArraySystem { name: "Kubernetes indexed job", index_var: "JOB_COMPLETION_INDEX", count_var: None },
    ArraySystem {
        name: "AWS Batch array job",
        index_var: "AWS_BATCH_JOB_ARRAY_INDEX",
        count_var: Some("AWS_BATCH_JOB_ARRAY_SIZE"),
    },
];

/// Resolves a `--shard` value: `I/N` as [`Shard::parse`], `auto` or `auto/N` from the array-job
/// variables that `env` returns (`env(name)` is the variable's value, `None` when unset).
///
/// Errors name `key`, the variable, its value and the valid range; nothing is read but `env`.
pub fn resolve_shard(key: &str, s: &str, env: &dyn Fn(&str) -> Option<String>) -> Result<ResolvedShard> {
    let t = s.trim();
    let given_count = match t.strip_prefix("auto") {
        None => return Ok(ResolvedShard { shard: Shard::parse(key, s)?, source: None }),
        Some("") => None,
        Some(rest) => {
            let n = rest.strip_prefix('/').ok_or_else(|| {
                Error::invalid(key, format!("`{s}` is not I/N, auto or auto/N (e.g. 0/4, auto, auto/8)"))
            })?;
            Some(parse_count(&format!("{key} auto/N"), n.trim())?)
        }
    };
    let auto_key = format!("{key} auto");
    let set: Vec<&ArraySystem> = SYSTEMS.iter().filter(|sys| env(sys.index_var).is_some()).collect();
    let system = match set.as_slice() {
        [one] => *one,
        [] => {
            let vars: Vec<&str> = SYSTEMS.iter().map(|sys| sys.index_var).collect();
            return Err(Error::invalid(
                auto_key,
                format!(
                    "no array-job variable is set (looked for {}): run inside a Slurm job array, a Kubernetes \
                     indexed job or an AWS Batch array job, or give the shard as I/N",
                    vars.join(", ")
                ),
            ));
        }
        several => {
            let vars: Vec<String> =
                several.iter().map(|sys| format!("{} = {:?}", sys.index_var, env(sys.index_var).unwrap())).collect();
            return Err(Error::invalid(
                auto_key,
                format!("{} are all set, so the batch system is ambiguous: give the shard as I/N", vars.join(" and ")),
            ));
        }
    };

    // The count: the system's own, `auto/N` and SWELL_SHARD_COUNT, which must agree.
    let mut counts: Vec<(String, u32)> = Vec::new();
    if let Some(var) = system.count_var {
        if let Some(v) = env(var) {
            counts.push((format!("{var} = {v}"), parse_count(&format!("{auto_key}: {var}"), &v)?));
        }
    }
    if let Some(n) = given_count {
        counts.push((format!("{key} auto/{n}"), n));
    }
    if let Some(v) = env(SHARD_COUNT_VAR) {
        counts.push((format!("{SHARD_COUNT_VAR} = {v}"), parse_count(&format!("{auto_key}: {SHARD_COUNT_VAR}"), &v)?));
    }
    let Some((count_from, count)) = counts.first().cloned() else {
        let hint = match system.count_var {
            Some(var) => format!("{var} is not set"),
            None => "it does not say how many tasks there are".to_string(),
        };
        return Err(Error::invalid(
            auto_key,
            format!(
                "{} found ({} = {}) but {hint}: write --shard auto/N with N the number of tasks (for Kubernetes, \
                 spec.completions), or set {SHARD_COUNT_VAR} = N",
                system.name,
                system.index_var,
                env(system.index_var).unwrap_or_default()
            ),
        ));
    };
    if let Some((other_from, other)) = counts.iter().find(|(_, n)| *n != count) {
        return Err(Error::invalid(
            auto_key,
            format!("the shard counts disagree: {count_from} gives {count} tasks, {other_from} gives {other}"),
        ));
    }

    let raw = env(system.index_var).unwrap_or_default();
    let (index, detail) = if system.index_var == "SLURM_ARRAY_TASK_ID" {
        slurm_index(&auto_key, &raw, count, env)?
    } else {
        let index = parse_whole(&format!("{auto_key}: {}", system.index_var), &raw, count, 0, 1)?;
        (index, format!("{} = {raw}", system.index_var))
    };
    Ok(ResolvedShard {
        shard: Shard { index, count },
        source: Some(format!("shard {index}/{count} from the {} ({detail}; count from {count_from})", system.name)),
    })
}

/// Slurm's index: `(id - min) / step`, with `min` and `step` from `SLURM_ARRAY_TASK_MIN` and
/// `SLURM_ARRAY_TASK_STEP` (0 and 1 when unset).
fn slurm_index(key: &str, raw_id: &str, count: u32, env: &dyn Fn(&str) -> Option<String>) -> Result<(u32, String)> {
    let number = |var: &str, v: &str, range: &str| -> Result<u32> {
        let v = v.trim();
        if v.is_empty() || !v.bytes().all(|c| c.is_ascii_digit()) {
            return Err(Error::invalid(format!("{key}: {var}"), format!("`{v}` is not a whole number in {range}")));
        }
        v.parse::<u32>().map_err(|_| Error::out_of_range(format!("{key}: {var}"), v, range.to_string()))
    };
    let min = match env("SLURM_ARRAY_TASK_MIN") {
        Some(v) => number("SLURM_ARRAY_TASK_MIN", &v, "[0, 4294967295]")?,
        None => 0,
    };
    let step = match env("SLURM_ARRAY_TASK_STEP") {
        Some(v) => number("SLURM_ARRAY_TASK_STEP", &v, "[1, 4294967295]")?,
        None => 1,
    };
    if step == 0 {
        return Err(Error::out_of_range(format!("{key}: SLURM_ARRAY_TASK_STEP"), 0, "[1, 4294967295]"));
    }
    let id = parse_whole(&format!("{key}: SLURM_ARRAY_TASK_ID"), raw_id, count, min, step)?;
    let offset = id - min; // parse_whole checked id >= min
    if offset % step != 0 {
        return Err(Error::invalid(
            format!("{key}: SLURM_ARRAY_TASK_ID"),
            format!(
                "{id} is not SLURM_ARRAY_TASK_MIN = {min} plus a multiple of SLURM_ARRAY_TASK_STEP = {step}: \
                 --shard auto needs an array that is one range A-B or A-B:S, not a list"
            ),
        ));
    }
    let mut detail = format!("SLURM_ARRAY_TASK_ID = {id}, SLURM_ARRAY_TASK_MIN = {min}");
    if step != 1 {
        detail.push_str(&format!(", SLURM_ARRAY_TASK_STEP = {step}"));
    }
    Ok((offset / step, detail))
}

/// Parses an index-like variable whose valid values are `first + k * step`, k in [0, count).
fn parse_whole(key: &str, raw: &str, count: u32, first: u32, step: u32) -> Result<u32> {
    let last = u64::from(first) + u64::from(count - 1) * u64::from(step);
    let range = if step == 1 {
        format!("[{first}, {last}]")
    } else {
        format!("{{{first}, {}, ..., {last}}}", u64::from(first) + u64::from(step))
    };
    let v = raw.trim();
    if v.is_empty() || !v.bytes().all(|c| c.is_ascii_digit()) {
        return Err(Error::invalid(key, format!("`{raw}` is not a whole number in {range}")));
    }
    match v.parse::<u64>() {
        Ok(x) if x >= u64::from(first) && x <= last => Ok(x as u32),
        _ => Err(Error::out_of_range(key, v, format!("{range} ({count} tasks)"))),
    }
}

/// Parses a shard count in [1, [`MAX_SHARDS`]].
fn parse_count(key: &str, raw: &str) -> Result<u32> {
    let v = raw.trim();
    let range = format!("[1, {MAX_SHARDS}]");
    if v.is_empty() || !v.bytes().all(|c| c.is_ascii_digit()) {
        return Err(Error::invalid(key, format!("`{raw}` is not a whole number in {range}")));
    }
    match v.parse::<u64>() {
        Ok(n) if (1..=u64::from(MAX_SHARDS)).contains(&n) => Ok(n as u32),
        _ => Err(Error::out_of_range(key, v, range)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn resolve(s: &str, vars: &[(&str, &str)]) -> Result<ResolvedShard> {
        let map: BTreeMap<String, String> = vars.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
        resolve_shard("--shard", s, &|k| map.get(k).cloned())
    }

    fn shard(s: &str, vars: &[(&str, &str)]) -> (u32, u32) {
        let r = resolve(s, vars).unwrap_or_else(|e| panic!("{s} {vars:?}: {e}"));
        (r.shard.index, r.shard.count)
    }

    fn error(s: &str, vars: &[(&str, &str)]) -> String {
        match resolve(s, vars) {
            Ok(r) => panic!("{s} {vars:?} resolved to {r:?}"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn explicit_shards_ignore_the_environment() {
        let r = resolve("2/5", &[("SLURM_ARRAY_TASK_ID", "7")]).unwrap();
        assert_eq!((r.shard, r.source), (Shard { index: 2, count: 5 }, None));
        assert!(error("5/5", &[]).contains("--shard index = 5 is outside [0, 4]"));
        assert!(error("automatic", &[]).contains("is not I/N, auto or auto/N"));
    }

    #[test]
    fn slurm_counts_from_the_arrays_first_id_in_its_steps() {
        let zero = [("SLURM_ARRAY_TASK_ID", "3"), ("SLURM_ARRAY_TASK_MIN", "0"), ("SLURM_ARRAY_TASK_COUNT", "16")];
        assert_eq!(shard("auto", &zero), (3, 16));
        // --array=1-16: ids 1..16 are shards 0..15.
        let one = [("SLURM_ARRAY_TASK_ID", "1"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")];
        assert_eq!(shard("auto", &one), (0, 16));
        let last = [("SLURM_ARRAY_TASK_ID", "16"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")];
        assert_eq!(shard("auto", &last), (15, 16));
        // --array=10-40:10: ids 10, 20, 30, 40.
        let step = [
            ("SLURM_ARRAY_TASK_ID", "30"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_STEP", "10"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        assert_eq!(shard("auto", &step), (2, 4));
        // MIN unset counts from 0; the count written as auto/N agrees.
        assert_eq!(shard("auto/4", &[("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_COUNT", "4")]), (2, 4));
        let r = resolve("auto", &one).unwrap();
        let source = r.source.unwrap();
        assert!(source.contains("Slurm") && source.contains("SLURM_ARRAY_TASK_ID = 1"), "{source}");
        assert!(source.contains("SLURM_ARRAY_TASK_MIN = 1") && source.contains("shard 0/16"), "{source}");
    }

    #[test]
    fn slurm_errors_name_the_variable_its_value_and_the_range() {
        let e = error(
            "auto",
            &[("SLURM_ARRAY_TASK_ID", "17"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")],
        );
        assert!(e.contains("SLURM_ARRAY_TASK_ID = 17 is outside [1, 16]"), "{e}");
        let e = error(
            "auto",
            &[("SLURM_ARRAY_TASK_ID", "0"), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")],
        );
        assert!(e.contains("SLURM_ARRAY_TASK_ID = 0 is outside [1, 16]"), "{e}");
        let e = error("auto", &[("SLURM_ARRAY_TASK_ID", "x1"), ("SLURM_ARRAY_TASK_COUNT", "4")]);
        assert!(e.contains("SLURM_ARRAY_TASK_ID") && e.contains("`x1` is not a whole number in [0, 3]"), "{e}");
        let e = error("auto", &[("SLURM_ARRAY_TASK_ID", "2")]);
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT is not set") && e.contains("auto/N"), "{e}");
        let e = error("auto", &[("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_COUNT", "0")]);
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT = 0 is outside [1, 100000]"), "{e}");
        let e = error("auto/8", &[("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_COUNT", "4")]);
        assert!(e.contains("disagree") && e.contains("SLURM_ARRAY_TASK_COUNT = 4") && e.contains("auto/8"), "{e}");
        let steps = [
            ("SLURM_ARRAY_TASK_ID", "15"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_STEP", "10"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        let e = error("auto", &steps);
        assert!(e.contains("not SLURM_ARRAY_TASK_MIN = 10 plus a multiple of SLURM_ARRAY_TASK_STEP = 10"), "{e}");
        let e = error(
            "auto",
            &[("SLURM_ARRAY_TASK_ID", "1"), ("SLURM_ARRAY_TASK_STEP", "0"), ("SLURM_ARRAY_TASK_COUNT", "4")],
        );
        assert!(e.contains("SLURM_ARRAY_TASK_STEP = 0 is outside [1, "), "{e}");
    }

    #[test]
    fn kubernetes_takes_the_count_from_the_option_or_swell_shard_count() {
        assert_eq!(shard("auto/8", &[("JOB_COMPLETION_INDEX", "7")]), (7, 8));
        assert_eq!(shard("auto", &[("JOB_COMPLETION_INDEX", "0"), ("SWELL_SHARD_COUNT", "8")]), (0, 8));
        assert_eq!(shard("auto/8", &[("JOB_COMPLETION_INDEX", "3"), ("SWELL_SHARD_COUNT", "8")]), (3, 8));
        let e = error("auto", &[("JOB_COMPLETION_INDEX", "3")]);
        assert!(e.contains("Kubernetes indexed job found (JOB_COMPLETION_INDEX = 3)"), "{e}");
        assert!(e.contains("auto/N") && e.contains("SWELL_SHARD_COUNT"), "{e}");
        let e = error("auto/8", &[("JOB_COMPLETION_INDEX", "8")]);
        assert!(e.contains("JOB_COMPLETION_INDEX = 8 is outside [0, 7]"), "{e}");
        let e = error("auto/8", &[("JOB_COMPLETION_INDEX", "-1")]);
        assert!(e.contains("JOB_COMPLETION_INDEX: `-1` is not a whole number in [0, 7]"), "{e}");
        let e = error("auto/8", &[("JOB_COMPLETION_INDEX", "1"), ("SWELL_SHARD_COUNT", "4")]);
        assert!(e.contains("disagree"), "{e}");
        let e = error("auto", &[("JOB_COMPLETION_INDEX", "1"), ("SWELL_SHARD_COUNT", "many")]);
        assert!(e.contains("SWELL_SHARD_COUNT: `many` is not a whole number in [1, 100000]"), "{e}");
        let e = error("auto/0", &[("JOB_COMPLETION_INDEX", "1")]);
        assert!(e.contains("auto/N = 0 is outside [1, 100000]"), "{e}");
        let e = error("auto/", &[("JOB_COMPLETION_INDEX", "1")]);
        assert!(e.contains("is not a whole number"), "{e}");
    }

    #[test]
    fn aws_batch_reads_index_and_size() {
        let vars = [("AWS_BATCH_JOB_ARRAY_INDEX", "9"), ("AWS_BATCH_JOB_ARRAY_SIZE", "10")];
        assert_eq!(shard("auto", &vars), (9, 10));
        assert!(resolve("auto", &vars).unwrap().source.unwrap().contains("AWS Batch"));
        let e = error("auto", &[("AWS_BATCH_JOB_ARRAY_INDEX", "10"), ("AWS_BATCH_JOB_ARRAY_SIZE", "10")]);
        assert!(e.contains("AWS_BATCH_JOB_ARRAY_INDEX = 10 is outside [0, 9]"), "{e}");
        let e = error("auto", &[("AWS_BATCH_JOB_ARRAY_INDEX", "1")]);
        assert!(e.contains("AWS_BATCH_JOB_ARRAY_SIZE is not set"), "{e}");
    }

    #[test]
    fn no_or_several_systems_are_refused() {
        let e = error("auto", &[("PATH", "/bin")]);
        assert!(e.contains("no array-job variable is set"), "{e}");
        for var in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "AWS_BATCH_JOB_ARRAY_INDEX"] {
            assert!(e.contains(var), "{e}");
        }
        let e = error("auto/2", &[("SLURM_ARRAY_TASK_ID", "1"), ("JOB_COMPLETION_INDEX", "1")]);
        assert!(
            e.contains("ambiguous") && e.contains("SLURM_ARRAY_TASK_ID") && e.contains("JOB_COMPLETION_INDEX"),
            "{e}"
        );
    }

    #[test]
    fn every_task_of_an_array_gets_a_different_shard() {
        // --array=1-16: the 16 tasks together are shards 0..15, each once.
        let mut seen: Vec<u32> = (1..=16)
            .map(|id| {
                let id = id.to_string();
                shard(
                    "auto",
                    &[("SLURM_ARRAY_TASK_ID", &id), ("SLURM_ARRAY_TASK_MIN", "1"), ("SLURM_ARRAY_TASK_COUNT", "16")],
                )
                .0
            })
            .collect();
        seen.sort();
        assert_eq!(seen, (0..16).collect::<Vec<_>>());
    }
}
