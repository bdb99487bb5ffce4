//! Reused buffers for the per-span work of the strategies: a vector handed back after use
//! keeps its heap block for the next span or curve on the same thread, so a batch does not
//! pay one allocation and one free per buffer, span and coordinate (the per-span Bernstein
//! forms, `enclose::newton::bernstein::SpanPoly`, take four each; the Newton engine's span
//! list and scratch vectors, eight per curve; the tight evaluator's per-span slots, one per
//! curve). Only capacity is shared: a vector is emptied when it is given back and a taken one
//! is always empty, so no value of one use can reach another.

use std::cell::RefCell;

/// The most vectors of one element type kept per thread (a curve needs a handful at a time;
/// beyond that, a returned vector is freed as usual).
const KEEP: usize = 16;

/// The largest capacity kept (elements): a vector of a rare high-degree span that is larger
/// is freed, so the pool stays small (at most 16 x 1,024 elements per type and thread, under
/// 0.5 MB for the largest element type; the usual degrees need a few dozen elements).
const KEEP_CAPACITY: usize = 1024;

/// Element types with a per-thread pool of vectors.
pub(crate) trait Pooled: 'static {
    /// Runs `f` with this thread's pool of the type.
    fn with_pool<R>(f: impl FnOnce(&RefCell<Vec<Vec<Self>>>) -> R) -> R;
}

macro_rules! pooled {
    ($($t:ty => $name:ident),*) => {
        thread_local! {
            $(static $name: std::cell::RefCell<Vec<Vec<$t>>> = const { std::cell::RefCell::new(Vec::new()) };)*
        }
        $(impl $crate::num::pool::Pooled for $t {
            fn with_pool<R>(f: impl FnOnce(&std::cell::RefCell<Vec<Vec<Self>>>) -> R) -> R {
                $name.with(f)
            }
        })*
    };
}

pub(crate) use pooled;

pooled!(
    crate::num::Mr => MR_POOL,
    crate::num::Ddi => DDI_POOL,
    inari::Interval => INTERVAL_POOL,
    (f64, f64) => PAIR_POOL,
    (f64, f64, u32) => GAP_POOL,
    (usize, f64, f64) => SPAN_POOL,
    usize => INDEX_POOL,
    bool => FLAG_POOL
);

/// An empty vector with room for at least `cap` elements, from this thread's pool where it
/// has one.
pub(crate) fn take<T: Pooled>(cap: usize) -> Vec<T> {
    let v = T::with_pool(|p| p.try_borrow_mut().ok().and_then(|mut p| p.pop()));
    match v {
        Some(mut v) => {
            v.clear();
            v.reserve(cap);
            v
        }
        None => Vec::with_capacity(cap),
    }
}

/// Hands `v` back to this thread's pool, its values dropped here (nothing to do for `Copy`
/// elements), or frees it where the pool is full or `v` is large or has no heap block.
pub(crate) fn give<T: Pooled>(mut v: Vec<T>) {
    if v.capacity() == 0 || v.capacity() > KEEP_CAPACITY {
        return;
    }
    v.clear();
    T::with_pool(|p| {
        if let Ok(mut p) = p.try_borrow_mut() {
            if p.len() < KEEP {
                p.push(v);
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Mr, Scalar};

    /// A value that counts its live copies (through the `Rc`): not `Copy`, with a destructor.
    struct Tracked {
        _live: std::rc::Rc<()>,
    }
    pooled!(Tracked => TRACKED_POOL);

    /// A vector of values with destructors given back drops them at once (nothing of one use
    /// stays alive in the pool), and its block is reused empty.
    #[test]
    fn a_given_vector_drops_its_values() {
        let live = std::rc::Rc::new(());
        let mut v: Vec<Tracked> = take(4);
        v.extend((0..3).map(|_| Tracked {
            _live: live.clone(),
        }));
        assert_eq!(std::rc::Rc::strong_count(&live), 4);
        let ptr = v.as_ptr();
        give(v);
        assert_eq!(
            std::rc::Rc::strong_count(&live),
            1,
            "dropped when given back"
        );
        let w: Vec<Tracked> = take(2);
        assert!(w.is_empty());
        assert_eq!(w.as_ptr(), ptr);
    }

    #[test]
    fn a_taken_vector_is_empty_and_reuses_a_given_block() {
        let mut v: Vec<Mr> = take(8);
        assert!(v.is_empty() && v.capacity() >= 8);
        v.extend([Mr::from_f64(1.0), Mr::from_f64(2.0)]);
        let ptr = v.as_ptr();
        give(v);
        let w: Vec<Mr> = take(4);
        assert!(w.is_empty(), "no value of one use reaches the next");
        assert_eq!(w.as_ptr(), ptr, "the block given back is the one taken");
        assert!(w.capacity() >= 8);
        // a large vector is not kept
        let big: Vec<Mr> = Vec::with_capacity(KEEP_CAPACITY + 1);
        give(big);
        let x: Vec<Mr> = take(1);
        assert!(x.capacity() < KEEP_CAPACITY + 1);
    }
}
