//! The two-phase Couette Stokes benchmark (004 §5.1).
