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

/// The one memory check: refuses work that needs `bytes` when `available` bytes are free,
/// before anything is allocated. The error says what needs it, both sizes and the way out.
pub fn check_memory(bytes: f64, available: f64, what: &str, fix: &str) -> crate::Result<()> {
    if bytes <= available {
        return Ok(());
    }
    let gib = 2f64.powi(30);
    Err(crate::Error::Input(format!(
        "{what} would need about {:.1} GiB, more than the {:.1} GiB available; {fix}",
        bytes / gib,
        available / gib
    )))
}
