//! Which vector instructions the lane loops run with: one definition of the choice, made at run
//! time from what the CPU reports, so one binary runs everywhere and uses the widest registers the
//! machine has.
//!
//! The lane loops ([`super::Lanes`], the sky rows, the Gerstner rows) are plain Rust loops that the
//! compiler vectorises; [`Isa::run`] compiles a closure's body a second and third time with AVX2
//! or AVX-512 enabled. Every build does the same IEEE operations lane by lane in the same order
//! (Rust never fuses a multiply and an add on its own, and vector square roots and divisions are
//! correctly rounded), so the images do not depend on the CPU: the tests compare every build the
//! machine has bit for bit (`isa_builds_agree` in `shading/water_optics.rs`, `render/sky_pass.rs`,
//! `render/sea_lod.rs` and `water/trochoidal_sum.rs`). The kernels written with AVX2 intrinsics
//! (the FFT ocean's, the RGBA8 encoder) ask [`Isa::is_available`] too.
//!
//! AVX-512 halves the instructions of a 64-lane loop against AVX2 (16 lanes per instruction, not
//! 8): on the 2-core AMD EPYC (Zen 4) this project is measured on, the `ocean` preset's CPU time
//! per frame fell by 12 % with the water shading compiled for it (docs/PERFORMANCE.md, session 12).

/// An instruction set the lane loops are compiled for, narrowest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Isa {
    /// The target's baseline (SSE2 on x86-64); every CPU.
    Portable,
    /// x86-64 with AVX2: 8 lanes per instruction.
    Avx2,
    /// x86-64 with AVX-512 (F, VL, DQ, BW): 16 lanes per instruction.
    Avx512,
}

impl Isa {
    /// Every instruction set, narrowest first.
    pub const ALL: [Isa; 3] = [Isa::Portable, Isa::Avx2, Isa::Avx512];

    /// Whether this CPU can run code built for `self` (std caches the CPU's answer).
    pub fn is_available(self) -> bool {
        match self {
            Isa::Portable => true,
            #[cfg(target_arch = "x86_64")]
            Isa::Avx2 => std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(target_arch = "x86_64")]
            Isa::Avx512 => {
                std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512vl")
                    && std::arch::is_x86_feature_detected!("avx512dq")
                    && std::arch::is_x86_feature_detected!("avx512bw")
                    && std::arch::is_x86_feature_detected!("avx2")
            }
            #[cfg(not(target_arch = "x86_64"))]
            _ => false,
        }
    }

    /// The widest instruction set this CPU has.
    pub fn widest() -> Isa {
        Isa::ALL.into_iter().rev().find(|isa| isa.is_available()).unwrap_or(Isa::Portable)
    }

    /// Runs `f` compiled for `self`, or for the baseline when this CPU lacks `self`. `f` must be
    /// an `#[inline(always)]` closure whose hot code is inlined into it too: only what is inlined
    /// into the wrapper is compiled with its instructions.
    #[inline(always)]
    pub fn run<R>(self, f: impl FnOnce() -> R) -> R {
        #[cfg(target_arch = "x86_64")]
        match self {
            // SAFETY: the CPU has the features each wrapper enables, checked first.
            Isa::Avx512 if self.is_available() => return unsafe { run_avx512(f) },
            Isa::Avx2 if self.is_available() => return unsafe { run_avx2(f) },
            _ => {}
        }
        f()
    }

    /// [`Self::run`] with the widest instruction set this CPU has.
    #[inline(always)]
    pub fn run_widest<R>(f: impl FnOnce() -> R) -> R {
        Isa::widest().run(f)
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn run_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512dq,avx512bw,avx2")]
unsafe fn run_avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_widest_is_available_and_the_baseline_always_is() {
        assert!(Isa::Portable.is_available());
        assert!(Isa::widest().is_available());
        for isa in Isa::ALL {
            // Every set runs, falling back to the baseline when the CPU lacks it.
            assert_eq!(isa.run(|| 2 + 2), 4);
        }
    }
}
