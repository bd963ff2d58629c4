//! Loops of a statement body whose control depends on the hit, compiled once per material
//! instance into a [`HitLoop`] that runs at each hit: the values the loop carries (the
//! variables it assigns) live in numbered slots ([`HitExpr::Slot`]), the loop's condition
//! and one turn of its body are expressions over those slots (and the hit), and the value
//! of a variable after the loop is [`HitExpr::LoopOut`]. `break` and `continue` under a
//! condition of the hit are part of the turn's expressions (see
//! [`super::statements`]); a `break` sets the turn's exit condition.
//!
//! Evaluating one needs no allocation: the slots are a fixed array ([`Frame`], copied on
//! the stack when a loop starts so that a loop evaluated inside another's turn does not
//! disturb it). A nest of loops whose slots fit in [`SMALL_FRAME`] runs in a frame of that
//! many (the common case: its copies stay small); a larger one, up to [`MAX_LOOP_SLOTS`]
//! values, in a frame of [`LARGE_FRAME`]; the outermost loop of a nest picks the size from
//! the most slots any loop of the nest reaches ([`HitLoop::top`]). A loop no loop is
//! around runs once per [`Evaluation`], however many of its values are read and wherever
//! (after it, or in a later loop's start or turns): its results wait in a small cache of
//! the render thread. Endless loops end: such a loop with the loops nested in it takes at
//! most [`MAX_LOOP_STEPS`] steps — each turn counts the nodes its condition and body
//! visit — and a loop that reaches that stops where it is, its variables keeping the
//! values of its last turn.

use std::cell::{Cell, RefCell};
use std::marker::PhantomData;
use std::sync::Arc;

use glam::Vec4;
use shader::State;

use super::hit::{HitExpr, MAX_HIT_NODES};

/// Most values the per-hit loops around any point of a body carry together (nested loops
/// add theirs to those of the loops around them): slots are numbered by a `u8`.
pub const MAX_LOOP_SLOTS: usize = 255;

/// Slots of the frame a nest of loops of the hit runs in when they fit (512 bytes).
pub const SMALL_FRAME: usize = 32;

/// Slots of the frame of a nest that needs more than [`SMALL_FRAME`] (4 KiB, copied when a
/// loop of the nest starts).
pub const LARGE_FRAME: usize = 256;

/// Most loops of the hit nested in one another when their nest runs in a large frame:
/// each level keeps its copies of the frame on the stack of the render thread (up to 16
/// KiB a level).
pub const MAX_LARGE_NESTING: usize = 16;

/// Most steps (expression nodes visited) a loop of the hit that no loop is around takes
/// with the loops nested in it: a quarter of what one evaluation may visit
/// ([`MAX_HIT_NODES`]), which counts each such loop once as this many.
pub const MAX_LOOP_STEPS: u64 = MAX_HIT_NODES / 4;

/// A loop of the hit: slots `base..base + init.len()` start at `init` (evaluated around
/// the loop), then while `cond` holds each turn replaces them by `next` and stops when
/// `exit` (a `break` taken) holds.
#[derive(Clone, Debug)]
pub struct HitLoop {
    /// The first slot the loop carries.
    pub base: u8,
    /// The slots' values when the loop starts.
    pub init: Box<[Arc<HitExpr>]>,
    /// Whether the next turn runs (over the slots).
    pub cond: Arc<HitExpr>,
    /// The slots' values after a turn (over the slots before it).
    pub next: Box<[Arc<HitExpr>]>,
    /// Whether a turn left the loop by `break` (over the slots before it).
    pub exit: Arc<HitExpr>,
    /// The condition is tested before the first turn (`for`, `while`), else only after it
    /// (`do`–`while`).
    pub test_first: bool,
    /// Nodes one turn visits (condition, next values and exit; the loops nested in it
    /// count one turn, their further turns are counted as they run).
    pub turn_cost: u64,
    /// One past the highest slot this loop and the loops nested in it use: the frame the
    /// nest needs.
    pub top: u8,
}

impl PartialEq for HitLoop {
    /// Loops compare by what they compute; their expressions are compared as the
    /// operands of [`HitExpr::LoopOut`] (see [`super::hit_eq`]).
    fn eq(&self, other: &HitLoop) -> bool {
        self.base == other.base
            && self.init.len() == other.init.len()
            && self.next.len() == other.next.len()
            && self.test_first == other.test_first
    }
}

impl HitLoop {
    /// The expressions the loop evaluates: the initial values, the condition, the next
    /// values, the exit condition (in that order).
    pub fn operands(&self) -> impl Iterator<Item = &Arc<HitExpr>> {
        self.init.iter().chain([&self.cond]).chain(self.next.iter()).chain([&self.exit])
    }

    /// Runs the loop at the shading point `s` in `outer`'s frame: slot `k` after it.
    #[inline]
    pub fn value<F: Slots>(&self, s: &State, outer: F, k: u8) -> Vec4 {
        outer.run(self, s, k)
    }

    /// Runs the loop at the shading point `s` in frame `f` (the slots of the loops around,
    /// taken by value so that a fresh frame is not copied again): the slots after it. Never
    /// inlined: its arrays would enlarge the stack frame of every evaluation.
    #[inline(never)]
    fn run_in<'a, const N: usize>(&self, s: &State, mut f: Frame<'a, N>) -> Frame<'a, N> {
        let base = usize::from(self.base);
        let mut fresh = [Vec4::ZERO; N];
        let n = self.init.len().min(N.saturating_sub(base));
        for (k, e) in self.init.iter().take(n).enumerate() {
            fresh[k] = e.eval_in(s, &f);
        }
        f.slots[base..base + n].copy_from_slice(&fresh[..n]);
        let mut first = true;
        loop {
            if (self.test_first || !first) && self.cond.eval_in(s, &f).x == 0.0 {
                break;
            }
            first = false;
            f.steps.set(f.steps.get() + self.turn_cost);
            if f.steps.get() > MAX_LOOP_STEPS {
                break;
            }
            for (k, e) in self.next.iter().take(n).enumerate() {
                fresh[k] = e.eval_in(s, &f);
            }
            let exit = self.exit.eval_in(s, &f).x != 0.0;
            f.slots[base..base + n].copy_from_slice(&fresh[..n]);
            if exit {
                break;
            }
        }
        f
    }
}

/// The slots of the per-hit loops an evaluation is inside (`N` of them), the steps they
/// took, and the evaluation they belong to.
#[derive(Clone, Debug)]
pub struct Frame<'a, const N: usize> {
    /// Slot values.
    pub slots: [Vec4; N],
    /// Loop steps taken so far by the nest.
    pub steps: Cell<u64>,
    /// The evaluation: where the loops no loop is around keep their results.
    pub top: &'a Evaluation,
}

impl<'a, const N: usize> Frame<'a, N> {
    /// A frame of zero slots that has taken no steps, in evaluation `top`.
    fn new(top: &'a Evaluation) -> Frame<'a, N> {
        Frame { slots: [Vec4::ZERO; N], steps: Cell::new(0), top }
    }
}

/// One evaluation of hit expressions at one shading point (one call of
/// [`HitExpr::eval`], or all the expressions a material reads at a hit). The loops of the
/// hit that no loop is around (`base` 0: functions of the hit alone) run once in it,
/// however many of their values are read and wherever they are read (after them, in the
/// starting values or turns of a later loop): their results stay in a cache of the
/// render thread under the evaluation's id, which it is given when its first such loop
/// runs (an evaluation without loops is only passed along, a pointer).
#[derive(Debug, Default)]
pub struct Evaluation {
    /// 0 until a loop runs in it; then unique on its thread.
    id: Cell<u64>,
    /// Not sent to another thread (its id names results in this thread's cache).
    _thread: PhantomData<*const ()>,
}

impl Evaluation {
    /// A fresh evaluation: no loop has run in it.
    #[inline]
    pub fn new() -> Evaluation {
        Evaluation::default()
    }

    /// Slot `k` after loop `l` (base 0) at the shading point `s`, running it unless it
    /// already ran in this evaluation.
    fn once(&self, l: &HitLoop, s: &State, k: u8) -> Vec4 {
        let key = std::ptr::from_ref(l);
        let (id, done) = RESULTS.with_borrow_mut(|r| {
            // The evaluation's id, given now if it has none.
            if self.id.get() == 0 {
                r.last_id += 1;
                self.id.set(r.last_id);
            }
            (self.id.get(), r.get(self.id.get(), key, k))
        });
        if let Some(v) = done {
            return v;
        }
        let n = l.init.len();
        // No borrow of the cache is held while the loop runs: its starting values or turns
        // may read other loops' results.
        if usize::from(l.top) <= SMALL_FRAME {
            let f = l.run_in(s, Frame::<SMALL_FRAME>::new(self));
            RESULTS.with_borrow_mut(|r| r.put(id, key, &f.slots[..n.min(SMALL_FRAME)]));
            f.slot(k)
        } else {
            let f = l.run_in(s, Frame::<LARGE_FRAME>::new(self));
            RESULTS.with_borrow_mut(|r| r.put(id, key, &f.slots[..n.min(LARGE_FRAME)]));
            f.slot(k)
        }
    }
}

/// The results of the loops (base 0) the latest evaluation with loops on this thread ran:
/// which loop, where its values start in `values` and how many.
#[derive(Default)]
struct Results {
    /// Loops (base 0) run on this thread so far.
    runs: u64,
    /// The latest id given to an evaluation on this thread.
    last_id: u64,
    /// The evaluation whose results these are.
    id: u64,
    loops: Vec<(*const HitLoop, usize, usize)>,
    values: Vec<Vec4>,
}

impl Results {
    /// Slot `k` of loop `key` if it ran in evaluation `id` (0 for a slot it does not carry).
    fn get(&self, id: u64, key: *const HitLoop, k: u8) -> Option<Vec4> {
        if self.id != id {
            return None;
        }
        let &(_, at, n) = self.loops.iter().find(|e| e.0 == key)?;
        let k = usize::from(k);
        Some(if k < n { self.values[at + k] } else { Vec4::ZERO })
    }

    /// Keeps loop `key`'s slots after it ran in evaluation `id` (forgetting those of
    /// another evaluation).
    fn put(&mut self, id: u64, key: *const HitLoop, slots: &[Vec4]) {
        if self.id != id {
            self.id = id;
            self.loops.clear();
            self.values.clear();
        }
        self.runs += 1;
        self.loops.push((key, self.values.len(), slots.len()));
        self.values.extend_from_slice(slots);
    }
}

thread_local! {
    static RESULTS: RefCell<Results> = RefCell::new(Results::default());
}

/// How many loops of the hit that no loop is around have run on this thread so far (each
/// runs once per [`Evaluation`]): what tests read to see that a loop ran once.
pub fn loops_run() -> u64 {
    RESULTS.with_borrow(|r| r.runs)
}

/// Where an evaluation reads loop slots: nowhere outside loops ([`Top`]), a [`Frame`]
/// inside one.
pub trait Slots: Copy {
    /// Slot `k`'s value (0 where there is none).
    fn slot(self, k: u8) -> Vec4;
    /// Runs loop `l` starting here at the shading point `s` (or reads its results, for a
    /// loop no loop is around that already ran): its slot `k` after it.
    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4;
}

/// No loop around: no slots; the evaluation the loops started here run once in.
#[derive(Clone, Copy, Debug)]
pub struct Top<'a>(pub &'a Evaluation);

impl Slots for Top<'_> {
    #[inline]
    fn slot(self, _: u8) -> Vec4 {
        Vec4::ZERO
    }

    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4 {
        if l.base == 0 {
            return self.0.once(l, s, k);
        }
        // Not made by the compiler (a loop inside others reads their slots); run alone.
        if usize::from(l.top) <= SMALL_FRAME {
            l.run_in(s, Frame::<SMALL_FRAME>::new(self.0)).slot(k)
        } else {
            l.run_in(s, Frame::<LARGE_FRAME>::new(self.0)).slot(k)
        }
    }
}

impl<const N: usize> Slots for &Frame<'_, N> {
    #[inline]
    fn slot(self, k: u8) -> Vec4 {
        self.slots.get(usize::from(k)).copied().unwrap_or(Vec4::ZERO)
    }

    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4 {
        if l.base == 0 {
            // A loop no loop is around, read inside another: its own run, once.
            return self.top.once(l, s, k);
        }
        // The loop runs in a copy, so that it does not disturb the turn around it; the
        // steps it took count for the loops around.
        let f = l.run_in(s, self.clone());
        self.steps.set(f.steps.get());
        f.slot(k)
    }
}
