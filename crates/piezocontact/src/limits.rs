//! The machine's limits that inputs are checked against before the work starts.

/// Memory available to this process [bytes]: MemAvailable of /proc/meminfo, else 24 GiB.
pub fn available_memory() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|t| {
            let line = t.lines().find(|l| l.starts_with("MemAvailable:"))?.to_string();
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(24.0 * 2f64.powi(30), |kib| kib * 1024.0)
}
