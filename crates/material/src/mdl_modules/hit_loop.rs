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
//! the most slots any loop of the nest reaches ([`HitLoop::top`]). Endless loops end: the
//! loops one evaluation starts (nested ones included) take at most [`MAX_LOOP_STEPS`]
//! steps together — each turn counts the nodes its condition and body visit — and a loop
//! that reaches that stops where it is, its variables keeping the values of its last turn.

use std::cell::Cell;
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

/// Most steps (expression nodes visited) the per-hit loops started by one evaluation take
/// together: a quarter of what one evaluation may visit ([`MAX_HIT_NODES`]), which counts
/// each loop as this many.
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
    fn run_in<const N: usize>(&self, s: &State, mut f: Frame<N>) -> Frame<N> {
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

/// The slots of the per-hit loops an evaluation is inside (`N` of them), and the steps
/// they took.
#[derive(Clone, Debug)]
pub struct Frame<const N: usize> {
    /// Slot values.
    pub slots: [Vec4; N],
    /// Loop steps taken so far in this evaluation.
    pub steps: Cell<u64>,
}

impl<const N: usize> Frame<N> {
    /// A frame of zero slots that has taken no steps.
    fn new() -> Frame<N> {
        Frame { slots: [Vec4::ZERO; N], steps: Cell::new(0) }
    }
}

/// Where an evaluation reads loop slots: nowhere outside loops ([`NoFrame`], a value of no
/// size, so that evaluations outside loops pass nothing more), a [`Frame`] inside one.
pub trait Slots: Copy {
    /// Slot `k`'s value (0 where there is none).
    fn slot(self, k: u8) -> Vec4;
    /// Runs loop `l` starting here at the shading point `s`: its slot `k` after it.
    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4;
}

/// No loop around: no slots, and each loop started here has its own steps, in a frame as
/// large as its nest needs.
#[derive(Clone, Copy, Debug)]
pub struct NoFrame;

impl Slots for NoFrame {
    #[inline]
    fn slot(self, _: u8) -> Vec4 {
        Vec4::ZERO
    }

    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4 {
        if usize::from(l.top) <= SMALL_FRAME {
            l.run_in(s, Frame::<SMALL_FRAME>::new()).slot(k)
        } else {
            l.run_in(s, Frame::<LARGE_FRAME>::new()).slot(k)
        }
    }
}

impl<const N: usize> Slots for &Frame<N> {
    #[inline]
    fn slot(self, k: u8) -> Vec4 {
        self.slots.get(usize::from(k)).copied().unwrap_or(Vec4::ZERO)
    }

    fn run(self, l: &HitLoop, s: &State, k: u8) -> Vec4 {
        // The loop runs in a copy, so that it does not disturb the turn around it; the
        // steps it took count for the loops around.
        let f = l.run_in(s, self.clone());
        self.steps.set(f.steps.get());
        f.slot(k)
    }
}
