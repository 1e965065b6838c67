//! A thread-local value set for the length of a call and restored after it (also when the
//! call unwinds): the job's cancel token and progress receiver.

use std::cell::RefCell;
use std::thread::LocalKey;

/// Runs `f` with `key` holding `value` (None: as it is); the previous value is restored
/// afterwards.
pub fn with_value<T: Clone + 'static, R>(
    key: &'static LocalKey<RefCell<Option<T>>>,
    value: Option<&T>,
    f: impl FnOnce() -> R,
) -> R {
    let Some(value) = value else {
        return f();
    };
    let before = key.with(|k| k.replace(Some(value.clone())));
    struct Restore<T: 'static>(&'static LocalKey<RefCell<Option<T>>>, Option<T>);
    impl<T: 'static> Drop for Restore<T> {
        fn drop(&mut self) {
            let before = self.1.take();
            self.0.with(|k| *k.borrow_mut() = before);
        }
    }
    let _restore = Restore(key, before);
    f()
}

/// The value `key` holds on this thread, if any (to hand on to worker threads).
pub fn current<T: Clone + 'static>(key: &'static LocalKey<RefCell<Option<T>>>) -> Option<T> {
    key.with(|k| k.borrow().clone())
}
