//! Native model format.
