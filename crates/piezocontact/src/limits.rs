//! The machine's limits that inputs are checked against before the work starts.

/// The environment variable that caps the memory a run may plan for \[bytes\], below what the
/// machine has available (for a machine shared with other work).
pub const MEMORY_LIMIT_VAR: &str = "PIEZOCONTACT_MEMORY_LIMIT";

/// Memory available to this process \[bytes\]: MemAvailable of /proc/meminfo (else 24 GiB),
/// or less when [`MEMORY_LIMIT_VAR`] says so.
pub fn available_memory() -> f64 {
    let machine = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|t| {
            let line = t.lines().find(|l| l.starts_with("MemAvailable:"))?.to_string();
            line.split_whitespace().nth(1)?.parse::<f64>().ok()
        })
        .map_or(24.0 * 2f64.powi(30), |kib| kib * 1024.0);
    let cap = std::env::var(MEMORY_LIMIT_VAR).ok().and_then(|v| v.trim().parse::<f64>().ok());
    cap.filter(|c| *c > 0.0).map_or(machine, |c| c.min(machine))
}

/// This process's peak resident memory so far \[bytes\]: VmHWM of /proc/self/status (Linux);
/// `None` elsewhere.
pub fn peak_resident_bytes() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024.0)
}

/// Resets this process's peak resident memory to what it holds now (Linux ≥ 4.0: "5" to
/// /proc/self/clear_refs), so that [`peak_resident_bytes`] measures the work that follows;
/// false where the system does not allow it.
pub fn reset_peak_resident() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Bytes in the unit that reads best: "12.3 GiB", "456.7 MiB", "12.6 KiB".
pub fn bytes_text(bytes: f64) -> String {
    let (gib, mib) = (2f64.powi(30), 2f64.powi(20));
    if bytes >= gib {
        format!("{:.1} GiB", bytes / gib)
    } else if bytes >= 0.1 * mib {
        format!("{:.1} MiB", bytes / mib)
    } else {
        format!("{:.1} KiB", bytes / 1024.0)
    }
}

/// The one memory check: refuses work that needs `bytes` when `available` bytes are free,
/// before anything is allocated. The error says what needs it, both sizes and the way out.
pub fn check_memory(bytes: f64, available: f64, what: &str, fix: &str) -> crate::Result<()> {
    if bytes <= available {
        return Ok(());
    }
    Err(crate::Error::Input(format!(
        "{what} would need about {}, more than the {} available; {fix}",
        bytes_text(bytes),
        bytes_text(available)
    )))
}

#[cfg(test)]
mod tests {
    use super::bytes_text;

    #[test]
    fn bytes_read_in_the_unit_that_fits_them() {
        assert_eq!(bytes_text(12_600.0), "12.3 KiB");
        assert_eq!(bytes_text(0.5 * 2f64.powi(20)), "0.5 MiB");
        assert_eq!(bytes_text(456.7 * 2f64.powi(20)), "456.7 MiB");
        assert_eq!(bytes_text(12.3 * 2f64.powi(30)), "12.3 GiB");
    }
}
