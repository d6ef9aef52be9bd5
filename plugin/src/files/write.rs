//! Writing files so that a failed write never leaves a truncated file in place of a good one.
