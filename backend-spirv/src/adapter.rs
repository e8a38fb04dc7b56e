//! Which Vulkan adapter runs the shaders: a real GPU when there is one, else lavapipe;
//! `SCRATCHWAVE_ADAPTER` overrides.

use std::fmt;
use std::str::FromStr;

/// Environment variable read by [`AdapterChoice::from_env`].
pub const ADAPTER_ENV: &str = "SCRATCHWAVE_ADAPTER";

/// What kind of device an adapter drives (wgpu's `DeviceType`, without the wgpu type).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum AdapterKind {
    /// A discrete GPU.
    DiscreteGpu,
    /// A GPU sharing memory with the CPU.
    IntegratedGpu,
    /// A GPU behind a virtualisation layer.
    VirtualGpu,
    /// A software rasteriser on the CPU (lavapipe).
    Cpu,
    /// Anything else.
    Other,
}

impl AdapterKind {
    fn from_wgpu(kind: wgpu::DeviceType) -> Self {
        match kind {
            wgpu::DeviceType::DiscreteGpu => Self::DiscreteGpu,
            wgpu::DeviceType::IntegratedGpu => Self::IntegratedGpu,
            wgpu::DeviceType::VirtualGpu => Self::VirtualGpu,
            wgpu::DeviceType::Cpu => Self::Cpu,
            wgpu::DeviceType::Other => Self::Other,
        }
    }

    /// A physical GPU (discrete or integrated).
    pub fn is_gpu(self) -> bool {
        matches!(self, Self::DiscreteGpu | Self::IntegratedGpu)
    }
}

/// A Vulkan adapter as the selection sees it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AdapterSummary {
    /// Device name, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)` for lavapipe.
    pub name: String,
    /// Device kind.
    pub kind: AdapterKind,
    /// Driver name and version, e.g. `llvmpipe` / `Mesa 22.3.6`.
    pub driver: String,
}

impl AdapterSummary {
    pub(crate) fn from_wgpu(info: &wgpu::AdapterInfo) -> Self {
        let driver = match (info.driver.is_empty(), info.driver_info.is_empty()) {
            (false, false) => format!("{} {}", info.driver, info.driver_info),
            (false, true) => info.driver.clone(),
            _ => info.driver_info.clone(),
        };
        Self {
            name: info.name.clone(),
            kind: AdapterKind::from_wgpu(info.device_type),
            driver,
        }
    }

    /// Mesa's lavapipe (the Vulkan driver on llvmpipe).
    pub fn is_lavapipe(&self) -> bool {
        self.kind == AdapterKind::Cpu || self.name.to_lowercase().contains("llvmpipe")
    }
}

impl fmt::Display for AdapterSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({:?}", self.name, self.kind)?;
        if !self.driver.is_empty() {
            write!(f, ", {}", self.driver)?;
        }
        write!(f, ")")
    }
}

/// How to pick the adapter.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum AdapterChoice {
    /// A discrete GPU, else an integrated one, else a virtual one, else lavapipe.
    #[default]
    Auto,
    /// lavapipe (`lavapipe`, `llvmpipe` or `cpu`): deterministic, runs everywhere.
    Lavapipe,
    /// A physical GPU (`gpu`): discrete preferred; an error if there is none.
    Gpu,
    /// The first adapter whose name contains this (case-insensitive).
    NameContains(String),
}

impl FromStr for AdapterChoice {
    type Err = std::convert::Infallible;

    /// `""`/`auto`, `lavapipe`/`llvmpipe`/`cpu`, `gpu`, or a name substring.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let trimmed = s.trim();
        Ok(match trimmed.to_lowercase().as_str() {
            "" | "auto" => Self::Auto,
            "lavapipe" | "llvmpipe" | "cpu" => Self::Lavapipe,
            "gpu" => Self::Gpu,
            _ => Self::NameContains(trimmed.to_owned()),
        })
    }
}

impl fmt::Display for AdapterChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Auto => write!(f, "auto"),
            Self::Lavapipe => write!(f, "lavapipe"),
            Self::Gpu => write!(f, "gpu"),
            Self::NameContains(name) => write!(f, "a name containing {name:?}"),
        }
    }
}

impl AdapterChoice {
    /// The choice in [`ADAPTER_ENV`], [`AdapterChoice::Auto`] when unset.
    pub fn from_env() -> Self {
        match std::env::var(ADAPTER_ENV) {
            Ok(value) => value.parse().unwrap_or_default(),
            Err(_) => Self::Auto,
        }
    }

    /// Index of the adapter this choice selects among `adapters`, if any.
    pub fn select(&self, adapters: &[AdapterSummary]) -> Option<usize> {
        let best_by = |rank: fn(AdapterKind) -> Option<u8>| {
            (0..adapters.len())
                .filter_map(|i| rank(adapters[i].kind).map(|r| (r, i)))
                .min()
                .map(|(_, i)| i)
        };
        match self {
            Self::Auto => best_by(|kind| Some(kind as u8)),
            Self::Gpu => best_by(|kind| kind.is_gpu().then_some(kind as u8)),
            Self::Lavapipe => adapters.iter().position(AdapterSummary::is_lavapipe),
            Self::NameContains(part) => {
                let part = part.to_lowercase();
                adapters
                    .iter()
                    .position(|a| a.name.to_lowercase().contains(&part))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn adapter(name: &str, kind: AdapterKind) -> AdapterSummary {
        AdapterSummary {
            name: name.into(),
            kind,
            driver: String::new(),
        }
    }

    fn machine() -> Vec<AdapterSummary> {
        vec![
            adapter("llvmpipe (LLVM 15.0.6, 256 bits)", AdapterKind::Cpu),
            adapter("Intel(R) UHD Graphics 770", AdapterKind::IntegratedGpu),
            adapter("NVIDIA GeForce RTX 4090", AdapterKind::DiscreteGpu),
        ]
    }

    #[test]
    fn parses_the_documented_spellings() {
        assert_eq!("".parse(), Ok(AdapterChoice::Auto));
        assert_eq!(" Auto ".parse(), Ok(AdapterChoice::Auto));
        assert_eq!("lavapipe".parse(), Ok(AdapterChoice::Lavapipe));
        assert_eq!("LLVMPIPE".parse(), Ok(AdapterChoice::Lavapipe));
        assert_eq!("cpu".parse(), Ok(AdapterChoice::Lavapipe));
        assert_eq!("gpu".parse(), Ok(AdapterChoice::Gpu));
        assert_eq!("RTX".parse(), Ok(AdapterChoice::NameContains("RTX".into())));
    }

    #[test]
    fn auto_prefers_discrete_then_integrated_then_lavapipe() {
        let mut adapters = machine();
        assert_eq!(AdapterChoice::Auto.select(&adapters), Some(2));
        adapters.pop();
        assert_eq!(AdapterChoice::Auto.select(&adapters), Some(1));
        adapters.pop();
        assert_eq!(AdapterChoice::Auto.select(&adapters), Some(0));
        assert_eq!(AdapterChoice::Auto.select(&[]), None);
    }

    #[test]
    fn explicit_choices() {
        let adapters = machine();
        assert_eq!(AdapterChoice::Lavapipe.select(&adapters), Some(0));
        assert_eq!(AdapterChoice::Gpu.select(&adapters), Some(2));
        assert_eq!(
            AdapterChoice::NameContains("intel".into()).select(&adapters),
            Some(1)
        );
        assert_eq!(
            AdapterChoice::NameContains("radeon".into()).select(&adapters),
            None
        );
        assert_eq!(AdapterChoice::Gpu.select(&adapters[..1]), None);
    }
}
