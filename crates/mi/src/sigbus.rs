//! A `SIGBUS` guard for mapped source files: a file truncated while mira has it mapped would
//! kill the process with `SIGBUS` when a lost page is read. The guard's handler puts a page
//! of zeros over the lost page instead, marks the map as faulted (so that the parse is
//! refused, see [`crate::text::SourceText::changed_on_disk`]) and lets the read go on.
//! Faults outside registered maps are passed to the handler that was there before (Rust's
//! own stack-overflow reporter, or the default action).

#![allow(unsafe_code)]

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::OnceLock;

/// How many maps can be guarded at once; a further file is read instead of mapped.
const SLOTS: usize = 64;

/// One guarded address range (`start == 0`: free).
struct Slot {
    start: AtomicUsize,
    len: AtomicUsize,
    faulted: AtomicBool,
}

#[allow(clippy::declare_interior_mutable_const)]
const FREE: Slot = Slot { start: AtomicUsize::new(0), len: AtomicUsize::new(0), faulted: AtomicBool::new(false) };
static GUARDED: [Slot; SLOTS] = [FREE; SLOTS];
static PAGE_SIZE: AtomicUsize = AtomicUsize::new(0);
/// The `SIGBUS` action before the guard's (`None`: installing failed).
static PREVIOUS: OnceLock<Option<libc::sigaction>> = OnceLock::new();

/// The size of a memory page, in bytes.
pub(crate) fn page_size() -> usize {
    let cached = PAGE_SIZE.load(Ordering::Relaxed);
    if cached != 0 {
        return cached;
    }
    // SAFETY: `sysconf` only reads a system constant.
    let size = unsafe { libc::sysconf(libc::_SC_PAGESIZE) };
    let size = if size > 0 { size as usize } else { 4096 };
    PAGE_SIZE.store(size, Ordering::Relaxed);
    size
}

/// Installs the handler once; whether it is in place.
fn install() -> bool {
    PREVIOUS
        .get_or_init(|| {
            page_size();
            // SAFETY: plain `sigaction` calls with zero-initialised (valid) structs; the
            // handler only touches atomics and calls `mmap`/`sigaction`, both system calls.
            unsafe {
                let mut old: libc::sigaction = std::mem::zeroed();
                if libc::sigaction(libc::SIGBUS, std::ptr::null(), &mut old) != 0 {
                    return None;
                }
                let mut new: libc::sigaction = std::mem::zeroed();
                new.sa_sigaction = on_sigbus as *const () as usize;
                new.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
                libc::sigemptyset(&mut new.sa_mask);
                // `PREVIOUS` is being initialised: the handler reads it only for faults
                // outside the guarded maps, of which none exists yet.
                if libc::sigaction(libc::SIGBUS, &new, std::ptr::null_mut()) != 0 {
                    return None;
                }
                Some(old)
            }
        })
        .is_some()
}

extern "C" fn on_sigbus(signal: libc::c_int, info: *mut libc::siginfo_t, context: *mut libc::c_void) {
    // SAFETY: the kernel passes a valid `siginfo_t` to an `SA_SIGINFO` handler.
    let addr = unsafe { (*info).si_addr() } as usize;
    let page = PAGE_SIZE.load(Ordering::Relaxed).max(1);
    for slot in &GUARDED {
        let start = slot.start.load(Ordering::Acquire);
        let len = slot.len.load(Ordering::Acquire);
        if start != 0 && addr >= start && addr - start < len {
            let at = addr - addr % page;
            // SAFETY: the page lies in a read-only map this process owns and never writes;
            // replacing it with a zero page changes only bytes the file no longer has.
            let p = unsafe {
                libc::mmap(
                    at as *mut libc::c_void,
                    page,
                    libc::PROT_READ,
                    libc::MAP_PRIVATE | libc::MAP_ANONYMOUS | libc::MAP_FIXED,
                    -1,
                    0,
                )
            };
            if p != libc::MAP_FAILED {
                slot.faulted.store(true, Ordering::Release);
                return;
            }
        }
    }
    // Not ours: hand over to the previous action. While the guard is still being installed
    // (`PREVIOUS` not yet set) that action is unknown: fall back to the default one rather
    // than return and fault again forever.
    let Some(Some(previous)) = PREVIOUS.get() else {
        // SAFETY: a zeroed `sigaction` with `SIG_DFL` is the default action; returning
        // re-runs the faulting access, which then ends the process as it would have.
        unsafe {
            let mut default: libc::sigaction = std::mem::zeroed();
            default.sa_sigaction = libc::SIG_DFL;
            libc::sigaction(libc::SIGBUS, &default, std::ptr::null_mut());
        }
        return;
    };
    let handler = previous.sa_sigaction;
    if handler == libc::SIG_DFL || handler == libc::SIG_IGN {
        // SAFETY: restores the previous action; returning re-runs the faulting access,
        // which then gets the default behaviour (the process ends as it would have; the
        // kernel does not let an ignored fault signal go by).
        unsafe { libc::sigaction(libc::SIGBUS, previous, std::ptr::null_mut()) };
    } else if previous.sa_flags & libc::SA_SIGINFO != 0 {
        // SAFETY: the previous handler was installed for this signal with this signature.
        let f: extern "C" fn(libc::c_int, *mut libc::siginfo_t, *mut libc::c_void) =
            unsafe { std::mem::transmute(handler) };
        f(signal, info, context);
    } else {
        // SAFETY: as above, for a plain one-argument handler.
        let f: extern "C" fn(libc::c_int) = unsafe { std::mem::transmute(handler) };
        f(signal);
    }
}

/// An address range guarded while this value lives.
pub(crate) struct Registration {
    slot: &'static Slot,
}

impl Registration {
    /// Guards `len` bytes from `start`; `None` when the handler cannot be installed or every
    /// slot is taken.
    pub(crate) fn new(start: usize, len: usize) -> Option<Registration> {
        if start == 0 || !install() {
            return None;
        }
        for slot in &GUARDED {
            if slot.start.compare_exchange(0, usize::MAX, Ordering::AcqRel, Ordering::Relaxed).is_ok() {
                slot.faulted.store(false, Ordering::Release);
                slot.len.store(len, Ordering::Release);
                slot.start.store(start, Ordering::Release);
                return Some(Registration { slot });
            }
        }
        None
    }

    /// Whether a page of the range was lost (the file shrank) and replaced by zeros.
    pub(crate) fn faulted(&self) -> bool {
        self.slot.faulted.load(Ordering::Acquire)
    }
}

impl Drop for Registration {
    fn drop(&mut self) {
        self.slot.len.store(0, Ordering::Release);
        self.slot.start.store(0, Ordering::Release);
    }
}
