//! The line of every instance read, for naming both lines of an id defined twice: the
//! differences from one instance's line to the next (they never decrease) as LEB128
//! varints, usually one byte an instance.

/// Lines in file order (see the module comment).
#[derive(Clone, Debug, Default)]
pub(super) struct Lines {
    bytes: Vec<u8>,
    /// The last line pushed.
    last: usize,
}

impl Lines {
    /// Append `line` (not before the last one).
    pub fn push(&mut self, line: usize) {
        let mut d = line.saturating_sub(self.last);
        self.last = line;
        loop {
            let b = (d & 0x7F) as u8;
            d >>= 7;
            if d == 0 {
                self.bytes.push(b);
                return;
            }
            self.bytes.push(b | 0x80);
        }
    }
    /// The lines in order.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        let mut at = 0;
        let mut line = 0usize;
        std::iter::from_fn(move || {
            let mut d = 0usize;
            let mut shift = 0;
            loop {
                let b = *self.bytes.get(at)?;
                at += 1;
                d |= usize::from(b & 0x7F).checked_shl(shift).unwrap_or(0);
                shift += 7;
                if b & 0x80 == 0 {
                    break;
                }
            }
            line += d;
            Some(line)
        })
    }
    /// The state to go back to with [`Lines::truncate`].
    pub fn mark(&self) -> (usize, usize) {
        (self.bytes.len(), self.last)
    }
    /// Back to the lines of `mark`.
    pub fn truncate(&mut self, (len, last): (usize, usize)) {
        self.bytes.truncate(len);
        self.last = last;
    }
}
