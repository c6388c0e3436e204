use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
struct Counting;
static BYTES: AtomicUsize = AtomicUsize::new(0);
static COUNT: AtomicUsize = AtomicUsize::new(0);
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 { BYTES.fetch_add(l.size(), Ordering::Relaxed); COUNT.fetch_add(1, Ordering::Relaxed); unsafe { System.alloc(l) } }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) { unsafe { System.dealloc(p, l) } }
    unsafe fn realloc(&self, p: *mut u8, l: Layout, n: usize) -> *mut u8 { BYTES.fetch_add(n, Ordering::Relaxed); COUNT.fetch_add(1, Ordering::Relaxed); unsafe { System.realloc(p, l, n) } }
}
#[global_allocator]
static A: Counting = Counting;
#[path = "../../cli/benches/gen.rs"]
mod gen;
#[test]
fn alloc_tmp() {
    let files = gen::project(400);
    let mut interner = automat_base::Interner::new();
    let b0 = BYTES.load(Ordering::Relaxed); let c0 = COUNT.load(Ordering::Relaxed);
    let units: Vec<_> = files.iter().enumerate().map(|(i, (_, t))| automat_syntax::parse(automat_base::FileId(i as u32), t, &mut interner).unit).collect();
    let b1 = BYTES.load(Ordering::Relaxed); let c1 = COUNT.load(Ordering::Relaxed);
    let a = automat_sema::check(&units, &mut interner);
    let b2 = BYTES.load(Ordering::Relaxed); let c2 = COUNT.load(Ordering::Relaxed);
    println!("parse: {} MB in {} allocs; check: {} MB in {} allocs", (b1-b0)/1000000, c1-c0, (b2-b1)/1000000, c2-c1);
    drop(a);
}
