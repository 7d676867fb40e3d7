//! Progress of long jobs. The library reports through a [`Progress`] its caller chooses: the
//! default is silent (a library prints nothing of its own accord; Python scripts and batch
//! runs over thousands of models stay quiet), and the command line passes
//! [`Progress::stderr`]. The jobs decide *when* to report (after the first second, at most
//! about once a second); the caller decides *where*.

/// Where a job's progress lines go: nowhere (the default) or to a function.
#[derive(Clone, Copy, Debug, Default)]
pub struct Progress(pub Option<fn(&str)>);

fn to_stderr(line: &str) {
    eprintln!("{line}");
}

impl Progress {
    /// Each line to standard error (what the command line passes).
    pub fn stderr() -> Progress {
        Progress(Some(to_stderr))
    }
    /// Report the line `line` makes; it is made only when the progress goes somewhere.
    pub fn say(&self, line: impl FnOnce() -> String) {
        if let Some(f) = self.0 {
            f(&line());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Progress;
    use std::sync::atomic::{AtomicUsize, Ordering};

    static HEARD: AtomicUsize = AtomicUsize::new(0);

    #[test]
    fn silent_by_default_and_heard_when_asked() {
        let made = std::cell::Cell::new(0);
        Progress::default().say(|| {
            made.set(made.get() + 1);
            "x".into()
        });
        assert_eq!(
            made.get(),
            0,
            "a silent progress does not even format its line"
        );
        let p = Progress(Some(|l: &str| {
            HEARD.fetch_add(l.len(), Ordering::SeqCst);
        }));
        p.say(|| "four".into());
        assert_eq!(HEARD.load(Ordering::SeqCst), 4);
    }
}
