//! The bilinear texel-rate limit (SMs × texture units per SM × clock) of known adapters. wgpu
//! cannot tell how many SMs a GPU has, so the figures are a table, overridable with
//! `--texel-rate`.

use serde::Serialize;

/// Where a texel-rate figure came from and what it is made of.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TexelRate {
    /// Bilinear texels per second, in billions.
    pub gtexels_per_s: f64,
    /// How the figure was obtained, for the report.
    pub source: String,
}

// (adapter name contains, SMs, texture units per SM, clock in GHz)
const KNOWN: [(&str, u32, u32, f64); 2] = [
    // 1.98 GHz: the SM clock seen steady under load on the project's machine (TOOLCHAIN.md).
    ("H100", 132, 4, 1.98),
    // The same chip (GH100, 132 SMs enabled) with more memory: the benchmark machine
    // (sandbox/BENCHMARKS.md, "Current figures").
    ("H200", 132, 4, 1.98),
];

/// The figure for `adapter_name`: the override if given, else the table, else `None`.
pub fn texel_rate(adapter_name: &str, override_gtexels: Option<f64>) -> Option<TexelRate> {
    if let Some(rate) = override_gtexels {
        return Some(TexelRate {
            gtexels_per_s: rate,
            source: "--texel-rate".to_owned(),
        });
    }
    KNOWN
        .iter()
        .find(|(name, ..)| adapter_name.contains(name))
        .map(|&(name, sms, units, ghz)| TexelRate {
            gtexels_per_s: f64::from(sms) * f64::from(units) * ghz,
            source: format!("{name}: {sms} SMs x {units} texture units/SM x {ghz} GHz"),
        })
}

#[cfg(test)]
mod tests {
    use super::texel_rate;

    #[test]
    fn h100_and_h200_from_the_table_override_wins_unknown_is_none() {
        let h100 = texel_rate("NVIDIA H100 80GB HBM3", None).unwrap();
        assert!((h100.gtexels_per_s - 1045.44).abs() < 1e-9);
        let h200 = texel_rate("NVIDIA H200", None).unwrap();
        assert!((h200.gtexels_per_s - 1045.44).abs() < 1e-9);
        assert!(h200.source.starts_with("H200"), "{}", h200.source);
        assert_eq!(
            texel_rate("NVIDIA H100", Some(7.0)).unwrap().gtexels_per_s,
            7.0
        );
        assert_eq!(texel_rate("llvmpipe (LLVM 15.0.6, 256 bits)", None), None);
    }
}
