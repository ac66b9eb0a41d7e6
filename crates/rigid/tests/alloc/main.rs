//! The allocation tests: a test binary of its own because it installs a counting
//! `#[global_allocator]` (one per binary), which would count the other integration tests'
//! allocations too.
//!
//! The counter is per thread: each test counts the allocations of the thread it runs on, so the
//! two tests of this binary (and the test harness, which prints from its own thread) can run in
//! parallel without disturbing each other. Everything measured runs on the calling thread (no
//! batch entry point, no rayon).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

#[path = "../it/common/mod.rs"]
mod common;

mod body_no_alloc;
mod constraints_no_alloc;
mod no_alloc;

struct Counting;

thread_local! {
    /// Allocations (and reallocations) made by this thread.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by this thread so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

/// Allocations made by this thread while `f` runs.
fn allocations_in(f: impl FnOnce()) -> usize {
    let before = allocations();
    f();
    allocations() - before
}
