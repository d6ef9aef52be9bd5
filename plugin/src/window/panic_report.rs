//! Reporting panics in a windowed app once: the message of a caught panic, and a panic hook
//! that prints each message and place only the first time.

use std::sync::Arc;

/// While it lives, a panic prints (through the hook there was before) only the first time its
/// message and place are seen: a system that panics every frame is reported once, as its
/// error would be.
pub(crate) struct OncePanicHook {
    previous: Arc<PanicHook>,
}

type PanicHook = dyn Fn(&std::panic::PanicHookInfo<'_>) + Send + Sync + 'static;

impl OncePanicHook {
    pub(crate) fn install() -> Self {
        let previous: Arc<PanicHook> = Arc::from(std::panic::take_hook());
        let seen = std::sync::Mutex::new(std::collections::HashSet::new());
        let print = Arc::clone(&previous);
        std::panic::set_hook(Box::new(move |info| {
            let first = seen
                .lock()
                .map_or(true, |mut seen| seen.insert(info.to_string()));
            if first {
                print(info);
            }
        }));
        Self { previous }
    }
}

impl Drop for OncePanicHook {
    fn drop(&mut self) {
        let previous = Arc::clone(&self.previous);
        std::panic::set_hook(Box::new(move |info| previous(info)));
    }
}

/// The message of a caught panic (`catch_unwind`'s payload): its text, or "(no message)".
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(text) = payload.downcast_ref::<&str>() {
        (*text).to_owned()
    } else if let Some(text) = payload.downcast_ref::<String>() {
        text.clone()
    } else {
        "(no message)".to_owned()
    }
}
