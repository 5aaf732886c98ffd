//! The calls the compiler cannot check: into the C library and the kernel, and into code
//! compiled for vector instructions the CPU must be asked about first. The crate denies
//! `unsafe` everywhere else; each block here says why it is sound.
#![allow(unsafe_code)]

/// Gives every allocation from 1 MiB up its own mapping, returned to the system when freed.
/// glibc raises that threshold to 32 MiB once such a block is freed, after which the trees
/// and texts of one phase (an upgrade's conversion, its proof) stay resident, freed but
/// scattered, while the next (the check of the output) maps its own. For a program (the
/// command line calls it first); a library user's process keeps its own allocator settings.
pub fn return_large_blocks_when_freed() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets a tuning parameter (glibc takes the arena lock for it).
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 20);
    }
}

/// The user id the process acts as (the owner of the files it creates).
#[cfg(unix)]
pub(crate) fn effective_user() -> u32 {
    // SAFETY: geteuid has no preconditions and cannot fail.
    unsafe { libc::geteuid() }
}

/// Asks for the whole 2 MiB pages inside `bytes` to be backed by huge pages where the
/// system offers them on request (transparent huge pages in `madvise` mode): filling fresh
/// memory is mostly page faults, and a huge page takes one where 4 KiB pages take 512.
pub(crate) fn advise_huge_pages(bytes: &mut [u8]) {
    #[cfg(target_os = "linux")]
    {
        const HUGE: usize = 2 << 20;
        let start = bytes.as_mut_ptr() as usize;
        let aligned = start.div_ceil(HUGE) * HUGE;
        let end = (start + bytes.len()) / HUGE * HUGE;
        if end > aligned {
            // SAFETY: the range lies inside `bytes`, which this function borrows mutably;
            // MADV_HUGEPAGE changes how its pages are backed, never their contents.
            unsafe {
                libc::madvise(
                    aligned as *mut libc::c_void,
                    end - aligned,
                    libc::MADV_HUGEPAGE,
                )
            };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = bytes;
}

/// Vector instruction sets a hot loop can be compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Vectors {
    /// AVX-512 F, DQ and VL.
    Avx512,
    /// AVX2.
    Avx2,
}

impl Vectors {
    /// Widest first.
    pub(crate) const ALL: [Vectors; 2] = [Vectors::Avx512, Vectors::Avx2];

    /// Whether this CPU runs them.
    pub(crate) fn available(self) -> bool {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            match self {
                Vectors::Avx512 => has!("avx512f") && has!("avx512dq") && has!("avx512vl"),
                Vectors::Avx2 => has!("avx2"),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            let _ = self;
            false
        }
    }
}

/// Runs `f` compiled for `vectors`, or `None` when the CPU does not run them. `f` must be
/// an `#[inline(always)]` closure so that its body is compiled inside the function that
/// enables them: plain arithmetic then changes speed, not results (no fused multiply-adds
/// are formed; each lane rounds as scalar `f64` does).
#[cfg(test)]
#[inline(always)]
pub(crate) fn compiled_for<R>(vectors: Vectors, f: impl FnOnce() -> R) -> Option<R> {
    vectors.available().then(|| run_available(vectors, f))
}

/// Runs `f` compiled with the widest vector instructions the CPU has (see
/// [`compiled_for`]), or as it is.
#[inline(always)]
pub(crate) fn with_widest_vectors<R>(f: impl FnOnce() -> R) -> R {
    match Vectors::ALL.into_iter().find(|v| v.available()) {
        Some(vectors) => run_available(vectors, f),
        None => f(),
    }
}

/// [`compiled_for`] once `vectors` were found available.
#[inline(always)]
fn run_available<R>(vectors: Vectors, f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: every caller has found the CPU to run `vectors`.
    unsafe {
        match vectors {
            Vectors::Avx512 => with_avx512(f),
            Vectors::Avx2 => with_avx2(f),
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = vectors;
        f()
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl")]
fn with_avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn with_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}
